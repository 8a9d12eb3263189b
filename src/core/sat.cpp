#include "core/sat.h"

#include <cmath>

#include "core/tolerances.h"

namespace graspcd {
namespace {

// The boxes in A's frame: R = A^T B, t = A^T (cB - cA), |R|, and the slack (tolerances.h).
struct SatFrame {
  Mat3 R, absR;
  Vec3 t;
  Vec3 a, b;  // half-extents
  double slack;
};

// Gap test on one of the 15 axes (Ericson, Real-Time Collision Detection, 4.4.1): separated when
// |t . L| > r_A + r_B + slack. The cross axis A_i x B_j uses i1, i2 = the other two indices of A
// in cyclic order and j1, j2 those of B.
bool separates(const SatFrame& f, SatAxis axis) {
  double dist, ra, rb;
  if (axis <= 3) {  // L = A_i
    const int i = axis - 1;
    dist = std::fabs(f.t[i]);
    ra = f.a[i];
    rb = f.b.dot(f.absR.row(i));
  } else if (axis <= 6) {  // L = B_j
    const int j = axis - 4;
    dist = std::fabs(f.t.dot(f.R.col(j)));
    ra = f.a.dot(f.absR.col(j));
    rb = f.b[j];
  } else {  // L = A_i x B_j
    const int i = (axis - 7) / 3, j = (axis - 7) % 3;
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    dist = std::fabs(f.t[i2] * f.R(i1, j) - f.t[i1] * f.R(i2, j));
    ra = f.a[i1] * f.absR(i2, j) + f.a[i2] * f.absR(i1, j);
    rb = f.b[j1] * f.absR(i, j2) + f.b[j2] * f.absR(i, j1);
  }
  return dist > ra + rb + f.slack;
}

}  // namespace

// Gottschalk, Lin, Manocha 1996 / Ericson 4.4.1, eq. (4) of the paper on the 15 candidate axes.
SatAxis sat_separating_axis(const Obb& a, const Obb& b, SatAxis first_axis) {
  SatFrame f;
  f.R = a.axes.transpose() * b.axes;
  f.absR = f.R.cwiseAbs();
  const Vec3 d = b.center - a.center;
  f.t = a.axes.transpose() * d;
  f.a = a.half;
  f.b = b.half;
  // Slack: relative to the boxes' size and distance, plus the rounding of far-away centres.
  f.slack = tol::kSatRelativeSlack * (a.half.sum() + b.half.sum() + d.lpNorm<1>()) +
            tol::kSatRoundoffFactor * (a.center.lpNorm<1>() + b.center.lpNorm<1>());
  // The hinted axis first (temporal coherence), then A's faces, B's faces, the edge pairs.
  if (first_axis != kSatNoAxis && separates(f, first_axis)) return first_axis;
  for (SatAxis axis = 1; axis <= 15; ++axis) {
    if (axis != first_axis && separates(f, axis)) return axis;
  }
  return kSatNoAxis;
}

}  // namespace graspcd
