// Containment (src/graspcd/core/containment.h): closedness after welding, the exact point-in-solid
// query against CGAL's Side_of_triangle_mesh (src/graspcd/exact) on points inside, outside, exactly
// on faces, edges and vertices, and on rays through edges and vertices, and the mesh-in-mesh check.
#include "graspcd/core/containment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "graspcd/core/tree_query.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/random_geometry.h"
#include "helpers/real_models.h"
#include "helpers/test_scale.h"

namespace graspcd {
namespace {

using testing::Rng;
using testing::scaled;
using testing::uniform;
using testing::uniform01;

// ---- Meshes -----------------------------------------------------------------------------------

// The boundary of a union of voxels: cell (i, j, k) is the box origin + [i, i+1] x [j, j+1] x
// [k, k+1] scaled by `cell` per axis. Every face between a filled and an empty cell becomes two
// triangles split along the same diagonal, outward, vertices shared by lattice position. With
// integer (or dyadic) origin and cell sizes every coordinate is exact, so points on faces, edges
// and vertices and rays through them are exact too.
struct Voxel {
  int i, j, k;
  friend bool operator<(const Voxel& a, const Voxel& b) {
    return std::tie(a.i, a.j, a.k) < std::tie(b.i, b.j, b.k);
  }
};

TriangleMesh voxel_mesh(const std::vector<Voxel>& voxels, const Vec3& origin = Vec3::Zero(),
                        const Vec3& cell = Vec3::Ones()) {
  TriangleMesh m;
  std::map<std::array<int, 3>, std::int32_t> index;
  const auto vertex = [&](std::array<int, 3> g) {
    const auto [it, added] = index.emplace(g, static_cast<std::int32_t>(m.vertices.size()));
    if (added) {
      m.vertices.emplace_back(origin[0] + g[0] * cell[0], origin[1] + g[1] * cell[1],
                              origin[2] + g[2] * cell[2]);
    }
    return it->second;
  };
  const std::vector<Voxel> sorted = [&] {
    std::vector<Voxel> s = voxels;
    std::sort(s.begin(), s.end());
    return s;
  }();
  const auto filled = [&](std::array<int, 3> g) {
    return std::binary_search(sorted.begin(), sorted.end(), Voxel{g[0], g[1], g[2]});
  };
  for (const Voxel& vx : sorted) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        std::array<int, 3> n{vx.i, vx.j, vx.k};
        n[axis] += side ? 1 : -1;
        if (filled(n)) continue;
        // The quad in the plane x_axis = cell + side, corners counter-clockwise in the cyclic
        // (u, v) = (axis + 1, axis + 2) for the +axis side (normal e_u x e_v = e_axis).
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        std::array<std::int32_t, 4> q{};
        const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
        for (int c = 0; c < 4; ++c) {
          std::array<int, 3> g{vx.i, vx.j, vx.k};
          g[axis] += side;
          g[u] += du[c];
          g[v] += dv[c];
          q[c] = vertex(g);
        }
        if (side) {
          m.faces.push_back({q[0], q[1], q[2]});
          m.faces.push_back({q[0], q[2], q[3]});
        } else {
          m.faces.push_back({q[0], q[2], q[1]});
          m.faces.push_back({q[0], q[3], q[2]});
        }
      }
    }
  }
  return m;
}

// The box [lo, hi] as 12 triangles.
TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  return voxel_mesh({{0, 0, 0}}, lo, hi - lo);
}

// A U-shaped channel (non-convex): 3 x 3 x 2 cells minus the column x = 1, y >= 1.
TriangleMesh u_mesh() {
  std::vector<Voxel> v;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 2; ++k)
        if (!(i == 1 && j >= 1)) v.push_back({i, j, k});
  return voxel_mesh(v);
}

// A square ring (genus 1): 3 x 3 x 1 cells minus the centre.
TriangleMesh ring_mesh() {
  std::vector<Voxel> v;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!(i == 1 && j == 1)) v.push_back({i, j, 0});
  return voxel_mesh(v);
}

TriangleMesh without_face(TriangleMesh m, std::size_t face) {
  m.faces.erase(m.faces.begin() + static_cast<std::ptrdiff_t>(face));
  return m;
}

