// Tree-against-tree collision query: a separator at the node pairs, a triangle test at the leaves.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/obb_tree.h"
#include "core/sat.h"
#include "core/tritri.h"

namespace graspcd {

enum class QueryMode {
  kFirstContact,  // stop at the first intersecting triangle pair
  kAllContacts,   // find every intersecting triangle pair
};

// Work done by queries; summed over calls until reset.
struct QueryCounters {
  std::uint64_t box_tests = 0;          // node pairs handed to the separator
  std::uint64_t perceptron_passes = 0;  // passes over the 16 corners (perceptron separators)
  std::uint64_t sat_fallbacks = 0;      // perceptron tests that fell back to SAT (Neuro-SAT)
  std::uint64_t cache_hits = 0;         // node pairs answered from a temporal-coherence cache
  std::uint64_t tri_tests = 0;          // triangle pairs tested
  std::uint64_t tri_pairs = 0;          // triangle pairs found intersecting

  QueryCounters& operator+=(const QueryCounters& o);
};

// An intersecting pair, as indices into the two inputs' face lists.
struct TrianglePair {
  std::int32_t a = 0;
  std::int32_t b = 0;
  friend bool operator==(const TrianglePair& x, const TrianglePair& y) {
    return x.a == y.a && x.b == y.b;
  }
  friend bool operator<(const TrianglePair& x, const TrianglePair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  }
};

struct QueryResult {
  bool intersect = false;
  std::uint64_t pair_count = 0;  // intersecting triangle pairs found (0 or 1 in first-contact mode)
};

// The separator policy of the paper's SAT: stateless.
struct SatSeparator {
  bool disjoint(const Obb& a, const Obb& b, std::int32_t /*node_a*/, std::int32_t /*node_b*/,
                QueryCounters& /*counters*/) {
    return sat_separating_axis(a, b) != kSatNoAxis;
  }
};

// The triangle test policy: the project's exact Moller by default.
struct ExactTriTest {
  bool operator()(const Triangle& a, const Triangle& b) const { return tri_tri_intersect(a, b); }
};

// Descends both trees from their roots. Tree B is placed in A's frame by `b_in_a`
// (x_A = R x_B + t): its boxes through transform(), its triangles through apply_pose() (the
// doubles the exact ground truth sees too). At each node pair the separator may prove the boxes
// disjoint; otherwise the larger node (by sum of half-extents) is split; at two leaves every
// triangle pair is tested. `pairs`, if given, receives the intersecting pairs as input face
// indices (unsorted). Separator: bool disjoint(const Obb& a, const Obb& b_in_a, int32 node_a,
// int32 node_b, QueryCounters&), which must never claim "disjoint" for overlapping boxes.
template <class Separator, class TriTest = ExactTriTest>
QueryResult collide(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryMode mode,
                    Separator& separator, QueryCounters& counters,
                    std::vector<TrianglePair>* pairs = nullptr, TriTest tri_test = TriTest{}) {
  QueryResult result;
  if (a.nodes().empty() || b.nodes().empty()) return result;
  const auto& na = a.nodes();
  const auto& nb = b.nodes();
  std::vector<std::pair<std::int32_t, std::int32_t>> stack;
  stack.reserve(64);
  stack.emplace_back(0, 0);
  while (!stack.empty()) {
    const auto [ia, ib] = stack.back();
    stack.pop_back();
    const ObbNode& x = na[ia];
    const ObbNode& y = nb[ib];
    // Node pair: ask the separator.
    ++counters.box_tests;
    if (separator.disjoint(x.box, transform(b_in_a, y.box), ia, ib, counters)) continue;
    // Two leaves: test their triangles.
    if (x.is_leaf() && y.is_leaf()) {
      for (std::int32_t j = y.first; j < y.first + y.count; ++j) {
        const Triangle tb = apply_pose(b_in_a, b.triangles()[j]);
        for (std::int32_t i = x.first; i < x.first + x.count; ++i) {
          ++counters.tri_tests;
          if (!tri_test(a.triangles()[i], tb)) continue;
          ++counters.tri_pairs;
          ++result.pair_count;
          result.intersect = true;
          if (pairs) pairs->push_back({a.face_ids()[i], b.face_ids()[j]});
          if (mode == QueryMode::kFirstContact) return result;
        }
      }
      continue;
    }
    // Otherwise split the larger node (a leaf is never split).
    const bool split_a = !x.is_leaf() && (y.is_leaf() || x.box.half.sum() >= y.box.half.sum());
    if (split_a) {
      stack.emplace_back(x.right, ib);
      stack.emplace_back(ia + 1, ib);
    } else {
      stack.emplace_back(ia, y.right);
      stack.emplace_back(ia, ib + 1);
    }
  }
  return result;
}

}  // namespace graspcd
