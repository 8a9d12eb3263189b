// Tree-against-tree collision query: a separator at the node pairs, a triangle test at the leaves.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
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
  std::uint64_t front_skips = 0;        // front pairs still apart by their gap (collide_coherent)
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

// A node pair of the two trees: indices into A's and B's nodes(). On a front, `disjoint` says
// whether the descent stopped there on a box test (true) or tested its two leaves (false), and
// `gap` (metres) is a lower bound, at the front's pose, on the distance between what the pair
// holds, 0 when none is known: for a disjoint pair between its two boxes (SAT's gap on the
// separating axis, sat_axis_gap); for two leaves whose triangle pairs were all rejected by a plane
// (Moller's eq. 6-7) between their triangles (the least of tri_tri_intersect's gaps).
struct NodePair {
  std::int32_t a = 0;
  std::int32_t b = 0;
  bool disjoint = false;
  double gap = 0;
};

// The front of an all-contacts query (collide_coherent): the node pairs where its descent stopped,
// either proven disjoint or two leaves whose triangles were tested. They cover every leaf pair of
// the two trees exactly once, whatever the pose, so a descent restarted from them finds every
// intersecting triangle pair a descent from the roots finds (the box tests never claim "disjoint"
// for overlapping boxes, and the triangle test is exact): the same set, only the work differs.
// The pairs' gaps hold at `pose` only: a front moved to another pose must have them set to 0.
// It belongs to one pair of trees; hand it to no other.
struct QueryFront {
  std::vector<NodePair> pairs;
  Pose pose;                         // B in A when it was recorded (where the gaps hold)
  std::uint64_t root_box_tests = 0;  // box tests of the last descent from the roots
  std::uint32_t queries = 0;         // queries that restarted from it (pull-up every few)
  bool valid = false;                // false: the next query descends from the roots
  bool restarted = false;            // the last query restarted from the front
  void reset() {
    pairs.clear();
    valid = false;
  }
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
// With a gap (tritri.h), the tree query can keep a leaf pair whose triangles were far apart on a
// front (collide_coherent).
// Given A's triangle with its plane (ObbTree::planes()), it takes the plane instead of computing
// it: the same answer and gap.
struct FilteredTriTest {
  bool operator()(const Triangle& a, const Triangle& b) const { return tri_tri_intersect(a, b); }
  bool operator()(const Triangle& a, const Triangle& b, double& gap) const {
    return tri_tri_intersect(a, b, gap);
  }
  bool operator()(const Triangle& a, const TrianglePlane& pa, const Triangle& b) const {
    return tri_tri_intersect(a, pa, b);
  }
  bool operator()(const Triangle& a, const TrianglePlane& pa, const Triangle& b,
                  double& gap) const {
    return tri_tri_intersect(a, pa, b, gap);
  }
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

// The descent's stack of node pairs, taken from a per-thread pool and returned when the lease
// ends: a query allocates nothing once its thread has run one as deep, which matters for the
// many small queries of a simulation (a near miss costs a dozen box tests). Each lease takes its
// own stack, so a query run from inside another (a TriTest that queries) keeps them apart; the
// pool is a deque, whose elements stay where they are as it grows.
class DescentStack {
 public:
  DescentStack() : level_(depth()) {
    std::deque<std::vector<FramedPair>>& p = pool();
    if (p.size() <= level_) p.emplace_back().reserve(64);
    stack_ = &p[level_];
    stack_->clear();
    ++depth();  // last: a constructor that throws takes no level
  }
  ~DescentStack() { --depth(); }
  DescentStack(const DescentStack&) = delete;
  DescentStack& operator=(const DescentStack&) = delete;
  std::vector<FramedPair>& operator*() { return *stack_; }

