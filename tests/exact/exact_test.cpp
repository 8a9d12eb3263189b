// Unit tests of the exact module (src/graspcd/exact): hand-built cases whose answers are known from
// the construction (dyadic coordinates, so every stated contact is exact in double).
#include "graspcd/exact/exact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "graspcd/support/random_geometry.h"

namespace graspcd {
namespace {

Triangle tri(const Vec3& a, const Vec3& b, const Vec3& c) { return Triangle{{a, b, c}}; }

// The answer must not depend on the order of the triangles or of their vertices: checks all
// 2 x 6 x 6 orderings against `expected`.
void expect_tri_tri(const Triangle& t1, const Triangle& t2, bool expected,
                    const std::string& what) {
  for (int p = 0; p < 6; ++p) {
    for (int q = 0; q < 6; ++q) {
      const Triangle a = testing::permuted(t1, p);
      const Triangle b = testing::permuted(t2, q);
      EXPECT_EQ(exact::tri_tri_intersect(a, b), expected) << what << " perm " << p << "," << q;
      EXPECT_EQ(exact::tri_tri_intersect(b, a), expected) << what << " swapped " << p << "," << q;
    }
  }
}

// The reference triangle of most cases: the right triangle x, y >= 0, x + y <= 1 in z = 0.
const Triangle kBase = tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));

TEST(ExactOrient3d, SignConvention) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  EXPECT_EQ(exact::orient3d(a, b, c, d), 1);  // d on the side (b-a) x (c-a) = +z points to
  EXPECT_EQ(exact::orient3d(a, c, b, d), -1);
  EXPECT_EQ(exact::orient3d(a, b, c, -d), -1);
  EXPECT_EQ(exact::orient3d(a, b, c, Vec3(5, -7, 0)), 0);
}

TEST(ExactOrient3d, DecidesTinyOffsetsExactly) {
  // d lifted off plane z = 0 by 2^-1000 far from the origin: a double determinant would be 0.
  const Vec3 a(1e10, 1e10, 0), b(1e10 + 1, 1e10, 0), c(1e10, 1e10 + 1, 0);
  EXPECT_EQ(exact::orient3d(a, b, c, Vec3(3e10, -2e10, std::ldexp(1.0, -1000))), 1);
  EXPECT_EQ(exact::orient3d(a, b, c, Vec3(3e10, -2e10, -std::ldexp(1.0, -1000))), -1);
  // Collinear-looking but not: c' = a + (1, 1 + 2^-52, 0) scaled, d above.
  const Vec3 p(0.5, 0.5, 0.5), q(1.5, 1.5, 1.5), r(2.5, 2.5, 2.5 + std::ldexp(1.0, -51));
  EXPECT_NE(exact::orient3d(p, q, r, Vec3(0, 1, 0)), 0);
  EXPECT_EQ(exact::orient3d(p, q, Vec3(2.5, 2.5, 2.5), Vec3(0, 1, 0)), 0);
}

TEST(ExactTriTri, GeneralPosition) {
  expect_tri_tri(kBase, tri(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)), false, "parallel");
  expect_tri_tri(kBase, tri(Vec3(0.25, 0.25, -1), Vec3(0.25, 0.25, 1), Vec3(2, 2, 0.5)), true,
                 "pierce");
  expect_tri_tri(kBase, tri(Vec3(0.75, 0.75, -1), Vec3(0.75, 0.75, 1), Vec3(2, 2, 0.5)), false,
                 "miss beside");
}

