// The separating axis test between two oriented boxes (paper eq. 4).
#pragma once

#include <cmath>

#include "graspcd/core/avx2.h"
#include "graspcd/core/obb.h"

namespace graspcd {

// Which of the 15 candidate axes separated two boxes: 0 means none did (the boxes may overlap);
// 1-3 are A's axes, 4-6 B's axes, 7-15 the cross products A_i x B_j with index 7 + 3 i + j.
using SatAxis = int;
inline constexpr SatAxis kSatNoAxis = 0;

// Gottschalk, Lin, Manocha 1996 (OBBTree) as written in Ericson, Real-Time Collision Detection,
// 4.4.1: both boxes in one frame, 15 axes with early exit. Conservative: returns an axis only when
// the gap on it exceeds the slack of tolerances.h, so "separated" is never wrong; boxes closer than
// the slack are answered "may overlap". `first_axis` (if not kSatNoAxis) is tried before the
// others, for temporal coherence.
SatAxis sat_separating_axis(const Obb& a, const Obb& b, SatAxis first_axis = kSatNoAxis);

// The gap on one axis, B given in A's frame (R = A^T B, T = A^T (cB - cA), absR = |R|):
// |T . L| - (r_A + r_B + slack) (Ericson, Real-Time Collision Detection, 4.4.1), positive exactly
// when the axis separates (sat_axis_separates). The cross axis A_i x B_j uses i1, i2 = the other
// two indices of A in cyclic order and j1, j2 those of B. With the slack covering the rounding of
// R and T (tolerances.h), a positive gap is a lower bound on the distance between the boxes: L is
// unit for the face axes and shorter for the cross axes (|A_i x B_j| <= 1), so the gap along the
// unnormalised L underestimates the gap along L / |L|, which the distance bounds.
inline double sat_axis_gap(const Mat3& R, const Mat3& absR, const Vec3& T, const Vec3& a,
                           const Vec3& b, double slack, SatAxis axis) {
  double dist, ra, rb;
  if (axis <= 3) {  // L = A_i
    const int i = axis - 1;
    dist = std::fabs(T[i]);
    ra = a[i];
    rb = b[0] * absR(i, 0) + b[1] * absR(i, 1) + b[2] * absR(i, 2);
  } else if (axis <= 6) {  // L = B_j
    const int j = axis - 4;
    dist = std::fabs(T[0] * R(0, j) + T[1] * R(1, j) + T[2] * R(2, j));
    ra = a[0] * absR(0, j) + a[1] * absR(1, j) + a[2] * absR(2, j);
    rb = b[j];
  } else {  // L = A_i x B_j
    const int i = (axis - 7) / 3, j = (axis - 7) % 3;
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    dist = std::fabs(T[i2] * R(i1, j) - T[i1] * R(i2, j));
    ra = a[i1] * absR(i2, j) + a[i2] * absR(i1, j);
    rb = b[j1] * absR(i, j2) + b[j2] * absR(i, j1);
  }
  // dist > bound exactly when dist - bound > 0 (a difference of two distinct finite doubles never
  // rounds to zero), so this agrees with sat_separating_axis_in_a's comparisons bit for bit.
  return dist - (ra + rb + slack);
}

// The gap test on one axis: separated when the gap is positive (sat_axis_gap).
inline bool sat_axis_separates(const Mat3& R, const Mat3& absR, const Vec3& T, const Vec3& a,
                               const Vec3& b, double slack, SatAxis axis) {
  return sat_axis_gap(R, absR, T, a, b, slack, axis) > 0;
}

// The 15-axis test of sat_separating_axis_in_a in scalar code, no hint, given |R|.
[[gnu::always_inline]] inline SatAxis sat_separating_axis_in_a_scalar(const Mat3& R,
                                                                      const Mat3& absR,
                                                                      const Vec3& T, const Vec3& a,
                                                                      const Vec3& b, double slack) {
  // The six face axes are all tested and their answers gathered in a bit mask, then the nine
  // edge axes likewise: two branches instead of up to fifteen hard-to-predict early exits. The
  // lowest set bit is the first separating axis in the order 1, ..., 15.
  unsigned mask = 0;
  // Test axes L = A_0, A_1, A_2.
  for (int i = 0; i < 3; ++i) {
    const double rb = b[0] * absR(i, 0) + b[1] * absR(i, 1) + b[2] * absR(i, 2);
    mask |= static_cast<unsigned>(std::fabs(T[i]) > a[i] + rb + slack) << i;
  }
  // Test axes L = B_0, B_1, B_2.
  for (int j = 0; j < 3; ++j) {
    const double ra = a[0] * absR(0, j) + a[1] * absR(1, j) + a[2] * absR(2, j);
    const double dist = std::fabs(T[0] * R(0, j) + T[1] * R(1, j) + T[2] * R(2, j));
    mask |= static_cast<unsigned>(dist > ra + b[j] + slack) << (3 + j);
  }
  if (mask != 0) return 1 + __builtin_ctz(mask);
  // Test axes L = A_i x B_j.
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double dist = std::fabs(T[i2] * R(i1, j) - T[i1] * R(i2, j));
      const double ra = a[i1] * absR(i2, j) + a[i2] * absR(i1, j);
      const double rb = b[j1] * absR(i, j2) + b[j2] * absR(i, j1);
      mask |= static_cast<unsigned>(dist > ra + rb + slack) << (3 * i + j);
    }
  }
  if (mask != 0) return 7 + __builtin_ctz(mask);
  return kSatNoAxis;
}

// The 15-axis test on B given in A's frame, RAPID's form (Gottschalk, Lin, Manocha 1996;
// Ericson 4.4.1): B's axes are the columns of R = A^T B, its centre is T = A^T (cB - cA), `a` and
// `b` the half-extents. No product of frames is formed here, so a caller that carries (R, T) down
// two trees (tree_query.h) pays 15 gap tests per node pair. The slack (metres, tolerances.h) must
// cover the rounding of R and T as the caller computed them. `first_axis` (if not kSatNoAxis) is
// tried first; the others follow in the order 1, 2, ..., 15, so the result is the same axis
// sat_separating_axis reports. The others go to the AVX2 kernel when it is on (avx2.h, use_avx2),
// to the scalar test otherwise: the same answer. (A hint that did not separate is tested again in
// its place, which cannot change the answer.) Always inlined, so that in the tree descent the
// constant hint of SatSeparator folds away.
[[gnu::always_inline]] inline SatAxis sat_separating_axis_in_a(const Mat3& R, const Vec3& T,
                                                               const Vec3& a, const Vec3& b,
                                                               double slack,
                                                               SatAxis first_axis = kSatNoAxis) {
  if (first_axis != kSatNoAxis && sat_axis_separates(R, R.cwiseAbs(), T, a, b, slack, first_axis)) {
    return first_axis;
  }
  if (detail::avx2_active()) {
    return sat_separating_axis_in_a_avx2(R.data(), T.data(), a.data(), b.data(), slack);
  }
  return sat_separating_axis_in_a_scalar(R, R.cwiseAbs(), T, a, b, slack);
}

inline bool sat_disjoint(const Obb& a, const Obb& b) {
  return sat_separating_axis(a, b) != kSatNoAxis;
}

}  // namespace graspcd