TriangleMesh merged(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const auto offset = static_cast<std::int32_t>(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) m.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  return m;
}

TriangleMesh flipped(TriangleMesh m) {
  for (auto& f : m.faces) std::swap(f[1], f[2]);
  return m;
}

// ---- Closedness -------------------------------------------------------------------------------

TEST(Closedness, ClosedBoxSphereTorusAndVoxelShapes) {
  const Closedness box = closedness(box_mesh(Vec3(-1, -2, -3), Vec3(1, 2, 3)));
  EXPECT_TRUE(box.closed()) << box.describe();
  EXPECT_EQ(box.faces, 12u);
  EXPECT_EQ(box.vertices, 8u);
  EXPECT_EQ(box.edges, 18u);
  EXPECT_EQ(box.component_faces, std::vector<std::int32_t>{0});

  for (const TriangleMesh& m : {testing::make_uv_sphere(0.02, 12, 16),
                                testing::make_torus(0.04, 0.012, 24, 12), u_mesh(), ring_mesh()}) {
    const Closedness c = closedness(m);
    EXPECT_TRUE(c.closed()) << c.describe();
    // Euler: 3F = 2E on a closed mesh.
    EXPECT_EQ(3 * c.faces, 2 * c.edges);
    EXPECT_EQ(c.component_faces.size(), 1u);
  }
  // Genus from Euler's formula: the torus and the ring have V - E + F = 0.
  for (const TriangleMesh& m : {testing::make_torus(0.04, 0.012, 24, 12), ring_mesh()}) {
    const Closedness c = closedness(m);
    EXPECT_EQ(
        static_cast<long>(c.vertices) - static_cast<long>(c.edges) + static_cast<long>(c.faces), 0);
  }
}

// Closedness welds exactly equal vertices: the same box as a soup (three fresh vertices per face,
// as MuJoCo's OBJ loader gives) and as the tree's triangles is closed too.
TEST(Closedness, WeldsExactlyEqualVertices) {
  const TriangleMesh box = box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  const Closedness soup = closedness(posed_triangles(box, Pose{}));
  EXPECT_TRUE(soup.closed()) << soup.describe();
  EXPECT_EQ(soup.vertices, 8u);
  const ObbTree tree = ObbTree::build(box);
  EXPECT_TRUE(closedness(tree).closed());
  // -0.0 and 0.0 are the same coordinate.
  TriangleMesh signed_zero = box_mesh(Vec3(-1, 0, -1), Vec3(1, 1, 1));
  for (Vec3& v : signed_zero.vertices) {
    if (v[1] == 0.0 && v[0] > 0) v[1] = -0.0;
  }
  EXPECT_TRUE(closedness(posed_triangles(signed_zero, Pose{})).closed());
  // A vertex moved by one ulp no longer welds: the mesh opens.
  TriangleMesh nudged = box;
  std::vector<Triangle> soup_nudged = posed_triangles(nudged, Pose{});
  soup_nudged[0].v[0][0] = std::nextafter(soup_nudged[0].v[0][0], 10.0);
  const Closedness n = closedness(soup_nudged);
  EXPECT_FALSE(n.closed());
  EXPECT_EQ(n.boundary_edges, 4u) << n.describe();
}