TEST(ExactTriTri, TouchingCountsAsIntersecting) {
  // A vertex on the face, the rest above.
  expect_tri_tri(kBase, tri(Vec3(0.25, 0.25, 0), Vec3(1, 1, 1), Vec3(-1, 0, 2)), true,
                 "vertex on face");
  // The same vertex 2^-60 above the face: disjoint.
  expect_tri_tri(kBase, tri(Vec3(0.25, 0.25, std::ldexp(1.0, -60)), Vec3(1, 1, 1), Vec3(-1, 0, 2)),
                 false, "vertex just above face");
  // A vertex on an edge (the hypotenuse), the rest above.
  expect_tri_tri(kBase, tri(Vec3(0.5, 0.5, 0), Vec3(1, 1, 1), Vec3(-1, 0, 2)), true,
                 "vertex on edge");
  // Shared edge, the other triangle folded up out of the plane.
  expect_tri_tri(kBase, tri(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1)), true, "shared edge");
  // Shared vertex only.
  expect_tri_tri(kBase, tri(Vec3(1, 0, 0), Vec3(2, 0, 1), Vec3(2, 1, 1)), true, "shared vertex");
  // Edge across edge at one point: the other triangle's edge x = 0.25, z = 0 above the plane.
  expect_tri_tri(kBase, tri(Vec3(0.25, -1, 0), Vec3(0.25, -0.5, 0), Vec3(0.25, -1, 1)), false,
                 "edge short of edge");
  expect_tri_tri(kBase, tri(Vec3(0.25, -1, 0), Vec3(0.25, 0, 0), Vec3(0.25, -1, 1)), true,
                 "edge ends on edge");
  expect_tri_tri(tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, -1)),
                 tri(Vec3(0.5, -1, 0), Vec3(0.5, 1, 0), Vec3(0.5, 0, 1)), true,
                 "edge crosses edge");
  expect_tri_tri(
      tri(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, -1)),
      tri(Vec3(0.5, -1, std::ldexp(1.0, -70)), Vec3(0.5, 1, std::ldexp(1.0, -70)), Vec3(0.5, 0, 1)),
      false, "edge passes above edge");
}

TEST(ExactTriTri, Coplanar) {
  expect_tri_tri(kBase, tri(Vec3(0.25, 0.25, 0), Vec3(2, 0.25, 0), Vec3(0.25, 2, 0)), true,
                 "coplanar overlap");
  expect_tri_tri(kBase, tri(Vec3(0.125, 0.125, 0), Vec3(0.25, 0.125, 0), Vec3(0.125, 0.25, 0)),
                 true, "coplanar contained");
  expect_tri_tri(kBase, tri(Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(1, 2, 0)), false,
                 "coplanar disjoint");
  expect_tri_tri(kBase, tri(Vec3(0.5, 0.5, 0), Vec3(2, 0.5, 0), Vec3(0.5, 2, 0)), true,
                 "coplanar touching at a point of the hypotenuse");
  expect_tri_tri(kBase, tri(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)), true,
                 "coplanar shared edge");
  expect_tri_tri(kBase, tri(Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0)), true,
                 "coplanar shared vertex");
  const double e = std::ldexp(1.0, -50);
  expect_tri_tri(kBase, tri(Vec3(0.5 + e, 0.5, 0), Vec3(2, 0.5, 0), Vec3(0.5 + e, 2, 0)), false,
                 "coplanar gap of 2^-50");
  // Coplanar in a tilted plane x + y + z = 1 (exact dyadic points on it).
  const Triangle slanted = tri(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
  expect_tri_tri(slanted, tri(Vec3(0.25, 0.25, 0.5), Vec3(0.5, 0.25, 0.25), Vec3(2, -2, 1)), true,
                 "slanted coplanar overlap");
  expect_tri_tri(slanted, tri(Vec3(2, -0.5, -0.5), Vec3(3, -1, -1), Vec3(2, -2, 1)), false,
                 "slanted coplanar disjoint");
}

