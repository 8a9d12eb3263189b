// The contact of one intersecting triangle pair: face and edge-edge directions, the depth cap,
// the prism clip, and degenerate triangles.
#include "graspcd/core/triangle_contact.h"

#include <gtest/gtest.h>

#include <cmath>

#include "graspcd/core/tritri.h"

namespace graspcd::triangle_contact_test {
namespace {

Triangle tri(Vec3 a, Vec3 b, Vec3 c) { return Triangle{{a, b, c}}; }

// A large floor triangle (normal +z) pierced by a small vertical one dipping 1 cm below it: the
// smaller push is along the floor's normal, 1 cm, and the position is on the segment's midpoint.
TEST(TrianglePairContact, VerticalTrianglePiercingAFloorUsesTheFloorNormal) {
  const Triangle floor = tri({-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  const Triangle blade = tri({-0.1, 0, 0.05}, {0.1, 0, 0.05}, {0, 0, -0.01});
  const TriContact c = triangle_pair_contact(floor, blade, 1.0, Vec3::UnitX());
  EXPECT_NEAR(c.normal.dot(Vec3::UnitZ()), 1.0, 1e-12);
  EXPECT_NEAR(c.depth, 0.01, 1e-12);
  EXPECT_NEAR(c.pos.z(), 0.0, 1e-12);
  EXPECT_NEAR(c.pos.x(), 0.0, 1e-12);
  // Swapped roles: the floor is geom2 now, its outward normal +z points toward geom1, so the
  // normal from geom1 to geom2 is -z.
  const TriContact s = triangle_pair_contact(blade, floor, 1.0, Vec3::UnitX());
  EXPECT_NEAR(s.normal.dot(-Vec3::UnitZ()), 1.0, 1e-12);
  EXPECT_NEAR(s.depth, 0.01, 1e-12);
}

// Two faces crossing along the edges of two solids (a's +y side and b's -x side of two boxes that
// overlap 1 cm in z): neither face normal is the penetration direction; the edge axis z is.
TEST(TrianglePairContact, CrossingSideFacesUseTheEdgeAxis) {
  const Triangle a = tri({-0.04, 0.04, -0.04}, {-0.04, 0.04, 0.04}, {0.04, 0.04, 0.04});   // +y
  const Triangle b = tri({-0.01, -0.03, 0.03}, {-0.01, 0.05, 0.11}, {-0.01, 0.05, 0.03});  // -x
  // The diagonals (a's edge 2, b's edge 0) are not edges of the boxes.
  const TriContact c = triangle_pair_contact(a, b, 1.0, Vec3::UnitX(), 0b011, 0b110);
  EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
  EXPECT_NEAR(c.depth, 0.01, 1e-12);
  // Without the face orientation, the axis a's x edge x b's z edge (a's face normal) would
  // separate the triangles with a 1 cm push along -y, into box a; the sign from the faces
  // rules that out, even with every edge taken as sharp.
  const TriContact all = triangle_pair_contact(a, b, 1.0, Vec3::UnitX());
  EXPECT_NEAR(all.normal.z(), 1.0, 1e-12);
  EXPECT_NEAR(all.depth, 0.01, 1e-12);
}

// Seen on the Robotiq pad against the voxel cup (mjcf/real_robotiq_cup.xml), coordinates as the
// served query had them: a horizontal face of the cup (b) crosses the pad's side face (a, normal
// -x) and grazes the pad's front face (y = -0.004) by 0.09 mm. The edge axis of the pad's z edge
// and the cup's x edge is y, tilted 0.23 degrees, so its dot product with n_a - n_b is 0.004: too
// small for the faces to decide its sign (tol::kContactSignCosine). The smaller side, 0.09 mm
// along -y, is the contact. Had the faces decided, that axis would have measured 10 mm and the
// side face's 1.9 mm along -x would have won: the kicks that let the held cup jitter.
TEST(TrianglePairContact, AnEdgeAxisNearlyInBothFacesTakesTheSmallerSide) {
  const Triangle a =
      tri({-0.011, -0.004, -0.009375}, {-0.011, -0.004, 0.009375}, {-0.011, 0.004, 0.009375});
  const Triangle b =
      tri({-0.009087654, -0.006248175, -0.001437782}, {-0.011701105, -0.003914970, -0.001433941},
          {-0.009097126, -0.003904448, -0.001432941});
  ASSERT_TRUE(tri_tri_intersect(a, b));
  const TriContact c = triangle_pair_contact(a, b, 0.01, Vec3::UnitX(), 0b011, 0b010);
  EXPECT_GT(c.normal.dot(-Vec3::UnitY()), 0.999);
  EXPECT_NEAR(c.depth, 0.088e-3, 0.002e-3);
}

TEST(TrianglePairContact, DepthIsClippedToTheCap) {
  const Triangle floor = tri({-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  const Triangle blade = tri({-0.1, 0, 0.05}, {0.1, 0, 0.05}, {0, 0, -0.2});
  const TriContact c = triangle_pair_contact(floor, blade, 0.003, Vec3::UnitX());
  EXPECT_DOUBLE_EQ(c.depth, 0.003);
}

// Only the part of the blade over the floor triangle counts: a blade whose deep tip lies beyond
// the floor's edge measures the depth inside the floor's prism only.
TEST(TrianglePairContact, DepthIsMeasuredInsideThePrism) {
  const Triangle floor = tri({0, -1, 0}, {1, -1, 0}, {0, 1, 0});  // x >= 0 only
  // Dips to -0.01 at x = 0.05 (inside) and to -0.1 at x = -0.05 (outside the prism).
  const Triangle blade = tri({0.05, 0, -0.01}, {-0.05, 0, -0.1}, {0.0, 0, 0.1});
  const TriContact c = triangle_pair_contact(floor, blade, 1.0, Vec3::UnitX());
  EXPECT_GT(c.depth, 0.0);
  EXPECT_LT(c.depth, 0.06);  // the clipped polygon reaches x = 0 at most: depth <= 0.055
}

// Two crossing segments (zero-area triangles): no face normal, the edge axis is their common
// perpendicular, with no penetration.
TEST(TrianglePairContact, CrossingSegmentsUseTheirCommonPerpendicular) {
  const Triangle a = tri({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  const Triangle b = tri({0.5, -1, 0}, {0.5, 1, 0}, {0.5, 0, 0});
  const TriContact c = triangle_pair_contact(a, b, 1.0, Vec3::UnitY());
  EXPECT_NEAR(std::abs(c.normal.z()), 1.0, 1e-15);
  EXPECT_EQ(c.depth, 0.0);
}

// Overlapping collinear segments: every edge pair is parallel, so the fallback normal is used.
TEST(TrianglePairContact, CollinearSegmentsUseTheFallbackNormal) {
  const Triangle a = tri({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  const Triangle b = tri({0.5, 0, 0}, {3, 0, 0}, {1.5, 0, 0});
  const TriContact c = triangle_pair_contact(a, b, 1.0, Vec3::UnitY());
  EXPECT_EQ(c.normal, Vec3::UnitY());
  EXPECT_EQ(c.depth, 0.0);
}

}  // namespace
}  // namespace graspcd::triangle_contact_test
