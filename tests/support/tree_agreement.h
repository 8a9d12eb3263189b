// Checks that a detector's tree query gives CGAL's brute-force answer (src/exact): the collision
// answer and the sorted intersecting triangle pairs in all-contacts mode, the answer and a 0/1
// count in first-contact mode. Shared by the tree query and the separator tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/separators.h"
#include "exact/exact.h"
#include "support/meshes.h"
#include "support/random_geometry.h"
#include "support/test_scale.h"

namespace graspcd::testing {

struct Agreement {
  int poses = 0, intersecting = 0;
  std::uint64_t pairs = 0;
  QueryCounters counters;
};

// A pose with its ground truth: CGAL's sorted intersecting pairs of a and b placed by the pose.
struct PoseCase {
  Pose pose;
  std::vector<TrianglePair> truth;
};

inline PoseCase make_case(const TriangleMesh& a, const TriangleMesh& b, const Pose& pose) {
  return {pose, exact::mesh_mesh_pairs(posed_triangles(a, Pose{}), posed_triangles(b, pose))};
}

// Both modes at one pose against the truth; fatal on the first disagreement.
inline void check_case(Detector& detector, const ObbTree& ta, const ObbTree& tb, const PoseCase& c,
                       Agreement& agreement) {
  std::vector<TrianglePair> pairs;
  const QueryResult all =
      detector.collide(ta, tb, c.pose, QueryMode::kAllContacts, agreement.counters, &pairs);
  std::sort(pairs.begin(), pairs.end());
  ASSERT_EQ(all.intersect, !c.truth.empty()) << method_name(detector.method());
  ASSERT_EQ(all.pair_count, c.truth.size()) << method_name(detector.method());
  ASSERT_EQ(pairs, c.truth) << method_name(detector.method());
  const QueryResult first =
      detector.collide(ta, tb, c.pose, QueryMode::kFirstContact, agreement.counters);
  ASSERT_EQ(first.intersect, !c.truth.empty()) << method_name(detector.method());
  ASSERT_EQ(first.pair_count, c.truth.empty() ? 0u : 1u);
  ++agreement.poses;
  agreement.intersecting += !c.truth.empty();
  agreement.pairs += c.truth.size();
}

// Poses of b around a with their truths: for each random direction and rotation, b is moved from
// a's centre outward; the transition from "intersect" to "not" is bracketed by bisection (with
// SAT's query: the truth is still CGAL's), then poses are taken at both sides of it (touching to
// within 1e-12 of the size), just outside (near miss), just inside (shallow) and deep inside.
inline std::vector<PoseCase> cases_around(const TriangleMesh& a, const TriangleMesh& b,
                                          int directions, std::uint64_t seed) {
  const ObbTree ta = ObbTree::build(a), tb = ObbTree::build(b);
  const double size = ta.root().box.half.norm() + tb.root().box.half.norm();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  Detector sat(Method::kSat);
  QueryCounters counters;
  const auto hits = [&](const Pose& p) {
    return sat.collide(ta, tb, p, QueryMode::kFirstContact, counters).intersect;
  };
  std::vector<PoseCase> cases;
  int used = 0;
  for (int attempt = 0; used < directions && attempt < 4 * directions; ++attempt) {
    Pose pose;
    pose.R = random_rotation(rng);
    const Vec3 dir = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Vec3 base = ta.root().box.center - pose.R * tb.root().box.center;
    const auto at = [&](double s) {
      Pose p = pose;
      p.t = base + s * dir;
      return p;
    };
    double lo = -1, hi = 2 * size;
    for (int i = 0; i < 16 && lo < 0; ++i) {
      if (hits(at(size * i / 16.0))) lo = size * i / 16.0;
    }
    if (lo < 0 || hits(at(hi))) continue;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (hits(at(mid)) ? lo : hi) = mid;
    }
    ++used;
    for (double s : {lo, hi, hi + 1e-4 * size, lo - 1e-3 * size, lo - 0.25 * size}) {
      cases.push_back(make_case(a, b, at(s)));
    }
  }
  EXPECT_EQ(used, directions);
  return cases;
}

// Every case for one detector.
inline void check_cases(Detector& detector, const ObbTree& ta, const ObbTree& tb,
                        const std::vector<PoseCase>& cases, Agreement& agreement) {
  for (const PoseCase& c : cases) {
    check_case(detector, ta, tb, c, agreement);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

}  // namespace graspcd::testing