TEST(ExactTriTri, ZeroAreaSegment) {
  // Three collinear points through the face's interior (the middle one listed first).
  const Triangle through = tri(Vec3(0.25, 0.25, 0), Vec3(0.25, 0.25, -1), Vec3(0.25, 0.25, 1));
  expect_tri_tri(kBase, through, true, "segment through face");
  expect_tri_tri(kBase, tri(Vec3(0.25, 0.25, 1), Vec3(0.25, 0.25, 0.5), Vec3(0.25, 0.25, 2)), false,
                 "segment above face");
  // A repeated vertex: the segment from (0.25, 0.25, 0) (on the face) up.
  expect_tri_tri(kBase, tri(Vec3(0.25, 0.25, 0), Vec3(0.25, 0.25, 1), Vec3(0.25, 0.25, 0)), true,
                 "segment ending on face");
  // A segment in the plane, crossing the hypotenuse, and one beside the triangle.
  expect_tri_tri(kBase, tri(Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0)), true,
                 "coplanar segment crossing");
  expect_tri_tri(kBase, tri(Vec3(0.75, 0.75, 0), Vec3(1, 1, 0), Vec3(2, 2, 0)), false,
                 "coplanar segment beside");
  // Segment against segment.
  const Triangle sx = tri(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0));
  expect_tri_tri(sx, tri(Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)), true, "segments cross");
  expect_tri_tri(sx, tri(Vec3(0, -1, 0.5), Vec3(0, 1, 0.5), Vec3(0, 0, 0.5)), false,
                 "skew segments");
  expect_tri_tri(sx, tri(Vec3(1, 0, 0), Vec3(3, 0, 0), Vec3(2, 0, 0)), true,
                 "collinear segments touching");
  expect_tri_tri(sx, tri(Vec3(1.5, 0, 0), Vec3(3, 0, 0), Vec3(2, 0, 0)), false,
                 "collinear segments apart");
  expect_tri_tri(sx, tri(Vec3(-0.5, 0, 0), Vec3(3, 0, 0), Vec3(2, 0, 0)), true,
                 "collinear segments overlapping");
}

TEST(ExactTriTri, ZeroAreaPoint) {
  const auto point = [](const Vec3& p) { return tri(p, p, p); };
  expect_tri_tri(kBase, point(Vec3(0.25, 0.25, 0)), true, "point in face");
  expect_tri_tri(kBase, point(Vec3(0.5, 0.5, 0)), true, "point on edge");
  expect_tri_tri(kBase, point(Vec3(0, 1, 0)), true, "point at vertex");
  expect_tri_tri(kBase, point(Vec3(0.75, 0.75, 0)), false, "point beside, in plane");
  expect_tri_tri(kBase, point(Vec3(0.25, 0.25, std::ldexp(1.0, -1000))), false, "point just above");
  const Triangle sx = tri(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 0));
  expect_tri_tri(sx, point(Vec3(0.5, 0, 0)), true, "point on segment");
  expect_tri_tri(sx, point(Vec3(1, 0, 0)), true, "point at segment end");
  expect_tri_tri(sx, point(Vec3(1.5, 0, 0)), false, "point past segment end");
  expect_tri_tri(sx, point(Vec3(0.5, std::ldexp(1.0, -60), 0)), false, "point beside segment");
  expect_tri_tri(point(Vec3(1, 2, 3)), point(Vec3(1, 2, 3)), true, "same point");
  expect_tri_tri(point(Vec3(1, 2, 3)), point(Vec3(1, 2, std::nextafter(3.0, 4.0))), false,
                 "points one ulp apart");
}

TEST(ExactTriTri, AgreesWithTheConstructionOfAdversarialPairs) {
  // Every lattice-placed adversarial pair whose answer is known by construction: CGAL must agree
  // (this checks the generator as much as the exact module).
  testing::Rng rng(20240611);
  int known = 0;
  for (int cls = 0; cls < testing::kPairClassCount; ++cls) {
    for (int i = 0; i < 300; ++i) {
      const auto placement = i % 2 ? testing::Placement::kLattice : testing::Placement::kLatticeFar;
      const auto pair =
          testing::make_adversarial(static_cast<testing::PairClass>(cls), placement, 1e-2, rng);
      if (pair.expected < 0) continue;
      ++known;
      ASSERT_EQ(exact::tri_tri_intersect(pair.t1, pair.t2), pair.expected == 1)
          << testing::pair_class_name(pair.cls) << " " << testing::placement_name(pair.placement);
    }
  }
  EXPECT_GT(known, 1000);
}