TEST(Closedness, HoleNonManifoldAndMisorientedAreReported) {
  // A hole: one triangle of the sphere removed leaves its three edges on the boundary.
  const TriangleMesh sphere = testing::make_uv_sphere(0.02, 12, 16);
  const Closedness hole = closedness(without_face(sphere, 40));
  EXPECT_FALSE(hole.closed());
  EXPECT_EQ(hole.boundary_edges, 3u);
  EXPECT_EQ(hole.non_manifold_edges, 0u);
  EXPECT_NE(hole.describe().find("3 boundary edges"), std::string::npos) << hole.describe();
  // A box without one side (two triangles): the side's four edges are on the boundary.
  const TriangleMesh box = box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  const Closedness open_box = closedness(without_face(without_face(box, 0), 0));
  EXPECT_EQ(open_box.boundary_edges, 4u) << open_box.describe();

  // Two cubes sharing only an edge: that edge is used by four faces.
  const Closedness edge_touch = closedness(voxel_mesh({{0, 0, 0}, {1, 1, 0}}));
  EXPECT_FALSE(edge_touch.closed());
  EXPECT_EQ(edge_touch.non_manifold_edges, 1u) << edge_touch.describe();
  EXPECT_EQ(edge_touch.boundary_edges, 0u);
  EXPECT_NE(edge_touch.describe().find("1 non-manifold edge"), std::string::npos);
  // Three triangles on one edge (a "book"): one non-manifold edge, six boundary edges.
  TriangleMesh book;
  book.vertices = {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, -1, 0)};
  book.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const Closedness b = closedness(book);
  EXPECT_EQ(b.non_manifold_edges, 1u);
  EXPECT_EQ(b.boundary_edges, 6u);

  // One face flipped: its three edges are traversed twice in the same direction.
  TriangleMesh flip = box;
  std::swap(flip.faces[3][1], flip.faces[3][2]);
  const Closedness f = closedness(flip);
  EXPECT_FALSE(f.closed());
  EXPECT_EQ(f.misoriented_edges, 3u) << f.describe();
  // Every face flipped: consistently inward is still closed.
  EXPECT_TRUE(closedness(flipped(box)).closed());

  // A collapsed face (two equal vertices) has no edges and does not open the mesh.
  TriangleMesh collapsed = box;
  collapsed.faces.push_back({0, 0, 1});
  const Closedness c = closedness(collapsed);
  EXPECT_TRUE(c.closed()) << c.describe();
  EXPECT_EQ(c.collapsed_faces, 1u);

  // Nothing to close.
  EXPECT_FALSE(closedness(TriangleMesh{}).closed());
  EXPECT_EQ(closedness(TriangleMesh{}).describe(), "not closed: no faces (0 faces)");

  // Two disjoint boxes: closed, two components, seeds are each box's first face.
  const Closedness two = closedness(merged(box, box_mesh(Vec3(3, 3, 3), Vec3(4, 4, 4))));
  EXPECT_TRUE(two.closed());
  EXPECT_EQ(two.component_faces, (std::vector<std::int32_t>{0, 12}));
}

// ---- Point queries against CGAL ---------------------------------------------------------------

struct Tally {
  int points = 0, inside = 0, on_surface = 0, outside = 0;
  void add(PointSide s) {
    ++points;
    inside += s == PointSide::kInside;
    on_surface += s == PointSide::kOnSurface;
    outside += s == PointSide::kOutside;
  }
};

PointSide from_cgal(int side) {
  return side > 0 ? PointSide::kInside : side == 0 ? PointSide::kOnSurface : PointSide::kOutside;
}

// Every point: the tree's answer with the automatic ray must equal CGAL's; the tree with one of the
// six fixed rays (cycling) and the brute force with another must equal it too (the perturbation
// makes the answer independent of the ray). Fatal on the first disagreement.
void check_points(const TriangleMesh& mesh, const Pose& pose, const std::vector<Vec3>& points,
                  Tally& tally, PointQueryStats* stats = nullptr, bool brute_force = true) {
  const ObbTree tree = ObbTree::build(mesh);
  const std::vector<Triangle> placed = posed_triangles(mesh, pose);
  const std::vector<int> truth = exact::side_of_closed_mesh(placed, points);
  ASSERT_EQ(truth.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    const PointSide expected = from_cgal(truth[i]);
    const PointSide side = point_side(tree, pose, p, RayDirection{}, stats);
    ASSERT_EQ(side, expected) << "point " << i << " (" << p.transpose() << "): core says "
                              << point_side_name(side) << ", CGAL " << point_side_name(expected);
    const RayDirection fixed{static_cast<int>(i % 3), (i / 3) % 2 ? -1 : 1};
    ASSERT_EQ(point_side(tree, pose, p, fixed), expected)
        << "point " << i << " ray axis " << fixed.axis << " sign " << fixed.sign;
    if (brute_force) {
      const RayDirection other{static_cast<int>((i + 1) % 3), (i / 6) % 2 ? -1 : 1};
      ASSERT_EQ(point_side(placed, p, other), expected) << "brute force, point " << i;
    }
    ASSERT_EQ(point_inside(tree, pose, p), expected != PointSide::kOutside);
    tally.add(expected);
  }
}

