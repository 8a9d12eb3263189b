// The core's triangle tests (src/graspcd/core/tritri.h) against the exact twin (CGAL,
// src/graspcd/exact): seeded random pairs at four scales, adversarial pairs of every degenerate
// class, symmetry under swapping the triangles and permuting their vertices, the variant with a
// triangle's plane given (bitwise the same answer and gap), and the documented defects of the two
// reference variants.
//
// GRASPCD_TEST_SCALE (a positive double, default 1) multiplies the number of random pairs (never
// below 1000 per size), so that the sanitizer build can run a subset; the adversarial suite is
// small and always runs in full.
#include "graspcd/core/tritri.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>

#include "graspcd/core/predicates.h"
#include "graspcd/exact/exact.h"
#include "graspcd/support/random_geometry.h"
#include "helpers/test_scale.h"

namespace graspcd::tritri_test {
namespace {

std::int64_t scaled_count(int n) { return testing::scaled(n, 1000); }

// The 18 doubles of a pair, as the `tritri` command reads them.
std::string format_pair(const Triangle& t1, const Triangle& t2) {
  std::string out;
  char buf[32];
  for (const Triangle* t : {&t1, &t2}) {
    for (const Vec3& v : t->v) {
      for (int k = 0; k < 3; ++k) {
        std::snprintf(buf, sizeof buf, "%.17g ", v[k]);
        out += buf;
      }
    }
  }
  out.pop_back();
  return out;
}

// Compares every core answer on a pair (both orders, permuted vertices, the exact fallback)
// with CGAL's. Returns the number of mismatching calls; prints the first few pairs.
struct Checker {
  int printed = 0;
  std::int64_t mismatches = 0;
  std::int64_t gaps = 0;  // pairs whose gap was positive (and checked against the distance)

  bool check(const Triangle& t1, const Triangle& t2, bool truth, testing::Rng& rng,
             const char* what) {
    const int p = static_cast<int>(testing::uniform_int(rng, 0, 5));
    const int q = static_cast<int>(testing::uniform_int(rng, 0, 5));
    const Triangle u1 = testing::permuted(t1, p), u2 = testing::permuted(t2, q);
    const std::array<bool, 5> answers = {tri_tri_intersect(t1, t2), tri_tri_intersect(t2, t1),
                                         tri_tri_intersect(u1, u2), tri_tri_intersect(u2, u1),
                                         tri_tri_intersect_predicates(t1, t2)};
    static constexpr const char* kNames[5] = {"fast", "fast swapped", "fast permuted",
                                              "fast permuted swapped", "exact"};
    bool ok = true;
    // The variant with a gap answers the same, and a gap is 0 for a pair that meets and a lower
    // bound on the two triangles' distance otherwise (tritri.h).
    double gap = -1;
    const bool with_gap = tri_tri_intersect(t1, t2, gap);
    const bool gap_ok = with_gap == truth && gap >= 0 &&
                        (truth ? gap == 0
                               : gap == 0 || exact::plane_keeps_apart(t1, t2, gap) ||
                                     exact::plane_keeps_apart(t2, t1, gap));
    if (!gap_ok) {
      ok = false;
      ++mismatches;
      if (printed < 10) {
        ++printed;
        ADD_FAILURE() << what << ": with a gap says " << with_gap << " gap " << gap
                      << ", CGAL says " << truth << "\n  " << format_pair(t1, t2);
      }
    }
    gaps += gap > 0;
    // With t1's plane given (as the tree query gives a tree's), the same answer and the same gap
    // bit for bit.
    const TrianglePlane plane = triangle_plane(t1);
    double plane_gap = -1;
    const bool given = tri_tri_intersect(t1, plane, t2, plane_gap);
    const bool given_no_gap = tri_tri_intersect(t1, plane, t2);
    if (given != with_gap || given_no_gap != with_gap || plane_gap != gap) {
      ok = false;
      ++mismatches;
      if (printed < 10) {
        ++printed;
        ADD_FAILURE() << what << ": with the plane given says " << given << "/" << given_no_gap
                      << " gap " << plane_gap << ", computed says " << with_gap << " gap " << gap
                      << "\n  " << format_pair(t1, t2);
      }
    }
    for (int i = 0; i < 5; ++i) {
      if (answers[i] == truth) continue;
      ok = false;
      ++mismatches;
      if (printed < 10) {
        ++printed;
        ADD_FAILURE() << what << ": " << kNames[i] << " says " << answers[i] << ", CGAL says "
                      << truth << " (perm " << p << "," << q << ")\n  " << format_pair(t1, t2);
      }
    }
    return ok;
  }
};

// ---- Random pairs at four scales --------------------------------------------------------------

class TriTriRandom : public ::testing::TestWithParam<double> {};

TEST_P(TriTriRandom, AgreesWithCgal) {
  const double size = GetParam();
  const std::int64_t n = scaled_count(200000);
  testing::Rng rng(0x5eed0000u + static_cast<std::uint64_t>(std::llround(1e3 * size)));
  // Fat triangles of `size` (random_geometry.h) about a point of a workspace of +-max(1 m, 10
  // sizes); the second one's centre is offset by up to 0.25 sizes per axis, which keeps about half
  // of the pairs intersecting (the band is asserted below).
  const double workspace = std::max(1.0, 10 * size);
  Checker checker;
  std::int64_t hits = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec3 c = testing::random_in_cube(rng, Vec3::Zero(), workspace);
    const Triangle t1 = testing::random_fat_triangle(rng, c, size);
    const Triangle t2 =
        testing::random_fat_triangle(rng, testing::random_in_cube(rng, c, 0.25 * size), size);
    const bool truth = exact::tri_tri_intersect(t1, t2);
    hits += truth;
    checker.check(t1, t2, truth, rng, "random");
  }
  const double rate = static_cast<double>(hits) / static_cast<double>(n);
  std::printf("size %g m: %" PRId64 " pairs, hit rate %.3f, %" PRId64 " disagreements\n", size, n,
              rate, checker.mismatches);
  RecordProperty("pairs", std::to_string(n));
  RecordProperty("hit_rate", std::to_string(rate));
  EXPECT_EQ(checker.mismatches, 0);
  EXPECT_GE(rate, 0.2);
  EXPECT_LE(rate, 0.8);
  EXPECT_GT(checker.gaps, n / 10) << "the plane test rejects many pairs, each with a gap";
}

TEST_P(TriTriRandom, AgreesWithCgalOnGridSnappedVertices) {
  // The same pairs with every coordinate rounded to a grid of size / 8 .. size / 16 (a power of
  // two, so the rounding is exact): random shared vertices, coplanar pairs, collinear and repeated
  // vertices and vertices on edges and faces appear by the thousand.
  const double size = GetParam();
  const std::int64_t n = scaled_count(200000);
  testing::Rng rng(0x9a1d0000u + static_cast<std::uint64_t>(std::llround(1e3 * size)));
  const double grid = std::ldexp(1.0, static_cast<int>(std::floor(std::log2(size))) - 3);
  const auto snap = [grid](Triangle t) {
    for (Vec3& v : t.v) {
      for (int k = 0; k < 3; ++k) v[k] = std::round(v[k] / grid) * grid;
    }
    return t;
  };
  const double workspace = std::max(1.0, 10 * size);
  Checker checker;
  std::int64_t hits = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec3 c = testing::random_in_cube(rng, Vec3::Zero(), workspace);
    const Triangle t1 = snap(testing::random_fat_triangle(rng, c, size));
    const Triangle t2 =
        snap(testing::random_fat_triangle(rng, testing::random_in_cube(rng, c, 0.25 * size), size));
    const bool truth = exact::tri_tri_intersect(t1, t2);
    hits += truth;
    checker.check(t1, t2, truth, rng, "snapped");
  }
  const double rate = static_cast<double>(hits) / static_cast<double>(n);
  std::printf("size %g m, snapped to %g m: %" PRId64 " pairs, hit rate %.3f, %" PRId64
              " disagreements\n",
              size, grid, n, rate, checker.mismatches);
  EXPECT_EQ(checker.mismatches, 0);
  EXPECT_GE(rate, 0.2);
  EXPECT_LE(rate, 0.8);
}

