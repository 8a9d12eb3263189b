#include "graspcd/core/sat.h"

#include <cmath>

#include "graspcd/core/tolerances.h"

namespace graspcd {

// Gottschalk, Lin, Manocha 1996 / Ericson 4.4.1, eq. (4) of the paper on the 15 candidate axes.
SatAxis sat_separating_axis(const Obb& a, const Obb& b, SatAxis first_axis) {
  // B in A's frame.
  const Mat3 R = a.axes.transpose() * b.axes;
  const Vec3 d = b.center - a.center;
  const Vec3 T = a.axes.transpose() * d;
  // Slack: relative to the boxes' size and distance, plus the rounding of far-away centres.
  const double slack = tol::kSatRelativeSlack * (a.half.sum() + b.half.sum() + d.lpNorm<1>()) +
                       tol::kSatRoundoffFactor * (a.center.lpNorm<1>() + b.center.lpNorm<1>());
  // The hinted axis first (temporal coherence), then A's faces, B's faces, the edge pairs.
  return sat_separating_axis_in_a(R, T, a.half, b.half, slack, first_axis);
}

}  // namespace graspcd