// Points around a placed mesh: uniform in its bounding box grown by 20 %, its vertices exactly,
// rounded points on edges and faces (CGAL decides which side they fell on), points pushed off a
// face by a few ulps, and points sharing two coordinates with a vertex, so that the ray along the
// third axis passes exactly through that vertex.
std::vector<Vec3> probe_points(const std::vector<Triangle>& tris, Rng& rng, int n) {
  Vec3 lo = tris[0].v[0], hi = lo;
  for (const Triangle& t : tris) {
    for (const Vec3& v : t.v) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  }
  const Vec3 pad = 0.2 * (hi - lo);
  lo -= pad;
  hi += pad;
  const auto any_triangle = [&]() -> const Triangle& {
    return tris[static_cast<std::size_t>(
        testing::uniform_int<std::size_t>(rng, 0, tris.size() - 1))];
  };
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    pts.push_back(testing::uniform_in_box(rng, lo, hi));
  }
  for (int i = 0; i < n / 4; ++i) {
    const Triangle& t = any_triangle();
    const int k = static_cast<int>(testing::uniform_int(rng, 0, 2));
    pts.push_back(t.v[k]);                                                 // a vertex
    pts.push_back(t.v[k] + uniform01(rng) * (t.v[(k + 1) % 3] - t.v[k]));  // on an edge, rounded
    double a = uniform01(rng), b = uniform01(rng);
    if (a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    const Vec3 on_face = t.v[0] + a * (t.v[1] - t.v[0]) + b * (t.v[2] - t.v[0]);
    pts.push_back(on_face);  // on a face, rounded
    const Vec3 normal = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    const double ulps = std::ldexp(1.0, -50) * (hi - lo).norm();
    if (normal.norm() > 0) {
      pts.push_back(on_face + (uniform(rng, -4, 4) * ulps / normal.norm()) * normal);
    }
    Vec3 through = t.v[k];  // the ray along `axis` passes through vertex k
    const int axis = static_cast<int>(testing::uniform_int(rng, 0, 2));
    through[axis] = uniform(rng, lo[axis], hi[axis]);
    pts.push_back(through);
  }
  return pts;
}

// Mean time of point_inside per point over `points` (ns), for the printout only.
double ns_per_query(const ObbTree& tree, const std::vector<Vec3>& points, int& inside) {
  const auto start = std::chrono::steady_clock::now();
  inside = 0;
  for (const Vec3& p : points) inside += point_inside(tree, p);
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start)
             .count() /
         static_cast<double>(points.size());
}

// The lattice points of [lo, hi] with the given step (exact: small dyadic numbers).
std::vector<Vec3> lattice(double lo, double hi, double step) {
  std::vector<Vec3> pts;
  const int n = static_cast<int>(std::lround((hi - lo) / step));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) pts.emplace_back(lo + i * step, lo + j * step, lo + k * step);
  return pts;
}