Obb box(const Vec3& center, const Vec3& half, const Mat3& axes = Mat3::Identity()) {
  Obb b;
  b.center = center;
  b.axes = axes;
  b.half = half;
  return b;
}

Mat3 rot_z(double angle) { return testing::rotation_about(Vec3(0, 0, 1), angle); }

void expect_boxes(const Obb& a, const Obb& b, bool expected, const std::string& what) {
  EXPECT_EQ(exact::box_box_overlap(a, b), expected) << what;
  EXPECT_EQ(exact::box_box_overlap(b, a), expected) << what << " (swapped)";
  EXPECT_EQ(exact::box_box_gap(a, b) > 0, !expected) << what << " (gap sign)";
}

TEST(ExactBoxBox, AxisAligned) {
  const Vec3 one(1, 1, 1);
  expect_boxes(box(Vec3(0, 0, 0), one), box(Vec3(2.5, 0, 0), one), false, "gap 0.5");
  expect_boxes(box(Vec3(0, 0, 0), one), box(Vec3(2, 0, 0), one), true, "touching faces");
  expect_boxes(box(Vec3(0, 0, 0), one), box(Vec3(2, 2, 2), one), true, "touching corners");
  expect_boxes(box(Vec3(0, 0, 0), one), box(Vec3(2 + std::ldexp(1.0, -40), 0, 0), one), false,
               "gap 2^-40");
  expect_boxes(box(Vec3(0, 0, 0), one), box(Vec3(0.5, 0.25, -0.5), Vec3(3, 0.5, 0.5)), true,
               "crossing");
  // Far from the origin, gap of one ulp of the centre.
  const double c = 1e6;
  expect_boxes(box(Vec3(c, c, c), one), box(Vec3(c + 2, c, c), one), true, "far, touching");
  expect_boxes(box(Vec3(c, c, c), one), box(Vec3(std::nextafter(c + 2, 2 * c), c, c), one), false,
               "far, ulp gap");
}

TEST(ExactBoxBox, Rotated45Degrees) {
  // B rotated 45 degrees about z: its corner reaches sqrt(2) towards A along x.
  const Vec3 one(1, 1, 1);
  const Obb a = box(Vec3(0, 0, 0), one);
  const Mat3 r45 = rot_z(testing::kPi / 4);
  expect_boxes(a, box(Vec3(2.4, 0, 0), one, r45), true, "corner into face");
  expect_boxes(a, box(Vec3(2.43, 0, 0), one, r45), false, "corner short of face");
  // Both rotated 45 degrees about z and placed along the diagonal: face to face at distance 2.
  const Vec3 diag = Vec3(1, 1, 0) / std::sqrt(2.0);
  expect_boxes(box(Vec3(0, 0, 0), one, r45), box(1.999 * diag, one, r45), true, "faces overlap");
  expect_boxes(box(Vec3(0, 0, 0), one, r45), box(2.001 * diag, one, r45), false, "faces apart");
  // Edge against edge: B rotated 45 degrees about x and about z, so that only its edge can meet
  // A's top edge region; centre placed so the gap along (0, 1, 1) is 0.01 / -0.01.
  const Mat3 rx = testing::rotation_about(Vec3(1, 0, 0), testing::kPi / 4);
  const Obb b_edge = box(Vec3(0, 0, 0), one, rx);
  const Vec3 n = Vec3(0, 1, 1) / std::sqrt(2.0);
  // A's extent along n is sqrt(2); B's (a rotated box with a face normal along n) is 1.
  const double reach = std::sqrt(2.0) + 1.0;
  Obb near = b_edge, far = b_edge;
  near.center = (reach - 0.01) * n;
  far.center = (reach + 0.01) * n;
  expect_boxes(a, near, true, "edge into face");
  expect_boxes(a, far, false, "edge short of face");
}

