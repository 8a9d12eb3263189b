// Checks that a detector's tree query gives CGAL's brute-force answer (src/graspcd/exact): the
// collision answer and the sorted intersecting triangle pairs in all-contacts mode, the answer and
// a 0/1 count in first-contact mode. Shared by the tree query and the separator tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "graspcd/core/separators.h"
#include "graspcd/exact/exact.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/random_geometry.h"
#include "helpers/contact_rays.h"
#include "helpers/test_scale.h"

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

// Poses of b around a with their truths: on each contact ray (bracketed with SAT's query: the
// truth is still CGAL's), poses at both sides of the transition (touching to within 1e-12 of the
// size), just outside (near miss), just inside (shallow) and deep inside.
inline std::vector<PoseCase> cases_around(const TriangleMesh& a, const TriangleMesh& b,
                                          int directions, std::uint64_t seed) {
  const ObbTree ta = ObbTree::build(a), tb = ObbTree::build(b);
  const double size = ta.root().box.half.norm() + tb.root().box.half.norm();
  Rng rng(seed);
  Detector sat(Method::kSat);
  QueryCounters counters;
  const auto hits = [&](const Pose& p) {
    return sat.collide(ta, tb, p, QueryMode::kFirstContact, counters).intersect;
  };
  std::vector<PoseCase> cases;
  for (const ContactRay& r : contact_rays(ta, tb, size, directions, rng, hits)) {
    for (double s : {r.lo, r.hi, r.hi + 1e-4 * size, r.lo - 1e-3 * size, r.lo - 0.25 * size}) {
      cases.push_back(make_case(a, b, r.at(s)));
    }
  }
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