// The box [-2, 2]^3 on the lattice of step 1/2 over [-3, 3]^3: 2197 points, many exactly on faces,
// on the faces' diagonals (edges), on the box's edges and vertices, and many whose rays along the
// axes run exactly through edges and vertices or along faces. The answer is known from the
// construction; CGAL and the core must both give it, for every ray direction.
TEST(PointSide, BoxLatticeMatchesConstructionAndCgal) {
  const TriangleMesh box = box_mesh(Vec3(-2, -2, -2), Vec3(2, 2, 2));
  const ObbTree tree = ObbTree::build(box);
  const std::vector<Vec3> pts = lattice(-3, 3, 0.5);
  const std::vector<int> cgal = exact::side_of_closed_mesh(posed_triangles(box, Pose{}), pts);
  Tally tally;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double m = pts[i].cwiseAbs().maxCoeff();
    const PointSide known = m < 2    ? PointSide::kInside
                            : m == 2 ? PointSide::kOnSurface
                                     : PointSide::kOutside;
    ASSERT_EQ(from_cgal(cgal[i]), known) << "CGAL at " << pts[i].transpose();
    for (int axis = -1; axis < 3; ++axis) {
      for (int sign : {1, -1}) {
        ASSERT_EQ(point_side(tree, Pose{}, pts[i], RayDirection{axis, sign}), known)
            << pts[i].transpose() << " axis " << axis << " sign " << sign;
        if (axis >= 0) {
          ASSERT_EQ(point_side(posed_triangles(box, Pose{}), pts[i], RayDirection{axis, sign}),
                    known);
        }
      }
    }
    tally.add(known);
  }
  EXPECT_GT(tally.inside, 0);
  EXPECT_GT(tally.on_surface, 0);
  EXPECT_GT(tally.outside, 0);
  std::printf(
      "box lattice: %d points (%d inside, %d on the surface, %d outside), 7 rays each, "
      "core = CGAL = construction\n",
      tally.points, tally.inside, tally.on_surface, tally.outside);
}

// Non-convex and genus-1 voxel shapes on a lattice of step 1/4: points on faces, edges, vertices
// and rays through them everywhere; CGAL is the judge.
TEST(PointSide, VoxelShapesOnLatticeAgreeWithCgal) {
  for (const auto& [name, mesh] :
       {std::pair<const char*, TriangleMesh>{"U channel", u_mesh()}, {"ring", ring_mesh()}}) {
    Tally tally;
    ASSERT_NO_FATAL_FAILURE(check_points(mesh, Pose{}, lattice(-0.5, 3.5, 0.25), tally));
    EXPECT_GT(tally.inside, 0);
    EXPECT_GT(tally.on_surface, 0);
    EXPECT_GT(tally.outside, 0);
    std::printf(
        "%s lattice: %d points (%d inside, %d on the surface, %d outside), all agree with "
        "CGAL\n",
        name, tally.points, tally.inside, tally.on_surface, tally.outside);
  }
}

// Random and adversarial points around generated meshes, in place and placed by random poses
// (the tree's triangles through apply_pose, CGAL on the same doubles).
TEST(PointSide, GeneratedMeshesAgreeWithCgal) {
  Rng rng(17);
  const std::vector<std::pair<const char*, TriangleMesh>> meshes = {
      {"sphere", testing::make_uv_sphere(0.03, 16, 24)},
      {"torus", testing::make_torus(0.04, 0.012, 40, 20)},
      {"U channel", u_mesh()},
      {"two boxes", merged(box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1)),
                           box_mesh(Vec3(0.25, 0.25, 0.25), Vec3(0.75, 0.75, 0.75)))},
  };
  for (const auto& [name, mesh] : meshes) {
    for (int placed = 0; placed < 2; ++placed) {
      Pose pose;
      if (placed) {
        pose.R = testing::random_rotation(rng);
        pose.t = testing::uniform_vec3(rng, -1, 1);
      }
      Tally tally;
      ASSERT_NO_FATAL_FAILURE(check_points(
          mesh, pose, probe_points(posed_triangles(mesh, pose), rng, scaled(1500)), tally));
      EXPECT_GT(tally.inside, tally.points / 20) << name;
      EXPECT_GT(tally.on_surface, 0) << name;
      EXPECT_GT(tally.outside, tally.points / 20) << name;
      std::printf(
          "%s%s: %d points (%d inside, %d on the surface, %d outside), all agree with "
          "CGAL\n",
          name, placed ? " (posed)" : "", tally.points, tally.inside, tally.on_surface,
          tally.outside);
    }
  }
}

