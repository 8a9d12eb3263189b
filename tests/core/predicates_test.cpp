// The filtered predicates against their exact evaluation, on inputs whose true sign is known from
// the construction (not from the code under test).
#include "graspcd/core/predicates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "graspcd/support/seeded.h"

namespace graspcd::predicates {
namespace {

int sign(double x) { return (x > 0) - (x < 0); }

// Kettner et al., "Classroom examples of robustness problems in geometric computations" (2008):
// p = (0.5 + x u, 0.5 + y u) against the line through q = (12, 12) and r = (24, 24). The exact
// orientation of (q, r, p) is sign(p_y - p_x) = sign(y - x): plain floating point gets it wrong on
// much of this grid.
TEST(Orient2d, KettnerGridMatchesTheExactSign) {
  const double u = std::ldexp(1.0, -53);
  const Vec3 q(12, 12, 0), r(24, 24, 0);
  int checked = 0;
  for (int x = 0; x < 256; ++x) {
    for (int y = 0; y < 256; ++y) {
      const Vec3 p(0.5 + x * u, 0.5 + y * u, 0);
      // Dropping z keeps (x, y) in cyclic order: the sign is that of the cross product's z.
      const int expected = sign(static_cast<double>(y - x));
      ASSERT_EQ(orient2d(q, r, p, 2), expected) << x << " " << y;
      ASSERT_EQ(orient2d_exact(q, r, p, 2), expected) << x << " " << y;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 65536);
}

// Exactly coplanar points (dyadic coordinates on the plane x + 2y + 4z = 8, far from the origin),
// then the fourth point moved by one ulp off the plane: the sign is that of the normal's
// component along the move.
TEST(Orient3d, CoplanarAndOneUlpOffThePlane) {
  seeded::Rng rng(20261122);
  const auto coord = [&rng] { return seeded::uniform_int(rng, -1000, 1000); };
  int zeros = 0, moved = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double offset = std::ldexp(1.0, trial % 40);  // up to 2^39 m from the origin
    const auto on_plane = [&](int ix, int iy) {
      const double x = ix / 64.0, y = iy / 64.0;
      return Vec3(x + offset, y + offset, (8 - x - 2 * y) / 4.0 - 0.75 * offset);
    };
    std::array<int, 8> k;
    for (int& ki : k) ki = coord();
    const Vec3 a = on_plane(k[0], k[1]), b = on_plane(k[2], k[3]), c = on_plane(k[4], k[5]);
    Vec3 d = on_plane(k[6], k[7]);
    const Vec3 normal = (b - a).cross(c - a);  // exact here: small dyadic differences
    if (normal.z() == 0) continue;
    ASSERT_EQ(orient3d(a, b, c, d), 0);
    ASSERT_EQ(orient3d_exact(a, b, c, d), 0);
    ++zeros;
    d.z() = std::nextafter(d.z(), INFINITY);
    ASSERT_EQ(orient3d(a, b, c, d), sign(normal.z()));
    ASSERT_EQ(orient3d_exact(a, b, c, d), sign(normal.z()));
    ++moved;
  }
  EXPECT_GT(zeros, 19000);
  EXPECT_EQ(zeros, moved);
}

// The sign is antisymmetric under swapping two points and invariant under cyclic shifts of
// (a, b, c); filtered and exact agree on random near-degenerate inputs.
TEST(Orient3d, FilterAgreesWithExactAndPermutationRules) {
  seeded::Rng rng(7);
  std::uint64_t exact_before = filter_stats().orient3d_exact_calls;
  for (int trial = 0; trial < 100000; ++trial) {
    const Vec3 a = seeded::uniform_vec3(rng, -1.0, 1.0);
    const Vec3 b = seeded::uniform_vec3(rng, -1.0, 1.0);
    const Vec3 c = seeded::uniform_vec3(rng, -1.0, 1.0);
    // d near the plane: an affine combination plus a tiny offset that may vanish in rounding.
    const double s = seeded::uniform(rng, -1.0, 1.0);
    const double t = seeded::uniform(rng, -1.0, 1.0);
    const double tiny = std::ldexp(seeded::uniform(rng, -1.0, 1.0), -50 - trial % 8);
    const Vec3 d = a + s * (b - a) + t * (c - a) + tiny * seeded::uniform_vec3(rng, -1.0, 1.0);
    const int o = orient3d(a, b, c, d);
    ASSERT_EQ(o, orient3d_exact(a, b, c, d));
    ASSERT_EQ(orient3d(b, c, a, d), o);
    ASSERT_EQ(orient3d(b, a, c, d), -o);
  }
  // Near-degenerate inputs do reach the exact stage (the test exercises both paths).
  EXPECT_GT(filter_stats().orient3d_exact_calls, exact_before);
}

TEST(Orient2d, EachDropAxisMatchesTheCrossProductComponent) {
  seeded::Rng rng(11);
  for (int trial = 0; trial < 10000; ++trial) {
    const Vec3 a = seeded::uniform_vec3(rng, -10.0, 10.0);
    const Vec3 b = seeded::uniform_vec3(rng, -10.0, 10.0);
    const Vec3 c = seeded::uniform_vec3(rng, -10.0, 10.0);
    const Vec3 n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) {
      // Away from zero the plain product has the right sign.
      if (std::fabs(n[k]) < 1e-9) continue;
      ASSERT_EQ(orient2d(a, b, c, k), sign(n[k]));
    }
  }
}

TEST(Orient3d, ExtremeButSupportedMagnitudes) {
  // Tiny and huge coordinates inside tol's range stay exact: a unit tetrahedron scaled.
  for (double s : {1e-45, 1e-20, 1.0, 1e20, 1e45}) {
    const Vec3 a(0, 0, 0), b(s, 0, 0), c(0, s, 0), d(0, 0, s);
    EXPECT_EQ(orient3d(a, b, c, d), 1) << s;
    EXPECT_EQ(orient3d(a, c, b, d), -1) << s;
    EXPECT_EQ(orient3d(a, b, c, Vec3(s, s, 0)), 0) << s;
  }
}

}  // namespace
}  // namespace graspcd::predicates

namespace graspcd::predicates {
namespace {

// A NaN or infinite coordinate has no orientation. Every predicate answers 0 at
// once, the exact variants included, and never fills an expansion with NaN.
TEST(Predicates, NonFiniteCoordinatesAnswerZeroWithoutExpansions) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  filter_stats() = FilterStats{};
  for (const double x : {std::nan(""), std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()}) {
    const Vec3 bad(x, 0.25, 0.5);
    EXPECT_EQ(orient3d(a, b, c, bad), 0);
    EXPECT_EQ(orient3d(bad, b, c, Vec3(0.25, 0.25, 1)), 0);
    EXPECT_EQ(orient3d_exact(a, b, c, bad), 0);
    for (int drop = 1; drop < 3; ++drop) {  // dropping x (drop 0) leaves finite coordinates
      EXPECT_EQ(orient2d(a, bad, c, drop), 0);
      EXPECT_EQ(orient2d_exact(a, bad, c, drop), 0);
    }
  }
  EXPECT_EQ(filter_stats().orient3d_exact_calls, 0u);
  EXPECT_EQ(filter_stats().orient2d_exact_calls, 0u);
}

}  // namespace
}  // namespace graspcd::predicates
