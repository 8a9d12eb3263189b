// The separating axis test (src/graspcd/core/sat.h) against the exact box test (src/graspcd/exact):
// random, near-parallel, near-touching and exactly touching box pairs at sizes 1 mm .. 100 m, near
// and far from the origin.
//
// What is asserted:
//  - SAT never calls overlapping boxes separated (a false "separated" would lose a collision);
//  - the axis it returns separates the boxes in exact arithmetic, and a first_axis hint changes
//    only the order of the tests, never the answer;
//  - a false "may overlap" (exact: disjoint) is allowed but bounded: on every one of SAT's 15 axes
//    the exact gap is at most twice the slack of tolerances.h (the factor 2 covers SAT's own
//    floating-point evaluation and axes up to 1e-9 off orthonormal, both far below the slack).
//    Equivalently: whenever some axis shows a gap above twice the slack, SAT separates.
//
// GRASPCD_TEST_SCALE (a positive double, default 1) multiplies the number of pairs (never below
// 1000), so that the sanitizer build can run a subset.
#include "graspcd/core/sat.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include "graspcd/core/tolerances.h"
#include "graspcd/exact/exact.h"
#include "graspcd/support/random_geometry.h"
#include "helpers/test_scale.h"

namespace graspcd {
namespace {

std::int64_t scaled_count(int n) { return testing::scaled(n, 1000); }

// The slack of sat.h, as documented in tolerances.h.
double sat_slack(const Obb& a, const Obb& b) {
  return tol::kSatRelativeSlack *
             (a.half.sum() + b.half.sum() + (b.center - a.center).lpNorm<1>()) +
         tol::kSatRoundoffFactor * (a.center.lpNorm<1>() + b.center.lpNorm<1>());
}

// The 30 numbers of a pair, as the `boxbox` command reads them.
std::string format_boxes(const Obb& a, const Obb& b) {
  std::string out;
  char buf[32];
  for (const Obb* box : {&a, &b}) {
    std::array<double, 15> v;
    for (int k = 0; k < 3; ++k) v[k] = box->center[k];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) v[3 + 3 * r + c] = box->axes(r, c);
    }
    for (int k = 0; k < 3; ++k) v[12 + k] = box->half[k];
    for (const double x : v) {
      std::snprintf(buf, sizeof buf, "%.17g ", x);
      out += buf;
    }
  }
  out.pop_back();
  return out;
}

// ---- Box pair generators ----------------------------------------------------------------------

enum class Kind {
  kRandom,           // random boxes, centres within a few sizes
  kRandomFar,        // the same 1e3 .. 1e5 sizes from the origin
  kNearParallel,     // B = A's frame turned by 1e-12 .. 1e-3 rad, face to face, gap 0 or tiny
  kNearTouching,     // random pair moved along its best axis to a gap of +-1e-16 .. 1e-3 sizes
  kDyadicTouching,   // axis-permuted boxes, face/edge/corner contact at an exact gap of 0 or 2^-k
  kDyadicEdgeCross,  // boxes turned 45 degrees about x and y: two edges cross at exact gap 0/2^-k
  kCount
};

constexpr int kKindCount = static_cast<int>(Kind::kCount);

const char* kind_name(Kind k) {
  static constexpr const char* kNames[kKindCount] = {"random",          "random_far",
                                                     "near_parallel",   "near_touching",
                                                     "dyadic_touching", "dyadic_edge_cross"};
  return kNames[static_cast<int>(k)];
}

struct BoxPair {
  Obb a, b;
  int expected = -1;  // 1 overlap, 0 disjoint, known by an exact construction; -1 unknown
};

// Moves every entry of the axes by up to 1e-10, keeping R^T R within kOrthonormalTol (1e-9) of
// the identity: valid input that is not orthonormal.
void perturb_axes(testing::Rng& rng, Mat3& axes) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) axes(r, c) += testing::uniform(rng, -1e-10, 1e-10);
  }
}

Vec3 random_center(testing::Rng& rng, double size, bool far) {
  if (!far) return testing::random_in_cube(rng, Vec3::Zero(), 10 * size);
  const double distance = testing::log_uniform(rng, 1e3, 1e5) * size;
  return distance * testing::random_unit(rng);
}

