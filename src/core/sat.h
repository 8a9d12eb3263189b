// The separating axis test between two oriented boxes (paper eq. 4).
#pragma once

#include "core/obb.h"

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

inline bool sat_disjoint(const Obb& a, const Obb& b) {
  return sat_separating_axis(a, b) != kSatNoAxis;
}

}  // namespace graspcd
