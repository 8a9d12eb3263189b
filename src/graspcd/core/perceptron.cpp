#include "graspcd/core/perceptron.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace graspcd {

PerceptronResult perceptron_separate(const Obb& a, const Obb& b, const PerceptronOptions& options,
                                     const SeparatingPlane* start) {
  constexpr double kRoundoff = tol::kUnitRoundoff;
  // The learning frame: x_local = (x - origin) / scale.
  Vec3 origin = Vec3::Zero();
  if (options.frame != PerceptronFrame::kOriginal) origin = 0.5 * (a.center + b.center);
  std::array<Vec3, 16> x;
  const std::array<Vec3, 8> ca = obb_corners(Obb{a.center - origin, a.axes, a.half});
  const std::array<Vec3, 8> cb = obb_corners(Obb{b.center - origin, b.axes, b.half});
  std::copy(ca.begin(), ca.end(), x.begin());
  std::copy(cb.begin(), cb.end(), x.begin() + 8);
  double scale = 1.0;
  if (options.frame == PerceptronFrame::kScaled) {
    double extent = 0.0;
    for (const Vec3& p : x) extent = std::max(extent, p.cwiseAbs().maxCoeff());
    if (extent > 0.0) scale = extent;
    for (Vec3& p : x) p /= scale;
  }

  // Start plane, carried into the learning frame: w.(s x' + o) + d = (s w).x' + (d + w.o).
  Vec3 w = Vec3::Zero();
  double d = 0.0;
  if (start) {
    w = scale * start->w;
    d = start->d + start->w.dot(origin);
  }

  // Rosenblatt's rule, one pass = the 16 corners in order.
  PerceptronResult result;
  for (int pass = 1; pass <= options.cap; ++pass) {
    bool changed = false;
    for (int i = 0; i < 16; ++i) {
      const bool desired = i < 8;
      const bool output = w.dot(x[i]) + d >= 0.0;
      if (output == desired) continue;
      const double step = desired ? 1.0 : -1.0;
      w += step * x[i];
      d += step;
      changed = true;
      ++result.updates;
    }
    result.passes = pass;
    if (!changed) {
      result.converged = true;
      break;
    }
  }
  result.plane.w = w / scale;
  result.plane.d = d - result.plane.w.dot(origin);
  if (!result.converged) return result;

  // Proof: every corner strictly on its side by more than |w|_1 times the corners' positional
  // error (tolerances.h, scaled into the learning frame) plus the rounding of w.x + d (4 products
  // and 3 sums: 8u of the absolute terms covers it).
  const double position_error =
      tol::kPerceptronCornerFactor *
      (a.center.lpNorm<1>() + b.center.lpNorm<1>() + a.half.sum() + b.half.sum()) / scale;
  const double w1 = w.lpNorm<1>();
  for (int i = 0; i < 16; ++i) {
    const double f = w.dot(x[i]) + d;
    const double margin =
        w1 * position_error + 8 * kRoundoff * (w1 * x[i].cwiseAbs().maxCoeff() + std::fabs(d));
    if (i < 8 ? !(f > margin) : !(f < -margin)) return result;
  }
  result.disjoint = true;
  return result;
}

}  // namespace graspcd