// The candidate axis (sat.h numbering, in the world frame) with the largest normalised gap, in
// floating point: its unit vector oriented from A to B, and the gap.
std::pair<Vec3, double> best_axis(const Obb& a, const Obb& b) {
  const Vec3 d = b.center - a.center;
  Vec3 best_axis_dir = Vec3::UnitX();
  double best = -1e300;
  for (int k = 1; k <= 15; ++k) {
    Vec3 L = k <= 3   ? a.axes.col(k - 1)
             : k <= 6 ? b.axes.col(k - 4)
                      : a.axes.col((k - 7) / 3).cross(b.axes.col((k - 7) % 3));
    if (L.norm() < 1e-6) continue;
    L.normalize();
    if (d.dot(L) < 0) L = -L;
    double gap = d.dot(L);
    for (int i = 0; i < 3; ++i) {
      gap -=
          a.half[i] * std::abs(a.axes.col(i).dot(L)) + b.half[i] * std::abs(b.axes.col(i).dot(L));
    }
    if (gap > best) {
      best = gap;
      best_axis_dir = L;
    }
  }
  return {best_axis_dir, best};
}

// A signed permutation matrix with determinant +1: an exact rotation of the frame.
Mat3 signed_permutation(testing::Rng& rng) {
  std::array<int, 3> p = {0, 1, 2};
  testing::shuffle(p, rng);
  Mat3 m = Mat3::Zero();
  for (int c = 0; c < 3; ++c) m(p[c], c) = testing::uniform_int(rng, 0, 1) ? 1.0 : -1.0;
  if (m.determinant() < 0) m.col(0) = -m.col(0);
  return m;
}

// World extent of a box with signed-permutation axes along world axis k.
double extent_along(const Obb& box, int k) {
  for (int c = 0; c < 3; ++c) {
    if (box.axes(k, c) != 0.0) return box.half[c];
  }
  return 0.0;
}