INSTANTIATE_TEST_SUITE_P(Sizes, TriTriRandom, ::testing::Values(1e-3, 1e-2, 1.0, 100.0),
                         [](const ::testing::TestParamInfo<double>& param) {
                           std::ostringstream s;
                           s << (param.param < 1 ? "mm" : "m")
                             << (param.param < 1 ? param.param * 1e3 : param.param);
                           return s.str();
                         });

// ---- Adversarial pairs ------------------------------------------------------------------------

TEST(TriTriAdversarial, AgreesWithCgalOnEveryClass) {
  testing::Rng rng(0xad7e55a1u);
  constexpr int kPerCell = 120;  // per class, placement and size
  constexpr std::array<double, 4> kSizes = {1e-3, 1e-2, 1.0, 100.0};
  constexpr std::array<testing::Placement, 4> kPlacements = {
      testing::Placement::kLattice, testing::Placement::kLatticeFar, testing::Placement::kRotated,
      testing::Placement::kRotatedFar};
  Checker checker;
  std::int64_t total = 0;
  for (int cls = 0; cls < testing::kPairClassCount; ++cls) {
    const auto pair_class = static_cast<testing::PairClass>(cls);
    std::int64_t count = 0, hits = 0, known = 0, class_mismatches = 0;
    for (const double size : kSizes) {
      for (const testing::Placement placement : kPlacements) {
        for (int i = 0; i < kPerCell; ++i) {
          const testing::AdversarialPair pair =
              testing::make_adversarial(pair_class, placement, size, rng);
          const bool truth = exact::tri_tri_intersect(pair.t1, pair.t2);
          ++count;
          hits += truth;
          if (pair.expected >= 0) {
            ++known;
            // The construction's answer (exact in double) must be CGAL's too.
            EXPECT_EQ(truth, pair.expected == 1)
                << testing::pair_class_name(pair_class) << " " << testing::placement_name(placement)
                << "\n  " << format_pair(pair.t1, pair.t2);
          }
          const std::string what = std::string(testing::pair_class_name(pair_class)) + " " +
                                   testing::placement_name(placement);
          if (!checker.check(pair.t1, pair.t2, truth, rng, what.c_str())) ++class_mismatches;
        }
      }
    }
    total += count;
    std::printf("%-18s %6" PRId64 " pairs, %6" PRId64 " intersecting, %6" PRId64
                " known by construction, %" PRId64 " disagreeing\n",
                testing::pair_class_name(pair_class), count, hits, known, class_mismatches);
    RecordProperty(testing::pair_class_name(pair_class), std::to_string(count));
    EXPECT_GT(count, 0);
  }
  EXPECT_GE(total, 20000);
  EXPECT_EQ(checker.mismatches, 0);
}

