// Bullet's GImpact, the second peer (src/graspcd/peer/gimpact_peer.h), on cases whose answer is
// known: the pose convention, margins 0, and agreement with CGAL where the meshes are clearly
// apart or clearly overlapping. GImpact is not exact (its clip method runs in floating point with
// its own thresholds), so touching poses are measured by the benchmark, not asserted here.
#include "graspcd/peer/gimpact_peer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "graspcd/exact/exact.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/random_geometry.h"

namespace graspcd::peer {
namespace {

std::vector<Triangle> posed(const TriangleMesh& m, const Pose& p) {
  std::vector<Triangle> out;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    Triangle t = m.triangle(f);
    for (Vec3& v : t.v) v = apply_pose(p, v);
    out.push_back(t);
  }
  return out;
}

std::vector<Triangle> triangles(const TriangleMesh& m) { return posed(m, Pose{}); }

// Two boxes 2 cm wide: B moved along +x by 1.9 cm overlaps A by 1 mm; by 2.1 cm it is 1 mm
// clear (margins 0: no contact); moved along -x the same. A pose applied to A instead of B, or
// a margin left at GImpact's default 1 cm, would fail one of these.
TEST(GimpactPeer, BoxesOverlapAndClearWithMarginsZero) {
  const TriangleMesh box = testing::make_box_mesh(0.01, 0.01, 0.01);
  const GimpactMesh a(box), b(box);
  EXPECT_EQ(a.triangle_count(), box.faces.size());
  GimpactQuery query;
  for (const double sign : {1.0, -1.0}) {
    Pose p;
    p.t = Vec3(sign * 0.019, 0.002, -0.003);
    const GimpactQueryResult hit = query.collide(a, b, p);
    EXPECT_TRUE(hit.intersect);
    EXPECT_GT(hit.contacts, 0u);
    p.t.x() = sign * 0.021;
    const GimpactQueryResult miss = query.collide(a, b, p);
    EXPECT_FALSE(miss.intersect);
    EXPECT_EQ(miss.contacts, 0u);
  }
}

// Two 3,968-triangle spheres of radius 5 cm at random rotations, their centres 9 cm apart
// (surfaces cross: CGAL says intersect) or 10.5 cm apart (clear by 5 mm: CGAL says not).
// GImpact must agree with CGAL on every one of these clear cases.
TEST(GimpactPeer, AgreesWithCgalAwayFromTouching) {
  const TriangleMesh sphere = testing::make_uv_sphere(0.05, 32, 64);
  const GimpactMesh a(sphere), b(sphere);
  const std::vector<Triangle> ta = triangles(sphere);
  GimpactQuery query;
  testing::Rng rng(20);
  int hits = 0;
  for (int i = 0; i < 16; ++i) {
    Pose p;
    p.R = testing::random_rotation(rng);
    const Vec3 dir = testing::random_unit(rng);
    p.t = (i % 2 == 0 ? 0.09 : 0.105) * dir;
    const bool truth = !exact::mesh_mesh_pairs(ta, posed(sphere, p), true).empty();
    EXPECT_EQ(truth, i % 2 == 0);
    EXPECT_EQ(query.collide(a, b, p).intersect, truth) << "pose " << i;
    hits += truth;
  }
  EXPECT_EQ(hits, 8);
}

}  // namespace
}  // namespace graspcd::peer