BoxPair make_pair(Kind kind, testing::Rng& rng) {
  BoxPair p;
  const double size = testing::log_uniform(rng, 1e-3, 1e2);
  const bool far = kind == Kind::kRandomFar || testing::uniform_int(rng, 0, 2) == 0;
  switch (kind) {
    case Kind::kRandom:
    case Kind::kRandomFar: {
      const Vec3 c = random_center(rng, size, kind == Kind::kRandomFar);
      p.a = testing::random_box(rng, c, 0.05 * size, size);
      p.b = testing::random_box(rng, c + testing::random_in_cube(rng, Vec3::Zero(), 0.8 * size),
                                0.05 * size, size);
      break;
    }
    case Kind::kNearParallel: {
      p.a = testing::random_box(rng, random_center(rng, size, far), 0.05 * size, size);
      p.b = p.a;
      p.b.axes = p.a.axes * testing::rotation_about(testing::random_unit(rng),
                                                    testing::log_uniform(rng, 1e-12, 1e-3));
      for (int i = 0; i < 3; ++i) p.b.half[i] = testing::log_uniform(rng, 0.05 * size, size);
      const int face = static_cast<int>(testing::uniform_int(rng, 0, 2));
      const double gap = testing::uniform_int(rng, 0, 9) == 0
                             ? 0.0
                             : (testing::uniform_int(rng, 0, 1) ? 1 : -1) * size *
                                   testing::log_uniform(rng, 1e-15, 1e-3);
      Vec3 v;
      for (int i = 0; i < 3; ++i) {
        const double reach = p.a.half[i] + p.b.half[i];
        v[i] = i == face ? reach + gap : testing::uniform(rng, -0.9, 0.9) * reach;
      }
      if (testing::uniform_int(rng, 0, 1)) v[face] = -v[face];
      p.b.center = p.a.center + p.a.axes * v;
      break;
    }
    case Kind::kNearTouching: {
      const Vec3 c = random_center(rng, size, far);
      p.a = testing::random_box(rng, c, 0.05 * size, size);
      p.b = testing::random_box(rng, c + testing::random_in_cube(rng, Vec3::Zero(), 2 * size),
                                0.05 * size, size);
      const auto [dir, gap] = best_axis(p.a, p.b);
      const double target = testing::uniform_int(rng, 0, 9) == 0
                                ? 0.0
                                : (testing::uniform_int(rng, 0, 1) ? 1 : -1) * size *
                                      testing::log_uniform(rng, 1e-16, 1e-3);
      p.b.center += (target - gap) * dir;
      break;
    }
    case Kind::kDyadicTouching: {
      // Everything on the lattice of step 2^(e-4) ~ size / 16; sums stay below 53 bits.
      const int e = static_cast<int>(std::floor(std::log2(size)));
      const double step = std::ldexp(1.0, e - 4);
      const std::int64_t reach = far ? (std::int64_t{1} << 20) : 160;
      for (Obb* box : {&p.a, &p.b}) {
        box->axes = signed_permutation(rng);
        for (int i = 0; i < 3; ++i) {
          box->half[i] = step * static_cast<double>(testing::uniform_int(rng, 1, 16));
        }
      }
      for (int k = 0; k < 3; ++k) {
        p.a.center[k] = step * static_cast<double>(testing::uniform_int(rng, -reach, reach));
      }
      // Contact on the first `contacts` axes of a random order (face, edge or corner); the rest
      // overlap strictly.
      std::array<int, 3> order = {0, 1, 2};
      testing::shuffle(order, rng);
      const int contacts = static_cast<int>(testing::uniform_int(rng, 1, 3));
      for (int n = 0; n < 3; ++n) {
        const int k = order[n];
        const double sum = extent_along(p.a, k) + extent_along(p.b, k);
        const double sign = testing::uniform_int(rng, 0, 1) ? 1.0 : -1.0;
        const auto steps = static_cast<std::int64_t>(sum / step);
        const double offset =
            n < contacts
                ? sum
                : step * static_cast<double>(testing::uniform_int<std::int64_t>(rng, 0, steps - 1));
        p.b.center[k] = p.a.center[k] + sign * offset;
      }
      // Exactly touching, or moved out (disjoint) or in (overlapping) by 2^-k steps on the first
      // contact axis.
      const int move = static_cast<int>(testing::uniform_int(rng, -1, 1));
      const double delta =
          step * std::ldexp(1.0, -static_cast<int>(testing::uniform_int(rng, 0, 28)));
      const int k0 = order[0];
      p.b.center[k0] += move * delta * (p.b.center[k0] > p.a.center[k0] ? 1.0 : -1.0);
      p.expected = move > 0 ? 0 : 1;
      break;
    }
    case Kind::kDyadicEdgeCross: {
      // A turned 45 degrees about y (its top edge runs along y), B turned 45 degrees about x (its
      // bottom edge runs along x). The columns use s = sqrt(1/2) rounded: exactly orthogonal,
      // unit to 1e-16, taken as given by both tests. A reaches s (hA0 + hA2) above its centre, B
      // s (hB1 + hB2) below its own; with those four half-extents 2^(e-2) each, the edges touch
      // when cB.z - cA.z = s 2^e, a product by a power of two and so exact.
      const double s = std::sqrt(0.5);
      const int e = static_cast<int>(std::floor(std::log2(size)));
      const double step = std::ldexp(1.0, e - 4);
      p.a.axes << s, 0, s, 0, 1, 0, -s, 0, s;
      p.b.axes << 1, 0, 0, 0, s, -s, 0, s, s;
      const double quarter = std::ldexp(1.0, e - 2);  // four of them sum to 2^e
      p.a.half =
          Vec3(quarter, step * static_cast<double>(testing::uniform_int(rng, 1, 16)), quarter);
      p.b.half =
          Vec3(step * static_cast<double>(testing::uniform_int(rng, 1, 16)), quarter, quarter);
      const std::int64_t reach = far ? (std::int64_t{1} << 20) : 160;
      p.a.center = Vec3(step * static_cast<double>(testing::uniform_int(rng, -reach, reach)),
                        step * static_cast<double>(testing::uniform_int(rng, -reach, reach)), 0.0);
      // The edges cross where |dx| < hB0 and |dy| < hA1 (strictly, on the lattice).
      const auto bx = static_cast<std::int64_t>(p.b.half[0] / step) - 1;
      const auto ay = static_cast<std::int64_t>(p.a.half[1] / step) - 1;
      const int move = static_cast<int>(testing::uniform_int(rng, -1, 1));
      const double delta =
          step * std::ldexp(1.0, -static_cast<int>(testing::uniform_int(rng, 0, 28)));
      p.b.center = p.a.center + Vec3(step * static_cast<double>(testing::uniform_int(rng, -bx, bx)),
                                     step * static_cast<double>(testing::uniform_int(rng, -ay, ay)),
                                     s * std::ldexp(1.0, e) + move * delta);
      p.expected = move > 0 ? 0 : 1;
      // Any signed permutation of the world axes, applied to both boxes, is exact.
      const Mat3 P = signed_permutation(rng);
      for (Obb* box : {&p.a, &p.b}) {
        box->axes = P * box->axes;
        box->center = P * box->center;
      }
      break;
    }
    case Kind::kCount:
      break;
  }
  if (p.expected < 0 && testing::uniform_int(rng, 0, 3) == 0) {
    perturb_axes(rng, p.a.axes);
    perturb_axes(rng, p.b.axes);
  }
  if (testing::uniform_int(rng, 0, 1)) std::swap(p.a, p.b);
  return p;
}

