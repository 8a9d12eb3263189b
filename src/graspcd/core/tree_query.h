// Tree-against-tree collision query: a separator at the node pairs, a triangle test at the leaves.
#pragma once

#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "graspcd/core/obb_tree.h"
#include "graspcd/core/sat.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/core/tritri.h"

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

// The separator policy of the paper's SAT: stateless. hint() and record() make it an axis
// separator: the tree query then runs SAT itself on frames carried down the trees (collide).
struct SatSeparator {
  bool disjoint(const Obb& a, const Obb& b, std::int32_t /*node_a*/, std::int32_t /*node_b*/,
                QueryCounters& /*counters*/) {
    return sat_separating_axis(a, b) != kSatNoAxis;
  }
  SatAxis hint(std::int32_t /*node_a*/, std::int32_t /*node_b*/) const { return kSatNoAxis; }
  void record(std::int32_t /*node_a*/, std::int32_t /*node_b*/, SatAxis /*axis*/, SatAxis /*hint*/,
              QueryCounters& /*counters*/) {}
};

// The triangle test policy: the project's Moller test by default (tri_tri_intersect: floating point
// with a proven error bound, decided exactly by tri_tri_intersect_predicates inside the bound).
struct FilteredTriTest {
  bool operator()(const Triangle& a, const Triangle& b) const { return tri_tri_intersect(a, b); }
};

namespace detail {

// Axis separators (SatSeparator, SatCachedSeparator): SAT with an optional hinted first axis,
// `SatAxis hint(node_a, node_b)`, and `record(node_a, node_b, axis, hint, counters)` called with
// the separating axis it found.
template <class S, class = void>
struct IsAxisSeparator : std::false_type {};
template <class S>
struct IsAxisSeparator<S, std::void_t<decltype(std::declval<S&>().hint(0, 0))>> : std::true_type {};

// A node pair on the descent: B's node ib in A's node ia's frame (R: its axes, T: its centre).
struct FramedPair {
  std::int32_t ia, ib;
  Mat3 R;
  Vec3 T;
};

// The leaves of a node pair: every triangle pair, B's through apply_pose (the doubles the exact
// ground truth sees too). True when the query is over (first contact found).
template <class TriTest>
bool test_leaves(const ObbTree& a, const ObbTree& b, const ObbNode& x, const ObbNode& y,
                 const Pose& b_in_a, QueryMode mode, QueryCounters& counters,
                 std::vector<TrianglePair>* pairs, TriTest& tri_test, QueryResult& result) {
  for (std::int32_t j = y.first; j < y.first + y.count; ++j) {
    const Triangle tb = apply_pose(b_in_a, b.triangles()[j]);
    for (std::int32_t i = x.first; i < x.first + x.count; ++i) {
      ++counters.tri_tests;
      if (!tri_test(a.triangles()[i], tb)) continue;
      ++counters.tri_pairs;
      ++result.pair_count;
      result.intersect = true;
      if (pairs) pairs->push_back({a.face_ids()[i], b.face_ids()[j]});
      if (mode == QueryMode::kFirstContact) return true;
    }
  }
  return false;
}

// The descent of collide() for axis separators, RAPID style (Gottschalk, Lin, Manocha 1996): the
// root pair's frame R = A0^T R_ab B0, T = A0^T (R_ab cB0 + t - cA0) is formed once; a step down A
// to a child with frame (P, p) in its parent (ObbTree::in_parent) gives (P^T R, P^T (T - p)), a
// step down B to a child with frame (Q, q) gives (R Q, R q + T). Each node pair then costs one
// 3x3 product and the 15-axis test in A's node frame (sat_separating_axis_in_a), instead of
// placing B's box and forming A^T B at every pair. The slack, tolerances.h
// (kSatCarriedRoundoffFactor), covers the rounding carried down. The visiting order, and so
// every counter, is that of the generic descent.
template <class Separator, class TriTest>
QueryResult collide_carried(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryMode mode,
                            Separator& separator, QueryCounters& counters,
                            std::vector<TrianglePair>* pairs, TriTest& tri_test) {
  QueryResult result;
  const auto& na = a.nodes();
  const auto& nb = b.nodes();
  const auto& fa = a.in_parent();
  const auto& fb = b.in_parent();
  // The root pair's frame and the absolute part of the slack.
  const Obb& a0 = na[0].box;
  const Obb& b0 = nb[0].box;
  const Vec3 cb0 = b_in_a.R * b0.center + b_in_a.t;
  const double size = 2 * (a0.center.lpNorm<1>() + a0.half.sum() + cb0.lpNorm<1>() + b0.half.sum());
  const double carried_slack = tol::kSatCarriedRoundoffFactor * (a.depth() + b.depth() + 2) * size;
  std::vector<FramedPair> stack;
  stack.reserve(64);
  stack.push_back(
      {0, 0, a0.axes.transpose() * (b_in_a.R * b0.axes), a0.axes.transpose() * (cb0 - a0.center)});
  while (!stack.empty()) {
    const FramedPair p = stack.back();
    stack.pop_back();
    const ObbNode& x = na[p.ia];
    const ObbNode& y = nb[p.ib];
    // Node pair: SAT in x's frame, the hinted axis first.
    ++counters.box_tests;
    const double slack =
        tol::kSatRelativeSlack * (x.box.half.sum() + y.box.half.sum() + 2 * p.T.lpNorm<1>()) +
        carried_slack;
    const SatAxis hint = separator.hint(p.ia, p.ib);
    const SatAxis axis = sat_separating_axis_in_a(p.R, p.T, x.box.half, y.box.half, slack, hint);
    if (axis != kSatNoAxis) {
      separator.record(p.ia, p.ib, axis, hint, counters);
      continue;
    }
    // Two leaves: test their triangles.
    if (x.is_leaf() && y.is_leaf()) {
      if (test_leaves(a, b, x, y, b_in_a, mode, counters, pairs, tri_test, result)) return result;
      continue;
    }
    // Otherwise split the larger node (a leaf is never split), carrying the frame down.
    const bool split_a = !x.is_leaf() && (y.is_leaf() || x.box.half.sum() >= y.box.half.sum());
    if (split_a) {
      for (const std::int32_t c : {x.right, p.ia + 1}) {
        const NodeFrame& f = fa[static_cast<std::size_t>(c)];
        stack.push_back({c, p.ib, f.R.transpose() * p.R, f.R.transpose() * (p.T - f.t)});
      }
    } else {
      for (const std::int32_t c : {y.right, p.ib + 1}) {
        const NodeFrame& f = fb[static_cast<std::size_t>(c)];
        stack.push_back({p.ia, c, p.R * f.R, p.R * f.t + p.T});
      }
    }
  }
  return result;
}

}  // namespace detail

