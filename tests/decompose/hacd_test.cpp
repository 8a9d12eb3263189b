// HACD's decomposition (src/graspcd/decompose/hacd.h), CGAL's measures of it
// (src/graspcd/exact/hausdorff.h) and the pieces of decompose --simplify (CGAL's edge collapse,
// src/graspcd/exact/simplify.h; the nearest face, src/graspcd/exact/surface_distance.h) on small
// closed meshes.
#include "graspcd/decompose/hacd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "graspcd/exact/hausdorff.h"
#include "graspcd/exact/simplify.h"
#include "graspcd/exact/surface_distance.h"
#include "graspcd/support/meshes.h"

namespace graspcd::decompose {
namespace {

using testing::make_box_mesh;
using testing::make_torus;
using testing::make_u_mesh;

// Convex and outward: every vertex of the piece lies on the inner side of every face's plane, to
// within `tol` metres (the hull's rounding), and the hull encloses a volume.
void expect_convex_piece(const TriangleMesh& hull, double tol) {
  ASSERT_GE(hull.vertices.size(), 4u);
  ASSERT_GE(hull.faces.size(), 4u);
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const Triangle t = hull.triangle(f);
    const Vec3 n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    if (n.norm() == 0) continue;  // a zero-area face has no plane to check
    const Vec3 unit = n.normalized();
    for (const Vec3& v : hull.vertices) {
      EXPECT_LE(unit.dot(v - t.v[0]), tol) << "face " << f << " sees a vertex outside its plane";
    }
  }
  EXPECT_GT(exact::closed_mesh_volume(hull), 0.0);
}

Vec3 lower(const TriangleMesh& m) {
  Vec3 lo = m.vertices.front();
  for (const Vec3& v : m.vertices) lo = lo.cwiseMin(v);
  return lo;
}
Vec3 upper(const TriangleMesh& m) {
  Vec3 hi = m.vertices.front();
  for (const Vec3& v : m.vertices) hi = hi.cwiseMax(v);
  return hi;
}

// A U (non-convex, closed): at most N convex pieces, each inside the U's bounding box (HACD's
// hull points are the mesh's own vertices, moved to its frame and back), and the input's scale
// and position kept.
TEST(Hacd, UShapeGivesAtMostNConvexPiecesInPlace) {
  TriangleMesh u = make_u_mesh(0.06, 0.05, 0.01, 0.02);
  for (Vec3& v : u.vertices) v += Vec3(0.5, -0.25, 1.0);  // away from the origin: no hidden shift
  const Vec3 lo = lower(u), hi = upper(u);
  const double tol = 1e-9 * (hi - lo).norm();
  for (const std::size_t n : {1u, 2u, 3u, 8u}) {
    HacdOptions options;
    options.max_pieces = n;
    const Decomposition d = hacd_decompose(u, options);
    EXPECT_GE(d.pieces.size(), 1u);
    EXPECT_LE(d.pieces.size(), n);
    for (const ConvexPiece& p : d.pieces) {
      expect_convex_piece(p.hull, tol);
      EXPECT_TRUE((lower(p.hull).array() >= (lo.array() - tol)).all());
      EXPECT_TRUE((upper(p.hull).array() <= (hi.array() + tol)).all());
    }
  }
}

// One piece of a U is its hull, which fills the notch: the Hausdorff distance from the pieces to
// the U's surface must then see the notch (at least a third of its depth, 0.04 m), and three
// pieces must do better than one.
TEST(Hacd, MorePiecesFollowTheSurfaceCloser) {
  const TriangleMesh u = make_u_mesh(0.06, 0.05, 0.01, 0.02);
  const auto distance = [&](std::size_t n) {
    HacdOptions options;
    options.max_pieces = n;
    std::vector<TriangleMesh> hulls;
    for (const ConvexPiece& p : hacd_decompose(u, options).pieces) hulls.push_back(p.hull);
    return exact::one_sided_hausdorff(hulls, u, 1e-5).distance;
  };
  const double one = distance(1);
  const double three = distance(3);
  EXPECT_GT(one, 0.01);
  EXPECT_LT(three, one);
}

// Two boxes 1 m apart (far beyond HACD's connection distance): never merged, so one piece each
// even when one piece is asked for.
TEST(Hacd, EveryComponentGivesAPiece) {
  TriangleMesh two = make_box_mesh(0.01, 0.02, 0.03);
  const TriangleMesh second = make_box_mesh(0.01, 0.02, 0.03);
  const auto offset = static_cast<std::int32_t>(two.vertices.size());
  for (const Vec3& v : second.vertices) two.vertices.push_back(v + Vec3(1, 0, 0));
  for (const auto& f : second.faces)
    two.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  HacdOptions options;
  options.max_pieces = 1;
  const Decomposition d = hacd_decompose(two, options);
  ASSERT_EQ(d.pieces.size(), 2u);
  const double x0 = lower(d.pieces[0].hull).x(), x1 = lower(d.pieces[1].hull).x();
  EXPECT_NEAR(std::min(x0, x1), -0.01, 1e-12);
  EXPECT_NEAR(std::max(x0, x1), 0.99, 1e-12);
}

// CGAL's measures on a case with a known answer: a cube of half-side 0.1 against one of 0.11
// about the same centre. From the outer surface, the farthest point from the inner surface is a
// corner, sqrt(3) * 0.01 away; from the inner one, a face centre 0.01 from the outer surface.
TEST(Hausdorff, NestedCubesMatchTheGeometry) {
  const TriangleMesh inner = make_box_mesh(0.1, 0.1, 0.1);
  const TriangleMesh outer = make_box_mesh(0.11, 0.11, 0.11);
  const double bound = 1e-6;
  const exact::BoundedHausdorff out_in = exact::one_sided_hausdorff({outer}, inner, bound);
  EXPECT_NEAR(out_in.distance, std::sqrt(3.0) * 0.01, bound);
  EXPECT_EQ(out_in.error_bound, bound);
  const exact::BoundedHausdorff in_out = exact::one_sided_hausdorff({inner}, outer, bound);
  EXPECT_NEAR(in_out.distance, 0.01, bound);
  EXPECT_NEAR(exact::closed_mesh_volume(inner), 0.2 * 0.2 * 0.2, 1e-15);
  EXPECT_NEAR(exact::closed_mesh_volume(outer), 0.22 * 0.22 * 0.22, 1e-15);
}

TEST(Hausdorff, AnOpenMeshHasNoVolume) {
  TriangleMesh open = make_box_mesh(0.1, 0.1, 0.1);
  open.faces.pop_back();
  EXPECT_THROW(exact::closed_mesh_volume(open), std::invalid_argument);
}

// CGAL's edge collapse on a torus of 2,304 faces: at most F faces, still closed, its volume kept
// (Lindstrom-Turk's placement preserves volume); a mesh of at most F faces keeps its faces.
TEST(Simplify, ATorusKeepsAtMostFFacesClosedAndItsVolume) {
  const TriangleMesh torus = make_torus(0.05, 0.02, 48, 24);
  const double volume = exact::closed_mesh_volume(torus);
  const TriangleMesh coarse = exact::simplify_edge_collapse(torus, 300);
  EXPECT_LE(coarse.faces.size(), 300u);
  EXPECT_GE(coarse.faces.size(), 250u);  // stopped at F, not far below it
  EXPECT_NEAR(exact::closed_mesh_volume(coarse), volume, 0.02 * volume);
  EXPECT_EQ(exact::simplify_edge_collapse(torus, 2304).faces.size(), torus.faces.size());
  EXPECT_THROW(exact::simplify_edge_collapse(torus, 0), std::invalid_argument);
}

// The nearest face is a face at the surface's distance from the point: points inside, outside
// and on the far side of a torus.
TEST(SurfaceDistance, NearestFaceIsAtTheSurfacesDistance) {
  const TriangleMesh torus = make_torus(0.05, 0.02, 24, 12);
  const exact::SurfaceDistance surface(torus);
  for (const Vec3& p : {Vec3(0.05, 0, 0), Vec3(0.08, 0.01, 0.005), Vec3(0, 0, 0.01),
                        Vec3(-0.03, -0.04, -0.03), Vec3(0.001, 0.07, 0.0)}) {
    const std::size_t f = surface.nearest_face(p);
    ASSERT_LT(f, torus.faces.size());
    TriangleMesh one;
    const Triangle t = torus.triangle(f);
    one.vertices = {t.v[0], t.v[1], t.v[2]};
    one.faces = {{0, 1, 2}};
    EXPECT_NEAR(exact::SurfaceDistance(one).distance(p), surface.distance(p), 1e-12);
  }
}

// decompose --simplify's pieces on a torus: HACD partitions the decimated copy, every face of the
// torus joins the cluster of its nearest decimated face, and the pieces (hulls of the torus's own
// vertices) hold every vertex of the torus: none lies outside all of them.
TEST(Simplify, PiecesOfATransferredPartitionHoldEveryOriginalVertex) {
  const TriangleMesh torus = make_torus(0.05, 0.02, 48, 24);
  const TriangleMesh coarse = exact::simplify_edge_collapse(torus, 200);
  HacdOptions options;
  options.max_pieces = 8;
  const Partition on_coarse = hacd_partition(coarse, options);
  ASSERT_EQ(on_coarse.cluster_of_face.size(), coarse.faces.size());
  const exact::SurfaceDistance nearest(coarse);
  Partition on_torus;
  on_torus.clusters = on_coarse.clusters;
  for (std::size_t f = 0; f < torus.faces.size(); ++f) {
    const Triangle t = torus.triangle(f);
    on_torus.cluster_of_face.push_back(
        on_coarse.cluster_of_face[nearest.nearest_face((t.v[0] + t.v[1] + t.v[2]) / 3.0)]);
  }
  const Decomposition d = pieces_of_partition(torus, on_torus);
  ASSERT_GE(d.pieces.size(), 2u);
  EXPECT_LE(d.pieces.size(), 8u);
  const double tol = 1e-12;
  for (const ConvexPiece& p : d.pieces) expect_convex_piece(p.hull, tol);
  // The torus's vertices outside every piece of `pieces`.
  const auto outside_all = [&](const std::vector<ConvexPiece>& pieces) {
    std::size_t outside = 0;
    for (const Vec3& v : torus.vertices) {
      bool inside_some = false;
      for (const ConvexPiece& p : pieces) {
        bool inside = true;
        for (std::size_t f = 0; f < p.hull.faces.size() && inside; ++f) {
          const Triangle t = p.hull.triangle(f);
          const Vec3 n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
          inside = n.norm() == 0 || n.normalized().dot(v - t.v[0]) <= tol;
        }
        inside_some = inside_some || inside;
      }
      if (!inside_some) ++outside;
    }
    return outside;
  };
  EXPECT_EQ(outside_all(d.pieces), 0u);
  // The hulls of the decimated copy's own clusters would not hold them: the check can fail.
  EXPECT_GT(outside_all(pieces_of_partition(coarse, on_coarse).pieces), 0u);
}

}  // namespace
}  // namespace graspcd::decompose