TEST(ExactBoxBox, FlatBoxes) {
  const Vec3 one(1, 1, 1);
  const Obb flat = box(Vec3(0, 0, 0), Vec3(1, 1, 0));  // the square |x|, |y| <= 1 in z = 0
  expect_boxes(flat, box(Vec3(0, 0, 1), one), true, "flat touching a box");
  expect_boxes(flat, box(Vec3(0, 0, 1 + std::ldexp(1.0, -30)), one), false, "flat below a box");
  expect_boxes(flat, box(Vec3(1.5, 0.5, 0), Vec3(1, 1, 0)), true, "coplanar flats overlapping");
  expect_boxes(flat, box(Vec3(2.5, 0.5, 0), Vec3(0.25, 1, 0)), false, "coplanar flats apart");
  expect_boxes(flat, box(Vec3(0.5, 0.5, 0), Vec3(0, 0, 0)), true, "point box on the square");
  expect_boxes(flat, box(Vec3(0.5, 0.5, 0.125), Vec3(0, 0, 0)), false, "point box above");
  // A segment box (two zero extents) crossing the square's plane, and one beside it.
  expect_boxes(flat, box(Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 0.5)), true, "segment box touching");
  expect_boxes(flat, box(Vec3(0.5, 1.5, 0), Vec3(0, 0, 0.5), rot_z(0.3)), false,
               "segment box beside");
  // Two skew segments (boxes with two zero extents): crossing and passing at 1/8.
  const Obb sx = box(Vec3(0, 0, 0), Vec3(1, 0, 0));
  expect_boxes(sx, box(Vec3(0, 0, 0), Vec3(0, 1, 0)), true, "segments cross");
  expect_boxes(sx, box(Vec3(0, 0, 0.125), Vec3(0, 1, 0)), false, "segments pass");
}

TEST(ExactBoxBox, AxesSlightlyOffOrthonormalAreTakenAsGiven) {
  // A's second column leans 1e-9 towards x: A reaches x = 1 + 1e-9, not 1. A test that assumed
  // orthonormal axes would call B (starting at x = 1 + 5e-10) disjoint.
  Mat3 skew = Mat3::Identity();
  skew(0, 1) = 1e-9;
  const Vec3 one(1, 1, 1);
  const Obb a = box(Vec3(0, 0, 0), one, skew);
  expect_boxes(a, box(Vec3(2 + 5e-10, 0, 0), one), true, "skewed column reaches");
  expect_boxes(a, box(Vec3(2 + 2e-9, 0, 0), one), false, "beyond the skewed reach");
  // A first column 1e-9 longer than unit: A reaches x = 1 + 1e-9.
  Mat3 longer = Mat3::Identity();
  longer(0, 0) = 1 + 1e-9;
  expect_boxes(box(Vec3(0, 0, 0), one, longer), box(Vec3(2 + 5e-10, 0, 0), one), true,
               "long column reaches");
  expect_boxes(box(Vec3(0, 0, 0), one, longer), box(Vec3(2 + 2e-9, 0, 0), one), false,
               "beyond the long column");
}