// Descends both trees from their roots. Tree B is placed in A's frame by `b_in_a`
// (x_A = R x_B + t): its boxes through transform(), its triangles through apply_pose() (the
// doubles the exact ground truth sees too). At each node pair the separator may prove the boxes
// disjoint; otherwise the larger node (by sum of half-extents) is split; at two leaves every
// triangle pair is tested. `pairs`, if given, receives the intersecting pairs as input face
// indices (unsorted). Separator: bool disjoint(const Obb& a, const Obb& b_in_a, int32 node_a,
// int32 node_b, QueryCounters&), which must never claim "disjoint" for overlapping boxes. Axis
// separators (detail::IsAxisSeparator) take the RAPID-style descent of detail::collide_carried,
// which visits the same node pairs in the same order.
template <class Separator, class TriTest = FilteredTriTest>
QueryResult collide(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryMode mode,
                    Separator& separator, QueryCounters& counters,
                    std::vector<TrianglePair>* pairs = nullptr, TriTest tri_test = TriTest{}) {
  QueryResult result;
  if (a.nodes().empty() || b.nodes().empty()) return result;
  if constexpr (detail::IsAxisSeparator<Separator>::value) {
    return detail::collide_carried(a, b, b_in_a, mode, separator, counters, pairs, tri_test);
  }
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
      if (detail::test_leaves(a, b, x, y, b_in_a, mode, counters, pairs, tri_test, result)) {
        return result;
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