// A fine sphere: the query must touch few triangles and nodes (the descent follows the ray), and
// its time per point is printed (not asserted).
TEST(PointSide, LargeMeshQueryIsSublinear) {
  const TriangleMesh sphere = testing::make_uv_sphere(0.05, 80, 128);
  const ObbTree tree = ObbTree::build(sphere);
  ASSERT_GT(sphere.faces.size(), 20000u);
  Rng rng(5);
  const std::vector<Vec3> pts = probe_points(posed_triangles(sphere, Pose{}), rng, scaled(2000));
  Tally tally;
  PointQueryStats stats;
  ASSERT_NO_FATAL_FAILURE(check_points(sphere, Pose{}, pts, tally, &stats, false));
  const double per_query_tris =
      static_cast<double>(stats.triangle_tests) / static_cast<double>(stats.queries);
  const double per_query_nodes =
      static_cast<double>(stats.nodes_visited) / static_cast<double>(stats.queries);
  EXPECT_LT(per_query_tris, static_cast<double>(sphere.faces.size()) / 100);
  EXPECT_LT(per_query_nodes, static_cast<double>(tree.nodes().size()) / 50);
  // Timing: every probe (a third of them on the surface or through vertices, which need the
  // exact arithmetic), and the uniform ones alone (the first scaled(2000) probes).
  int inside = 0;
  const double ns_all = ns_per_query(tree, pts, inside);
  EXPECT_EQ(inside, tally.inside + tally.on_surface);
  const std::vector<Vec3> uniform_pts(pts.begin(), pts.begin() + scaled(2000));
  const double ns_uniform = ns_per_query(tree, uniform_pts, inside);
  std::printf(
      "sphere of %zu faces (%zu nodes, depth %d): %d points agree with CGAL; per query %.1f "
      "nodes, %.2f triangles tested; %.0f ns per query over all points, %.0f ns over uniform "
      "points\n",
      sphere.faces.size(), tree.nodes().size(), tree.depth(), tally.points, per_query_nodes,
      per_query_tris, ns_all, ns_uniform);
}

// Real meshes from ../shared/models, where closed: cube_cup_hi, the mug, and spot (the cow).
TEST(PointSide, RealMeshesAgreeWithCgalWhereClosed) {
  std::string why_not;
  const std::optional<testing::CupAndMug> real = testing::load_cup_and_mug(why_not);
  if (!real) GTEST_SKIP() << why_not;
  std::vector<std::pair<std::string, TriangleMesh>> meshes = {{"cube_cup_hi", real->cup},
                                                              {"mug", real->mug}};
  const std::filesystem::path spot =
      std::filesystem::path(GRASPCD_MODELS_DIR) / "objects/mujoco/spot.obj";
  if (std::filesystem::exists(spot)) meshes.emplace_back("spot", io::load_mesh(spot.string()));
  Rng rng(23);
  int tested = 0;
  std::string skipped;
  for (const auto& [name, mesh] : meshes) {
    const Closedness c = closedness(mesh);
    std::printf("%s: %s\n", name.c_str(), c.describe().c_str());
    if (!c.closed()) {
      skipped += name + " (" + c.describe() + ") ";
      continue;
    }
    const ObbTree tree = ObbTree::build(mesh);
    const std::vector<Vec3> pts = probe_points(posed_triangles(mesh, Pose{}), rng, scaled(2000));
    Tally tally;
    PointQueryStats stats;
    ASSERT_NO_FATAL_FAILURE(check_points(mesh, Pose{}, pts, tally, &stats, false));
    int inside = 0;
    const double ns_all = ns_per_query(tree, pts, inside);
    EXPECT_EQ(inside, tally.inside + tally.on_surface);
    EXPECT_GT(tally.inside, 0) << name;
    const std::vector<Vec3> uniform_pts(pts.begin(), pts.begin() + scaled(2000));
    const double ns_uniform = ns_per_query(tree, uniform_pts, inside);
    std::printf(
        "%s: %d points (%d inside, %d on the surface, %d outside), all agree with CGAL; per "
        "query %.1f nodes, %.2f triangles; %.0f ns per query over all points, %.0f ns over "
        "uniform points\n",
        name.c_str(), tally.points, tally.inside, tally.on_surface, tally.outside,
        static_cast<double>(stats.nodes_visited) / static_cast<double>(stats.queries),
        static_cast<double>(stats.triangle_tests) / static_cast<double>(stats.queries), ns_all,
        ns_uniform);
    ++tested;
  }
  if (tested == 0) GTEST_SKIP() << "no closed real mesh: " << skipped;
  if (!skipped.empty()) std::printf("not closed, skipped: %s\n", skipped.c_str());
}

