// The perceptron box separator (paper sections 4-5): Rosenblatt's rule learns a plane between the
// 8 corners of box A (class 1) and the 8 corners of box B (class 0).
#pragma once

#include "graspcd/core/obb.h"
#include "graspcd/core/tolerances.h"

namespace graspcd {

// The coordinates the perceptron learns in.
enum class PerceptronFrame {
  kDisplaced,  // the paper's: origin moved to the midpoint of the two box centres (section 5)
  kOriginal,   // no displacement: the frame the boxes are given in (to measure what section 5 buys)
  kScaled,     // beyond the paper: displaced, then divided by the largest corner coordinate, so
               // the bias input 1 is comparable to the corner coordinates
};

struct PerceptronOptions {
  int cap = tol::kPerceptronDefaultCap;  // at most this many passes over the 16 corners (>= 1)
  PerceptronFrame frame = PerceptronFrame::kDisplaced;
};

// A plane {x : w.x + d = 0} in the boxes' frame; A's side is w.x + d >= 0.
struct SeparatingPlane {
  Vec3 w = Vec3::Zero();
  double d = 0.0;
};

struct PerceptronResult {
  bool disjoint = false;   // proven: converged, and every corner clears the plane by its margin
  bool converged = false;  // a pass over the 16 corners changed nothing, within the cap
  int passes = 0;          // passes made; the final pass without a change counts
  int updates = 0;         // weight changes (Rosenblatt updates)
  SeparatingPlane plane;   // the last plane, in the boxes' frame
};

// Rosenblatt 1958 as the paper's section 5 and docs/design.md fix it: weights start at zero (or at
// `start`, a plane in the boxes' frame: the warm start of temporal coherence); inputs are A's 8
// corners (class 1) then B's 8 (class 0), each in the order of obb_corners; output O = 1 when
// w.x + d >= 0; on a wrong output w += (D - O) x and d += (D - O). It stops after a pass without a
// change or after options.cap passes. A converged plane proves the closed boxes disjoint only when
// every corner clears it by more than its rounding and positional error (tolerances.h); overlapping
// or touching boxes never converge (a common point would lie on both sides).
PerceptronResult perceptron_separate(const Obb& a, const Obb& b, const PerceptronOptions& options,
                                     const SeparatingPlane* start = nullptr);

}  // namespace graspcd