TEST(ExactBoxBox, AgreesWithCornerContainmentAndBoundingSpheres) {
  // Known answers on random pairs: a pair whose bounding spheres are apart is disjoint; a pair
  // where a corner of one lies strictly inside the other (checked with a margin) overlaps.
  testing::Rng rng(7);
  int disjoint = 0, overlapping = 0;
  for (int i = 0; i < 4000; ++i) {
    const Obb a = testing::random_box(rng, Vec3::Zero(), 0.1, 1.0);
    const Obb b = testing::random_box(rng, testing::random_in_cube(rng, Vec3::Zero(), 2), 0.1, 1.0);
    const bool spheres_apart = (b.center - a.center).norm() > a.half.norm() + b.half.norm() + 1e-9;
    bool corner_inside = false;
    for (const Vec3& p : obb_corners(b)) {
      const Vec3 local = a.axes.transpose() * (p - a.center);
      corner_inside = corner_inside || (local.cwiseAbs().array() < a.half.array() - 1e-9).all();
    }
    const bool overlap = exact::box_box_overlap(a, b);
    if (spheres_apart) {
      ++disjoint;
      EXPECT_FALSE(overlap) << i;
    }
    if (corner_inside) {
      ++overlapping;
      EXPECT_TRUE(overlap) << i;
    }
  }
  EXPECT_GT(disjoint, 100);
  EXPECT_GT(overlapping, 100);
}

TEST(ExactBoxBox, FilteredTestAgreesWithPurelyExactGap) {
  // box_box_overlap decides most axes with intervals; box_box_gap is rational throughout. On
  // touching and nearly touching pairs (where the filter must hand over) their signs must agree.
  testing::Rng rng(11);
  int touching = 0;
  for (int i = 0; i < 3000; ++i) {
    Obb a = testing::random_box(rng, testing::random_in_cube(rng, Vec3::Zero(), 4.0), 0.25, 2.0);
    Obb b = a;
    b.axes =
        a.axes * testing::rotation_about(testing::random_unit(rng),
                                         i % 3 == 0 ? 0.0 : testing::log_uniform(rng, 1e-12, 1));
    // B's centre on A's face plane offset by B's own reach along A's axis 0, up to 2^-k.
    const double reach = (b.axes.transpose() * a.axes.col(0)).cwiseAbs().dot(b.half);
    const double offset = a.half[0] + reach;
    const int shift = static_cast<int>(testing::uniform_int(rng, -1, 1));
    b.center =
        a.center +
        (offset + shift * std::ldexp(1.0, -static_cast<int>(testing::uniform_int(rng, 1, 60)))) *
            a.axes.col(0);
    if (i % 3 == 0) {
      // Same frame, moved along an exact axis: with axes = identity the contact is exact.
      a.axes = b.axes = Mat3::Identity();
      b.center = a.center + Vec3(a.half[0] + b.half[0], 0.5 * a.half[1], 0);
      if (shift != 0) b.center[0] += shift * std::ldexp(1.0, -20);
      touching += shift == 0 && b.center[0] - a.center[0] == a.half[0] + b.half[0];
    }
    const bool overlap = exact::box_box_overlap(a, b);
    EXPECT_EQ(overlap, !(exact::box_box_gap(a, b) > 0)) << i;
    EXPECT_EQ(overlap, exact::box_box_overlap(b, a)) << i;
  }
  EXPECT_GT(touching, 100);
}

TEST(ExactBoxBox, GapsOnAxes) {
  const Vec3 one(1, 1, 1);
  const Obb a = box(Vec3(0, 0, 0), one);
  const Obb b = box(Vec3(2.5, 0.5, 0), one);
  EXPECT_EQ(exact::sat_axis_gap(a, b, 1), 0.5);       // A's x axis
  EXPECT_EQ(exact::sat_axis_gap(a, b, 2), -1.5);      // A's y axis
  EXPECT_EQ(exact::sat_axis_gap(a, b, 4), 0.5);       // B's x axis
  EXPECT_EQ(exact::sat_axis_gap(a, b, 7), 0.0);       // x cross x is zero
  EXPECT_EQ(exact::sat_axis_gap(a, b, 7 + 1), -2.0);  // A_x cross B_y = z: |0| - 1 - 1
  EXPECT_EQ(exact::box_box_gap(a, b), 0.5);
  EXPECT_THROW(exact::sat_axis_gap(a, b, 0), std::invalid_argument);
  EXPECT_THROW(exact::sat_axis_gap(a, b, 16), std::invalid_argument);
}