// ---- The reference variants' documented defects -----------------------------------------------

TEST(TriTriReferenceVariants, NaiveMollerCallsDisjointGraspScalePairsIntersecting) {
  // Moller's absolute epsilon (1e-6 on plane distances scaled by |N| ~ (5 mm)^2) treats any vertex
  // within centimetres of the other plane as on it: disjoint 5 mm pairs become "intersecting".
  testing::Rng rng(5);
  const double size = 5e-3;
  std::int64_t disjoint = 0, false_hits = 0, false_misses = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 c = testing::random_in_cube(rng, Vec3::Zero(), 0.5);
    const Triangle t1 = testing::random_triangle(rng, c, size);
    const Triangle t2 =
        testing::random_triangle(rng, testing::random_in_cube(rng, c, 0.6 * size), size);
    const bool truth = exact::tri_tri_intersect(t1, t2);
    const bool naive = tri_tri_moller_naive(t1, t2);
    disjoint += !truth;
    false_hits += !truth && naive;
    false_misses += truth && !naive;
  }
  std::printf("naive Moller at 5 mm: %" PRId64 " of %" PRId64
              " disjoint pairs called intersecting, %" PRId64 " intersecting pairs missed\n",
              false_hits, disjoint, false_misses);
  EXPECT_GT(disjoint, 1000);
  EXPECT_GT(false_hits, 100);
}

TEST(TriTriReferenceVariants, PlainMollerMissesTouchingPairs) {
  // Without any epsilon, a shared vertex or edge gives plane distances that round to either sign:
  // some touching pairs come out "disjoint".
  testing::Rng rng(6);
  std::int64_t touching = 0, missed = 0;
  for (int i = 0; i < 4000; ++i) {
    const auto cls = i % 2 ? testing::PairClass::kSharedEdge : testing::PairClass::kSharedVertex;
    const auto pair = testing::make_adversarial(cls, testing::Placement::kRotated, 1e-2, rng);
    ASSERT_TRUE(exact::tri_tri_intersect(pair.t1, pair.t2));
    ++touching;
    missed += !tri_tri_moller_plain(pair.t1, pair.t2);
  }
  std::printf("plain Moller: %" PRId64 " of %" PRId64 " touching pairs missed\n", missed, touching);
  EXPECT_GT(missed, 0);
}

}  // namespace
}  // namespace graspcd::tritri_test

namespace graspcd {
namespace {

// A triangle with a NaN or infinite coordinate is no set of points; both exact
// tests say "disjoint" at once, whatever the other coordinates, without exact arithmetic.
TEST(TriTriNonFinite, ATriangleWithANanOrInfIntersectsNothing) {
  const Triangle t1{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}};
  predicates::filter_stats() = predicates::FilterStats{};
  for (const double x : {std::nan(""), std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()}) {
    // Piercing t1 but for one coordinate.
    const Triangle t2{{Vec3(0.2, 0.2, -1), Vec3(0.25, 0.2, 1), Vec3(x, 0.3, 0)}};
    EXPECT_FALSE(tri_tri_intersect(t1, t2)) << x;
    EXPECT_FALSE(tri_tri_intersect(t2, t1)) << x;
    EXPECT_FALSE(tri_tri_intersect_predicates(t1, t2)) << x;
    EXPECT_FALSE(tri_tri_intersect_predicates(t2, t2)) << x;
    // With a plane given (a tree's), the same: its triangle or the other one non-finite.
    EXPECT_FALSE(triangle_plane(t2).finite) << x;
    EXPECT_FALSE(tri_tri_intersect(t2, triangle_plane(t2), t1)) << x;
    EXPECT_FALSE(tri_tri_intersect(t1, triangle_plane(t1), t2)) << x;
    double gap = -1;
    EXPECT_FALSE(tri_tri_intersect(t1, triangle_plane(t1), t2, gap)) << x;
    EXPECT_EQ(gap, 0) << x;
  }
  EXPECT_EQ(predicates::filter_stats().orient3d_exact_calls, 0u);
  EXPECT_TRUE(
      tri_tri_intersect(t1, Triangle{{Vec3(0.2, 0.2, -1), Vec3(0.25, 0.2, 1), Vec3(0.3, 0.3, 0)}}));
}

}  // namespace
}  // namespace graspcd