TEST(PointSide, BadRayThrows) {
  const ObbTree tree = ObbTree::build(box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
  EXPECT_THROW(point_side(tree, Pose{}, Vec3::Zero(), RayDirection{3, 1}), std::invalid_argument);
  EXPECT_THROW(point_side(tree, Pose{}, Vec3::Zero(), RayDirection{0, 0}), std::invalid_argument);
}

// ---- Mesh in mesh -----------------------------------------------------------------------------

struct Operand {
  ObbTree tree;
  Closedness closedness;
  explicit Operand(const TriangleMesh& m)
      : tree(ObbTree::build(m)), closedness(graspcd::closedness(tree)) {}
};

bool surfaces_meet(const Operand& a, const Pose& pose, const Operand& b) {
  SatSeparator sat;
  QueryCounters counters;
  return collide(a.tree, b.tree, pose, QueryMode::kFirstContact, sat, counters).intersect;
}

Pose pose_at(const Vec3& t, const Mat3& R = Mat3::Identity()) {
  Pose p;
  p.R = R;
  p.t = t;
  return p;
}

// B inside, partly out, wholly out, and inside an open A; each with the caller's surface answer
// and with the tree query run by mesh_inside itself, and both directions of mesh_containment.
TEST(MeshInside, SmallBoxInsideBigBox) {
  const Operand big(box_mesh(Vec3(-4, -4, -4), Vec3(4, 4, 4)));
  const Operand small(box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
  Rng rng(3);
  const Mat3 R = testing::random_rotation(rng);
  struct Case {
    const char* what;
    Pose pose;
    bool meet, inside;
  };
  const std::vector<Case> cases = {
      {"inside", pose_at(Vec3(0.5, -0.3, 0.2), R), false, true},
      {"inside, axis-aligned, touching nothing", pose_at(Vec3(2.5, 2.5, 2.5)), false, true},
      {"face on face (touching)", pose_at(Vec3(3, 0, 0)), true, false},
      {"partly out", pose_at(Vec3(3.5, 0, 0), R), true, false},
      {"wholly out", pose_at(Vec3(10, 0, 0), R), false, false},
  };
  for (const Case& c : cases) {
    const bool meet = surfaces_meet(big, c.pose, small);
    ASSERT_EQ(meet, c.meet) << c.what;
    EXPECT_EQ(mesh_inside(big.tree, big.closedness, c.pose, small.tree, small.closedness, meet),
              c.inside)
        << c.what;
    EXPECT_EQ(mesh_inside(big.tree, big.closedness, c.pose, small.tree, small.closedness), c.inside)
        << c.what;
    const MeshContainment m =
        mesh_containment(big.tree, big.closedness, c.pose, small.tree, small.closedness);
    EXPECT_EQ(m.surfaces_intersect, c.meet) << c.what;
    EXPECT_EQ(m.b_inside_a, c.inside) << c.what;
    EXPECT_FALSE(m.a_inside_b) << c.what;
    // The symmetric call: the big box placed in the small one's frame, the small one at the
    // origin: A (small) inside B (big) exactly when the pose above put it inside.
    if (c.pose.R == Mat3::Identity()) {
      const MeshContainment s = mesh_containment(small.tree, small.closedness, pose_at(-c.pose.t),
                                                 big.tree, big.closedness);
      EXPECT_EQ(s.surfaces_intersect, c.meet) << c.what;
      EXPECT_EQ(s.a_inside_b, c.inside) << c.what;
      EXPECT_FALSE(s.b_inside_a) << c.what;
    }
  }

  // An open A (one side removed): its "solid" is undefined, so nothing is inside it, although the
  // small box is where the closed box's inside was.
  const Operand open(without_face(without_face(box_mesh(Vec3(-4, -4, -4), Vec3(4, 4, 4)), 0), 0));
  ASSERT_FALSE(open.closedness.closed());
  const Pose inside = cases[0].pose;
  EXPECT_FALSE(surfaces_meet(open, inside, small));
  EXPECT_FALSE(mesh_inside(open.tree, open.closedness, inside, small.tree, small.closedness));
  EXPECT_FALSE(mesh_containment(open.tree, open.closedness, inside, small.tree, small.closedness)
                   .b_inside_a);
}

// A B of two components, one inside A and one outside: the surfaces do not meet, one vertex of
// the inner component is inside, and still B is not inside A (every component is checked, in
// either order of the components).
TEST(MeshInside, EveryComponentOfBIsChecked) {
  const Operand big(box_mesh(Vec3(-4, -4, -4), Vec3(4, 4, 4)));
  const TriangleMesh in = box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  const TriangleMesh out = box_mesh(Vec3(6, -1, -1), Vec3(8, 1, 1));
  for (const TriangleMesh& two : {merged(in, out), merged(out, in)}) {
    const Operand b(two);
    ASSERT_EQ(b.closedness.component_faces.size(), 2u);
    EXPECT_FALSE(surfaces_meet(big, Pose{}, b));
    EXPECT_FALSE(mesh_inside(big.tree, big.closedness, Pose{}, b.tree, b.closedness));
  }
  const Operand both(merged(in, box_mesh(Vec3(2, 2, 2), Vec3(3, 3, 3))));
  EXPECT_TRUE(mesh_inside(big.tree, big.closedness, Pose{}, both.tree, both.closedness));
}

// Spheres: nested (inside), overlapping (not), and the documented cavity case: A a hollow shell,
// B in its cavity is outside A's solid; B wrapping the cavity within the shell's wall passes
// (its surface is inside A's solid).
TEST(MeshInside, NestedSpheresAndCavity) {
  const Operand outer(testing::make_uv_sphere(0.05, 24, 32));
  const Operand inner(testing::make_uv_sphere(0.02, 12, 16));
  EXPECT_TRUE(mesh_inside(outer.tree, outer.closedness, pose_at(Vec3(0.01, 0, 0.005)), inner.tree,
                          inner.closedness));
  EXPECT_FALSE(mesh_inside(outer.tree, outer.closedness, pose_at(Vec3(0.04, 0, 0)), inner.tree,
                           inner.closedness));
  EXPECT_FALSE(mesh_inside(inner.tree, inner.closedness, Pose{}, outer.tree, outer.closedness));
  const MeshContainment swapped =
      mesh_containment(inner.tree, inner.closedness, Pose{}, outer.tree, outer.closedness);
  EXPECT_TRUE(swapped.a_inside_b);
  EXPECT_FALSE(swapped.b_inside_a);

  const Operand shell(merged(box_mesh(Vec3(-4, -4, -4), Vec3(4, 4, 4)),
                             flipped(box_mesh(Vec3(-2, -2, -2), Vec3(2, 2, 2)))));
  ASSERT_TRUE(shell.closedness.closed());
  EXPECT_FALSE(point_inside(shell.tree, Vec3::Zero()));  // the cavity is outside
  EXPECT_TRUE(point_inside(shell.tree, Vec3(3, 0, 0)));
  const Operand in_cavity(box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
  EXPECT_FALSE(
      mesh_inside(shell.tree, shell.closedness, Pose{}, in_cavity.tree, in_cavity.closedness));
  const Operand wrapping(box_mesh(Vec3(-3, -3, -3), Vec3(3, 3, 3)));
  EXPECT_TRUE(
      mesh_inside(shell.tree, shell.closedness, Pose{}, wrapping.tree, wrapping.closedness));
}

TEST(MeshInside, ClosednessMustComeFromTheTree) {
  const Operand a(box_mesh(Vec3(-4, -4, -4), Vec3(4, 4, 4)));
  const Operand b(testing::make_uv_sphere(0.5, 8, 8));
  EXPECT_THROW(mesh_inside(a.tree, b.closedness, Pose{}, b.tree, b.closedness),
               std::invalid_argument);
  EXPECT_THROW(mesh_inside(a.tree, a.closedness, Pose{}, b.tree, a.closedness, false),
               std::invalid_argument);
}

}  // namespace
}  // namespace graspcd