// The square [0, 2]^2 in z = 0 as a 2 x 2 grid of cells (i, j), each split along its diagonal into
// a lower triangle (index 2 (2 j + i)) and an upper one (index 2 (2 j + i) + 1).
std::vector<Triangle> grid_mesh() {
  std::vector<Triangle> out;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const double x = i, y = j;
      out.push_back(tri(Vec3(x, y, 0), Vec3(x + 1, y, 0), Vec3(x + 1, y + 1, 0)));
      out.push_back(tri(Vec3(x, y, 0), Vec3(x + 1, y + 1, 0), Vec3(x, y + 1, 0)));
    }
  }
  return out;
}

TEST(ExactMeshMesh, HandCountedPairs) {
  const std::vector<Triangle> a = grid_mesh();
  const std::vector<Triangle> b = {
      // 0: pierces cell (0, 0)'s lower triangle only (section y = 0.25, x in [0.78, 0.85]).
      tri(Vec3(0.75, 0.25, -1), Vec3(0.875, 0.25, -1), Vec3(0.8125, 0.25, 1)),
      // 1: floats above everything.
      tri(Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(0, 2, 1)),
      // 2: touches the grid vertex (1, 1) from above: the six triangles around it.
      tri(Vec3(1, 1, 0), Vec3(1.5, 1, 1), Vec3(1, 1.5, 1)),
      // 3: coplanar, inside cell (1, 1)'s upper triangle.
      tri(Vec3(1.125, 1.75, 0), Vec3(1.25, 1.75, 0), Vec3(1.125, 1.875, 0)),
      // 4: coplanar, outside the square.
      tri(Vec3(3, 3, 0), Vec3(4, 3, 0), Vec3(3, 4, 0)),
      // 5: parallel to the square, 2^-40 above.
      tri(Vec3(0, 0, std::ldexp(1.0, -40)), Vec3(2, 0, std::ldexp(1.0, -40)),
          Vec3(0, 2, std::ldexp(1.0, -40))),
      // 6: a zero-area face, the vertical segment through (0.5, 1.5): on cell (0, 1)'s diagonal.
      tri(Vec3(0.5, 1.5, -1), Vec3(0.5, 1.5, 1), Vec3(0.5, 1.5, 0)),
  };
  const std::vector<TrianglePair> expected = {{0, 0}, {0, 2}, {1, 2}, {3, 2}, {4, 2},
                                              {4, 6}, {5, 6}, {6, 2}, {7, 2}, {7, 3}};
  EXPECT_EQ(exact::mesh_mesh_pairs(a, b), expected);

  const std::vector<TrianglePair> first = exact::mesh_mesh_pairs(a, b, true);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(std::find(expected.begin(), expected.end(), first[0]) != expected.end());

  // Swapping the meshes swaps the pairs.
  std::vector<TrianglePair> swapped;
  for (const TrianglePair& p : expected) swapped.push_back({p.b, p.a});
  std::sort(swapped.begin(), swapped.end());
  EXPECT_EQ(exact::mesh_mesh_pairs(b, a), swapped);

  EXPECT_TRUE(exact::mesh_mesh_pairs(a, {b[1], b[4], b[5]}).empty());
  EXPECT_TRUE(exact::mesh_mesh_pairs(a, {b[1]}, true).empty());
  EXPECT_TRUE(exact::mesh_mesh_pairs({}, b).empty());
}