// ---- The test ---------------------------------------------------------------------------------

struct KindStats {
  std::int64_t pairs = 0, overlapping = 0, separated = 0, known = 0;
  std::int64_t false_separated = 0, false_may_overlap = 0;
  double worst_axis_gap_over_slack = 0;  // over false "may overlap": max SAT-axis gap / slack
  double worst_gap = 0;                  // over false "may overlap": box_box_gap, metres
  double worst_gap_over_slack = 0;       // the same divided by that pair's slack
};

TEST(SatVsExact, NeverFalselySeparatedAndFalseOverlapsBoundedBySlack) {
  const std::int64_t n = scaled_count(120000);
  testing::Rng rng(0x5a7'0001u);
  std::array<KindStats, kKindCount> stats{};
  int printed = 0;
  const auto report = [&printed](const std::string& what, const Obb& a, const Obb& b) {
    if (printed++ < 10) ADD_FAILURE() << what << "\n  " << format_boxes(a, b);
  };
  for (std::int64_t i = 0; i < n; ++i) {
    const Kind kind = static_cast<Kind>(i % kKindCount);
    KindStats& st = stats[static_cast<int>(kind)];
    const BoxPair pair = make_pair(kind, rng);
    const Obb& a = pair.a;
    const Obb& b = pair.b;
    ASSERT_TRUE(is_rotation(a.axes, tol::kOrthonormalTol) &&
                is_rotation(b.axes, tol::kOrthonormalTol))
        << format_boxes(a, b);

    const bool overlap = exact::box_box_overlap(a, b);
    const SatAxis axis = sat_separating_axis(a, b);
    ++st.pairs;
    st.overlapping += overlap;
    st.separated += axis != kSatNoAxis;
    if (pair.expected >= 0) {
      ++st.known;
      if (overlap != (pair.expected == 1)) report("exact test contradicts construction", a, b);
    }

    if (axis != kSatNoAxis) {
      // Separated: it must be true, on the very axis returned, and the hint must agree.
      if (overlap) {
        ++st.false_separated;
        report("SAT separates overlapping boxes on axis " + std::to_string(axis), a, b);
      } else if (!(exact::sat_axis_gap(a, b, axis) > 0)) {
        report("SAT's axis " + std::to_string(axis) + " does not separate", a, b);
      }
      if (sat_separating_axis(a, b, axis) != axis) report("hint of the found axis ignored", a, b);
    } else if (!overlap) {
      // False "may overlap": every axis' exact gap within twice the slack.
      ++st.false_may_overlap;
      const double slack = sat_slack(a, b);
      double worst_axis = -1e300;
      for (SatAxis k = 1; k <= 15; ++k)
        worst_axis = std::max(worst_axis, exact::sat_axis_gap(a, b, k));
      st.worst_axis_gap_over_slack = std::max(st.worst_axis_gap_over_slack, worst_axis / slack);
      if (worst_axis > 2 * slack)
        report("SAT misses a gap of " + std::to_string(worst_axis / slack) + " slacks", a, b);
      const double gap = exact::box_box_gap(a, b);
      st.worst_gap = std::max(st.worst_gap, gap);
      st.worst_gap_over_slack = std::max(st.worst_gap_over_slack, gap / slack);
    }

    // Any hint: same verdict; a separating answer must separate exactly.
    const auto hint = static_cast<SatAxis>(testing::uniform_int(rng, 1, 15));
    const SatAxis hinted = sat_separating_axis(a, b, hint);
    if ((hinted != kSatNoAxis) != (axis != kSatNoAxis)) {
      report("hint " + std::to_string(hint) + " changes the verdict", a, b);
    } else if (hinted != kSatNoAxis && hinted != axis && !(exact::sat_axis_gap(a, b, hinted) > 0)) {
      report("hinted axis " + std::to_string(hinted) + " does not separate", a, b);
    }
  }

  std::int64_t total = 0, false_separated = 0;
  for (int k = 0; k < kKindCount; ++k) {
    const KindStats& st = stats[k];
    std::printf("%-18s %6" PRId64 " pairs, %6" PRId64 " overlapping, %6" PRId64
                " separated by SAT, %" PRId64 " false separated, %5" PRId64
                " false may-overlap (worst axis gap %.5g slacks; worst distance gap %.3g m = "
                "%.4g slacks)\n",
                kind_name(static_cast<Kind>(k)), st.pairs, st.overlapping, st.separated,
                st.false_separated, st.false_may_overlap, st.worst_axis_gap_over_slack,
                st.worst_gap, st.worst_gap_over_slack);
    RecordProperty(std::string(kind_name(static_cast<Kind>(k))) + "_false_may_overlap",
                   std::to_string(st.false_may_overlap));
    total += st.pairs;
    false_separated += st.false_separated;
    // Each kind must exercise both answers.
    EXPECT_GT(st.overlapping, 0) << kind_name(static_cast<Kind>(k));
    EXPECT_GT(st.pairs - st.overlapping, 0) << kind_name(static_cast<Kind>(k));
  }
  EXPECT_GE(total, std::min<std::int64_t>(n, 100000));
  EXPECT_EQ(false_separated, 0);
  EXPECT_GT(stats[static_cast<int>(Kind::kDyadicTouching)].known, 0);
  EXPECT_GT(stats[static_cast<int>(Kind::kDyadicEdgeCross)].known, 0);
  EXPECT_EQ(printed, 0);
}

TEST(SatVsExact, ReturnsAxesInDocumentedNumbering) {
  // Axis-aligned unit boxes apart along x, y, z: A's axes 1, 2, 3 (A's are tried first).
  for (int k = 0; k < 3; ++k) {
    Obb a, b;
    a.half = b.half = Vec3(1, 1, 1);
    b.center[k] = 2.5;
    EXPECT_EQ(sat_separating_axis(a, b), 1 + k);
    // With A's axes tried first, B's axis k (4 + k) is only reported when hinted.
    EXPECT_EQ(sat_separating_axis(a, b, 4 + k), 4 + k);
    EXPECT_GT(exact::sat_axis_gap(a, b, 4 + k), 0);
  }
  // An edge-edge separation: A turned 45 degrees about y, B 45 degrees about x, B above with a
  // gap of 0.25 in z: only A_1 x B_0 (= y x x, index 7 + 3 + 0 = 10) separates.
  const double s = std::sqrt(0.5);
  Obb a, b;
  a.axes << s, 0, s, 0, 1, 0, -s, 0, s;
  b.axes << 1, 0, 0, 0, s, -s, 0, s, s;
  a.half = b.half = Vec3(1, 1, 1);
  b.center = Vec3(0, 0, 4 * s + 0.25);
  EXPECT_EQ(sat_separating_axis(a, b), 10);
  EXPECT_GT(exact::sat_axis_gap(a, b, 10), 0);
  b.center[2] = 4 * s;  // touching edge to edge
  EXPECT_EQ(sat_separating_axis(a, b), kSatNoAxis);
  EXPECT_TRUE(exact::box_box_overlap(a, b));
}

}  // namespace
}  // namespace graspcd