 private:
  static std::size_t& depth() {
    thread_local std::size_t d = 0;
    return d;
  }
  static std::deque<std::vector<FramedPair>>& pool() {
    thread_local std::deque<std::vector<FramedPair>> p;
    return p;
  }
  std::size_t level_;
  std::vector<FramedPair>* stack_;
};

// The absolute part of the descent's SAT slack (tolerances.h, kSatCarriedRoundoffFactor): the
// rounding carried down both trees, relative to the root pair's size S at `b_in_a`.
inline double carried_slack(const ObbTree& a, const ObbTree& b, const Pose& b_in_a) {
  const Obb& a0 = a.nodes()[0].box;
  const Obb& b0 = b.nodes()[0].box;
  const Vec3 cb0 = b_in_a.R * b0.center + b_in_a.t;
  const double size = 2 * (a0.center.lpNorm<1>() + a0.half.sum() + cb0.lpNorm<1>() + b0.half.sum());
  return tol::kSatCarriedRoundoffFactor * (a.depth() + b.depth() + 2) * size;
}

// B's node ib in A's node ia's frame, formed directly from the two boxes (as the root pair's is).
inline FramedPair direct_frame(const ObbTree& a, const ObbTree& b, const Pose& b_in_a,
                               std::int32_t ia, std::int32_t ib) {
  const Obb& x = a.nodes()[static_cast<std::size_t>(ia)].box;
  const Obb& y = b.nodes()[static_cast<std::size_t>(ib)].box;
  return {ia, ib, x.axes.transpose() * (b_in_a.R * y.axes),
          x.axes.transpose() * ((b_in_a.R * y.center + b_in_a.t) - x.center)};
}

// The SAT slack at a node pair with frame T (tolerances.h): relative to the boxes, plus `carried`.
inline double node_slack(const Obb& x, const Obb& y, const Vec3& T, double carried) {
  return tol::kSatRelativeSlack * (x.half.sum() + y.half.sum() + 2 * T.lpNorm<1>()) + carried;
}

// Triangle tests that also give a gap when they reject (FilteredTriTest).
template <class T, class = void>
struct HasGapTest : std::false_type {};
template <class T>
struct HasGapTest<T, std::void_t<decltype(std::declval<T&>()(
                         std::declval<const Triangle&>(), std::declval<const Triangle&>(),
                         std::declval<double&>()))>> : std::true_type {};

// apply_pose on a triangle (geometry.h), by the AVX2 kernel where it is on (avx2.h): the same
// doubles bit for bit.
static_assert(sizeof(Triangle) == 9 * sizeof(double), "a triangle is nine contiguous doubles");
inline Triangle posed_triangle(const Pose& pose, const Triangle& t) {
  if (!avx2_active()) return apply_pose(pose, t);
  Triangle out;
  apply_pose_avx2(pose.R.data(), pose.t.data(), t.v[0].data(), out.v[0].data());
  return out;
}

// Triangle tests that take A's triangle with its plane (FilteredTriTest).
template <class T, class = void>
struct HasPlaneTest : std::false_type {};
template <class T>
struct HasPlaneTest<T, std::void_t<decltype(std::declval<T&>()(
                           std::declval<const Triangle&>(), std::declval<const TrianglePlane&>(),
                           std::declval<const Triangle&>()))>> : std::true_type {};

// The leaves of a node pair: every triangle pair, B's through apply_pose (the doubles the exact
// ground truth sees too; posed_triangle). True when the query is over (first contact found).
// `gap`, when given, receives the least of the pairs' gaps (tritri.h) when the test gives gaps and
// no pair intersects, else 0.
template <class TriTest>
bool test_leaves(const ObbTree& a, const ObbTree& b, const ObbNode& x, const ObbNode& y,
                 const Pose& b_in_a, QueryMode mode, QueryCounters& counters,
                 std::vector<TrianglePair>* pairs, TriTest& tri_test, QueryResult& result,
                 double* gap = nullptr) {
  constexpr bool kGaps = HasGapTest<TriTest>::value;
  constexpr bool kPlanes = HasPlaneTest<TriTest>::value;
  double least = std::numeric_limits<double>::infinity();
  if (gap) *gap = 0;
  for (std::int32_t j = y.first; j < y.first + y.count; ++j) {
    const Triangle tb = posed_triangle(b_in_a, b.triangles()[j]);
    for (std::int32_t i = x.first; i < x.first + x.count; ++i) {
      ++counters.tri_tests;
      bool hit;
      if constexpr (kGaps && kPlanes) {
        if (gap) {
          double g = 0;
          hit = tri_test(a.triangles()[i], a.planes()[i], tb, g);
          least = std::min(least, g);
        } else {
          hit = tri_test(a.triangles()[i], a.planes()[i], tb);
        }
      } else if constexpr (kGaps) {
        if (gap) {
          double g = 0;
          hit = tri_test(a.triangles()[i], tb, g);
          least = std::min(least, g);
        } else {
          hit = tri_test(a.triangles()[i], tb);
        }
      } else if constexpr (kPlanes) {
        hit = tri_test(a.triangles()[i], a.planes()[i], tb);
      } else {
        hit = tri_test(a.triangles()[i], tb);
      }
      if (!hit) continue;
      least = 0;
      ++counters.tri_pairs;
      ++result.pair_count;
      result.intersect = true;
      if (pairs) pairs->push_back({a.face_ids()[i], b.face_ids()[j]});
      if (mode == QueryMode::kFirstContact) return true;
    }
  }
  if (kGaps && gap && least > 0 && least < std::numeric_limits<double>::infinity()) *gap = least;
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
//
// `starts`, when given, replaces the root pair: the descent starts from each of these node pairs in
// turn, whose frames are formed directly from the boxes as the root's is (so the carried rounding
// below them is what the slack already covers). `stops`, when given, receives every node pair where
// the descent stopped (disjoint with SAT's gap, or two leaves tested): the front of QueryFront.
// `moved` (metres, or negative for none), given with both: a bound on how far any point of B's
// boxes moved since the starts' gaps were measured (front_motion). A disjoint start whose gap
// exceeds it is still disjoint, since the distance between two boxes shrinks by at most what
// either moved: it goes to `stops` untested with its gap less `moved` (motion-bounded front
// tracking: Ehmann and Lin 2001 keep a front of the bounding volume test tree, and conservative
// advancement, Mirtich 1996, bounds the approach of two bodies by their motion). So does a start of
// two leaves whose gap (their triangles' distance, test_leaves) exceeds it: no triangle pair of
// theirs can meet yet. A start of two leaves with no gap at all goes to the triangle test without
// the box test.
template <class Separator, class TriTest>
QueryResult collide_carried(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryMode mode,
                            Separator& separator, QueryCounters& counters,
                            std::vector<TrianglePair>* pairs, TriTest& tri_test,
                            const std::vector<NodePair>* starts = nullptr,
                            std::vector<NodePair>* stops = nullptr, double moved = -1) {
  QueryResult result;
  const auto& na = a.nodes();
  const auto& nb = b.nodes();
  const auto& fa = a.in_parent();
  const auto& fb = b.in_parent();
  // The absolute part of the slack.
  const double carried = carried_slack(a, b, b_in_a);
  DescentStack lease;
  std::vector<FramedPair>& stack = *lease;
  const auto push_direct = [&](std::int32_t ia, std::int32_t ib) {
    stack.push_back(direct_frame(a, b, b_in_a, ia, ib));
  };
  // Two leaves' triangles tested, their gap kept on the front; true when the query is over
  // (first contact found).
  const auto leaf_pair = [&](std::int32_t ia, std::int32_t ib, const ObbNode& x, const ObbNode& y) {
    double gap = 0;
    const bool over = test_leaves(a, b, x, y, b_in_a, mode, counters, pairs, tri_test, result,
                                  stops ? &gap : nullptr);
    if (stops) stops->push_back({ia, ib, false, gap});
    return over;
  };
  // The descent below what is on the stack; true when the query is over (first contact found).
  const auto descend_stack = [&]() {
    while (!stack.empty()) {
      const FramedPair p = stack.back();
      stack.pop_back();
      const ObbNode& x = na[p.ia];
      const ObbNode& y = nb[p.ib];
      // Node pair: SAT in x's frame, the hinted axis first.
      ++counters.box_tests;
      const double slack = node_slack(x.box, y.box, p.T, carried);
      const SatAxis hint = separator.hint(p.ia, p.ib);
      const SatAxis axis = sat_separating_axis_in_a(p.R, p.T, x.box.half, y.box.half, slack, hint);
      if (axis != kSatNoAxis) {
        separator.record(p.ia, p.ib, axis, hint, counters);
        if (stops) {
          const double gap =
              sat_axis_gap(p.R, p.R.cwiseAbs(), p.T, x.box.half, y.box.half, slack, axis);
          stops->push_back({p.ia, p.ib, true, gap});
        }
        continue;
      }
      // Two leaves: test their triangles (keeping their gap on the front).
      if (x.is_leaf() && y.is_leaf()) {
        if (leaf_pair(p.ia, p.ib, x, y)) return true;
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
    return false;
  };
  if (!starts) {
    push_direct(0, 0);
    descend_stack();
    return result;
  }
  // Each start in turn, with the descent below it: the depth-first order of a descent that pushed
  // them all at once.
  const bool skip = stops && moved >= 0;
  for (const NodePair& s : *starts) {
    if (skip && s.gap > moved) {
      ++counters.front_skips;
      stops->push_back({s.a, s.b, s.disjoint, s.gap - moved});
      continue;
    }
    const ObbNode& x = na[static_cast<std::size_t>(s.a)];
    const ObbNode& y = nb[static_cast<std::size_t>(s.b)];
    if (!s.disjoint && s.gap == 0 && x.is_leaf() && y.is_leaf()) {
      // Two leaves whose last triangle test found no positive plane gap (they met, or no plane
      // kept them apart): at a small motion their boxes mostly overlap again, so the box test is
      // skipped and the triangles are tested at once. Only speed: the triangle test is exact,
      // and the box test only ever spares it for triangles that cannot meet.
      if (leaf_pair(s.a, s.b, x, y)) return result;
      continue;
    }
    push_direct(s.a, s.b);
    if (descend_stack()) return result;
  }
  return result;
}

}  // namespace detail

namespace detail {

// The descent for every separator, from the roots or from `starts`, recording where it stopped in
// `stops` (see collide_carried).
template <class Separator, class TriTest>
QueryResult descend(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryMode mode,
                    Separator& separator, QueryCounters& counters, std::vector<TrianglePair>* pairs,
                    TriTest& tri_test, const std::vector<NodePair>* starts,
                    std::vector<NodePair>* stops, double moved = -1) {
  QueryResult result;
  if (a.nodes().empty() || b.nodes().empty()) return result;
  // A pose with a NaN or an infinity places no triangle anywhere: every triangle test says
  // "disjoint" (tritri.h), so the answer is known without a descent that no box test could prune.
  if (!b_in_a.R.allFinite() || !b_in_a.t.allFinite()) return result;
  if constexpr (IsAxisSeparator<Separator>::value) {
    return collide_carried(a, b, b_in_a, mode, separator, counters, pairs, tri_test, starts, stops,
                           moved);
  }
  const auto& na = a.nodes();
  const auto& nb = b.nodes();
  std::vector<std::pair<std::int32_t, std::int32_t>> stack;
  stack.reserve(64);
  if (starts) {
    for (auto it = starts->rbegin(); it != starts->rend(); ++it) stack.emplace_back(it->a, it->b);
  } else {
    stack.emplace_back(0, 0);
  }
  while (!stack.empty()) {
    const auto [ia, ib] = stack.back();
    stack.pop_back();
    const ObbNode& x = na[static_cast<std::size_t>(ia)];
    const ObbNode& y = nb[static_cast<std::size_t>(ib)];
    // Node pair: ask the separator.
    ++counters.box_tests;
    if (separator.disjoint(x.box, transform(b_in_a, y.box), ia, ib, counters)) {
      if (stops) stops->push_back({ia, ib, true, 0.0});
      continue;
    }
    // Two leaves: test their triangles.
    if (x.is_leaf() && y.is_leaf()) {
      if (stops) stops->push_back({ia, ib, false, 0.0});
      if (test_leaves(a, b, x, y, b_in_a, mode, counters, pairs, tri_test, result)) return result;
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

}  // namespace detail

// Descends both trees from their roots. Tree B is placed in A's frame by `b_in_a`
// (x_A = R x_B + t): its boxes through transform(), its triangles through apply_pose() (the
// doubles the exact ground truth sees too). A pose holding a NaN or an infinity intersects
// nothing (no descent runs). At each node pair the separator may prove the boxes
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
  return detail::descend(a, b, b_in_a, mode, separator, counters, pairs, tri_test, nullptr,
                         nullptr);
}

// True when a query at `b_in_a` should restart from `front` rather than from the roots: the front
// is valid and B moved little relative to A since it was recorded (a rotation of at most
// tol::kFrontMaxRotation radians and a displacement of B's root box centre of at most
// tol::kFrontMaxShift times B's root box size). Only a matter of speed: any front gives the same
// answer.
bool front_applies(const QueryFront& front, const ObbTree& b, const Pose& b_in_a);

// A bound (metres) on how far any point of any of B's node boxes moved relative to A between the
// front's pose and `b_in_a`: for the pose change (R0, t0) -> (R1, t1), a point x of B moves by
// |(R1 - R0) x + t1 - t0| <= |(R1 - R0) c + t1 - t0| + |R1 - R0|_F * ObbTree::reach() with c B's
// root box centre (the Frobenius norm bounds the spectral one), enlarged to cover its own rounding
// (tolerances.h, kFrontMotionRelative). Rigorous for any two poses, whatever happened between them.
double front_motion(const QueryFront& front, const ObbTree& b, const Pose& b_in_a);

// Pulls a front up where it went deeper than it needs now: two disjoint node pairs that split the
// same parent pair (adjacent in the front's depth-first order) are replaced by the parent when SAT
// (on the parent's frame formed directly, with the descent's slack: it never claims "disjoint" for
// overlapping boxes) proves the parent's boxes disjoint at `b_in_a`, repeatedly up the trees; the
// parent keeps SAT's gap on its separating axis, as a pair where the descent stopped does, so a
// restart can keep it untested while B moves less. The front still covers every leaf pair once.
// `b_in_a` must be the front's pose (where its gaps hold). Counts its box tests.
void pull_up_front(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryFront& front,
                   QueryCounters& counters);

// The all-contacts query with temporal coherence, after the front lists of FCL (Pan, Chitta,
// Manocha 2012), which follow Ehmann and Lin's "generalized front tracking" of the bounding volume
// test tree (Eurographics 2001): when front_applies, the descent restarts from the node pairs where
// the last one stopped (pairs above the front, nearly always "may overlap" again at a small
// motion, are not tested again), otherwise from the roots; either way `front` then holds where
// this descent stopped. A restarted descent does not test a front pair whose gap exceeds how far B
// moved since (front_motion): a disjoint pair's boxes, or a leaf pair's triangles, are still apart.
// Every tol::kFrontPullUpPeriod restarts the front is pulled up where the pairs moved apart
// (pull_up_front); when a restarted descent still costs more box tests than the last descent from
// the roots did, the front is dropped and the next query starts from the roots. The intersecting
// triangle pairs are exactly those of collide(..., kAllContacts, ...) at the same pose, as a set
// (the order may differ; sort them to compare). Returns collide's result.
template <class Separator, class TriTest = FilteredTriTest>
QueryResult collide_coherent(const ObbTree& a, const ObbTree& b, const Pose& b_in_a,
                             Separator& separator, QueryCounters& counters,
                             std::vector<TrianglePair>* pairs, QueryFront& front,
                             TriTest tri_test = TriTest{}) {
  thread_local std::vector<NodePair> stops;
  stops.clear();
  const bool restart = front_applies(front, b, b_in_a);
  front.restarted = restart;
  const std::uint64_t before = counters.box_tests;
  const QueryResult result = detail::descend(
      a, b, b_in_a, QueryMode::kAllContacts, separator, counters, pairs, tri_test,
      restart ? &front.pairs : nullptr, &stops, restart ? front_motion(front, b, b_in_a) : -1.0);
  const std::uint64_t cost = counters.box_tests - before;
  if (stops.empty()) {
    // No descent ran (an empty tree, or a non-finite pose): nothing to follow next time.
    front.reset();
    return result;
  }
  front.pairs.swap(stops);
  front.pose = b_in_a;
  front.valid = true;
  if (!restart) {
    front.root_box_tests = cost;
    front.queries = 0;
  } else if (cost > front.root_box_tests) {
    front.valid = false;  // the front has grown past what a fresh descent costs
  } else if (++front.queries % tol::kFrontPullUpPeriod == 0) {
    pull_up_front(a, b, b_in_a, front, counters);
  }
  return result;
}

}  // namespace graspcd