TEST(ExactMeshMesh, MatchesAllPairsBruteForce) {
  // Random soups (including coplanar grids sharing vertices with the other soup): the box
  // filter must not lose a pair that the plain double loop finds.
  testing::Rng rng(99);
  for (int round = 0; round < 5; ++round) {
    std::vector<Triangle> a, b;
    for (int i = 0; i < 150; ++i) {
      a.push_back(
          testing::random_triangle(rng, testing::random_in_cube(rng, Vec3::Zero(), 1.0), 0.4));
      b.push_back(
          testing::random_triangle(rng, testing::random_in_cube(rng, Vec3::Zero(), 1.0), 0.4));
    }
    for (const Triangle& t : grid_mesh()) a.push_back(t);
    b.push_back(tri(Vec3(1, 1, 0), Vec3(1.5, 1, 1), Vec3(1, 1.5, 1)));  // touches 6 grid faces
    std::vector<TrianglePair> brute;
    for (std::size_t i = 0; i < a.size(); ++i) {
      for (std::size_t j = 0; j < b.size(); ++j) {
        if (exact::tri_tri_intersect(a[i], b[j])) {
          brute.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
        }
      }
    }
    EXPECT_GT(brute.size(), 6u);
    EXPECT_EQ(exact::mesh_mesh_pairs(a, b), brute) << "round " << round;
  }
}

// Soups whose whole boxes overlap in a slab or only touch (the plane x = 1, where one triangle of
// each meets the other's at a shared vertex): keeping only the triangles that meet the other
// soup's box loses no pair of the plain double loop.
TEST(ExactMeshMesh, SoupsThatMeetInASlabOrAtAPointKeepEveryPair) {
  testing::Rng rng(7);
  for (const double shift : {0.8, 1.0}) {
    std::vector<Triangle> a, b;
    for (int i = 0; i < 200; ++i) {
      a.push_back(testing::random_triangle(
          rng, testing::random_in_cube(rng, Vec3(0.5, 0.5, 0.5), 0.3), 0.4));
      b.push_back(testing::random_triangle(
          rng, testing::random_in_cube(rng, Vec3(shift + 0.5, 0.5, 0.5), 0.3), 0.4));
    }
    // Clipped into the unit cube and [shift, shift + 1] along x: the whole boxes meet in a slab
    // of 0.2 (shift 0.8) or in the plane x = 1 (shift 1).
    for (Triangle& t : a) {
      for (Vec3& v : t.v) v = v.cwiseMax(Vec3::Zero()).cwiseMin(Vec3::Ones());
    }
    for (Triangle& t : b) {
      for (Vec3& v : t.v) v = v.cwiseMax(Vec3(shift, 0, 0)).cwiseMin(Vec3(shift + 1, 1, 1));
    }
    a.push_back(tri(Vec3(1, 0.5, 0.5), Vec3(0.5, 0.25, 0.5), Vec3(0.5, 0.75, 0.5)));
    b.push_back(tri(Vec3(1, 0.5, 0.5), Vec3(1.5, 0.5, 0.25), Vec3(1.5, 0.5, 0.75)));
    std::vector<TrianglePair> brute;
    for (std::size_t i = 0; i < a.size(); ++i) {
      for (std::size_t j = 0; j < b.size(); ++j) {
        if (exact::tri_tri_intersect(a[i], b[j])) {
          brute.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
        }
      }
    }
    const TrianglePair touching{static_cast<std::int32_t>(a.size() - 1),
                                static_cast<std::int32_t>(b.size() - 1)};
    EXPECT_NE(std::find(brute.begin(), brute.end(), touching), brute.end()) << "shift " << shift;
    if (shift < 1) {
      EXPECT_GT(brute.size(), 1u);
    }
    EXPECT_EQ(exact::mesh_mesh_pairs(a, b), brute) << "shift " << shift;
    EXPECT_EQ(exact::mesh_mesh_pairs(a, b, true).size(), 1u) << "shift " << shift;
  }
}

TEST(ExactVersion, IsCgal5) {
  EXPECT_EQ(std::string(exact::cgal_version()).rfind("5.", 0), 0u) << exact::cgal_version();
}

}  // namespace
}  // namespace graspcd
