#include "graspcd/core/tree_query.h"

#include <cmath>
#include <vector>

#include "graspcd/core/sat.h"

namespace graspcd {

QueryCounters& QueryCounters::operator+=(const QueryCounters& o) {
  box_tests += o.box_tests;
  perceptron_passes += o.perceptron_passes;
  sat_fallbacks += o.sat_fallbacks;
  cache_hits += o.cache_hits;
  front_skips += o.front_skips;
  tri_tests += o.tri_tests;
  tri_pairs += o.tri_pairs;
  return *this;
}

bool front_applies(const QueryFront& front, const ObbTree& b, const Pose& b_in_a) {
  if (!front.valid || b.nodes().empty()) return false;
  // The relative rotation's angle: trace(R0^T R) = 1 + 2 cos(angle).
  const double trace = (front.pose.R.transpose() * b_in_a.R).trace();
  if (!(trace >= 1 + 2 * std::cos(tol::kFrontMaxRotation))) return false;
  const Obb& root = b.root().box;
  const Vec3 moved =
      (b_in_a.R * root.center + b_in_a.t) - (front.pose.R * root.center + front.pose.t);
  return moved.norm() <= tol::kFrontMaxShift * 2 * root.half.norm();
}

double front_motion(const QueryFront& front, const ObbTree& b, const Pose& b_in_a) {
  if (b.nodes().empty()) return 0;
  const Vec3& c = b.root().box.center;
  const Mat3 dR = b_in_a.R - front.pose.R;
  const double moved = (dR * c + (b_in_a.t - front.pose.t)).norm() + dR.norm() * b.reach();
  // The rounding of the lines above: relative to the magnitudes that entered them.
  const double scale = c.lpNorm<1>() + b.reach() + b_in_a.t.lpNorm<1>() + front.pose.t.lpNorm<1>();
  return moved * (1 + tol::kFrontMotionRelative) + tol::kFrontMotionRelative * scale;
}

// A bottom-up reduction over the front in its depth-first order (the descent pushes a split's
// second child below its first, so the two children of a parent are adjacent when both stopped):
// a stack of kept pairs, whose top two merge into their parent while they are disjoint siblings
// and SAT proves the parent disjoint; the generalised front tracking of Ehmann and Lin 2001,
// pulled up lazily.
void pull_up_front(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, QueryFront& front,
                   QueryCounters& counters) {
  const auto& na = a.nodes();
  const auto& nb = b.nodes();
  // The parent pair of two front pairs that split it, first child then second; false otherwise.
  const auto parent_of = [&](const NodePair& x, const NodePair& y, NodePair& parent) {
    if (x.b == y.b && x.a > 0 && !na[static_cast<std::size_t>(x.a - 1)].is_leaf() &&
        na[static_cast<std::size_t>(x.a - 1)].right == y.a) {
      parent = {x.a - 1, x.b, true, 0.0};
      return true;
    }
    if (x.a == y.a && x.b > 0 && !nb[static_cast<std::size_t>(x.b - 1)].is_leaf() &&
        nb[static_cast<std::size_t>(x.b - 1)].right == y.b) {
      parent = {x.a, x.b - 1, true, 0.0};
      return true;
    }
    return false;
  };
  std::vector<NodePair>& kept = front.pairs;
  if (kept.empty()) return;
  const double carried = detail::carried_slack(a, b, b_in_a);
  std::size_t top = 0;  // kept[0, top) is the reduced front so far
  for (std::size_t i = 0; i < kept.size(); ++i) {
    kept[top++] = kept[i];
    NodePair parent;
    while (top >= 2 && kept[top - 2].disjoint && kept[top - 1].disjoint &&
           parent_of(kept[top - 2], kept[top - 1], parent)) {
      ++counters.box_tests;
      const Obb& x = na[static_cast<std::size_t>(parent.a)].box;
      const Obb& y = nb[static_cast<std::size_t>(parent.b)].box;
      const detail::FramedPair f = detail::direct_frame(a, b, b_in_a, parent.a, parent.b);
      const double slack = detail::node_slack(x, y, f.T, carried);
      const SatAxis axis = sat_separating_axis_in_a(f.R, f.T, x.half, y.half, slack);
      if (axis == kSatNoAxis) break;
      parent.gap = sat_axis_gap(f.R, f.R.cwiseAbs(), f.T, x.half, y.half, slack, axis);
      top -= 2;
      kept[top++] = parent;
    }
  }
  kept.resize(top);
}

}  // namespace graspcd
