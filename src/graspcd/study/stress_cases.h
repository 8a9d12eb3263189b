// The generators of the stress suite's cases (stress.h), private to it: the class ids, and one
// seeded pair of boxes or triangles of a class per call, every draw from the class's stream.
#pragma once

#include "graspcd/study/stress_pairs.h"
#include "graspcd/support/seeded.h"

namespace graspcd::study::stress_cases {

// The project's one seeded generator (graspcd/support/seeded.h): its draws are sequenced and
// its distributions written out, so the cases are the same on every compiler and standard library.
using seeded::chance;
using seeded::kPi;
using seeded::log_uniform;
using seeded::normal;
using seeded::random_rotation;
using seeded::random_sign;
using seeded::random_unit;
using seeded::Rng;
using seeded::rotation_about;
using seeded::uniform;
using seeded::uniform01;
using seeded::uniform_int;

enum ClassId {
  kBoxScale,
  kBoxFar,
  kBoxParallelFaces,
  kBoxParallelEdges,
  kBoxSliver,
  kBoxGap,
  kTriScale,
  kTriFar,
  kTriParallelEdges,
  kTriCoplanar,
  kTriNearCoplanar,
  kTriSliver,
  kTriDegenerate,
  kTriGap,
  kClassCount
};

// A box pair of the box class `id` (throws std::logic_error for another class).
BoxPairCase make_box_case(ClassId id, Rng& rng);

// A triangle pair of the triangle class `id` (throws std::logic_error for another class).
TrianglePairCase make_triangle_case(ClassId id, Rng& rng);

// The signed gap of a case, as a fraction of its size: touching (0) one time in eight, else
// +-10^[log10 lo, log10 hi], each sign half the time.
inline double signed_gap(Rng& rng, double lo, double hi) {
  if (chance(rng, 0.125)) return 0.0;
  const double sign = random_sign(rng);
  return sign * log_uniform(rng, lo, hi);
}

// A signed angle, log-uniform in magnitude.
inline double signed_log_uniform(Rng& rng, double lo, double hi) {
  const double sign = random_sign(rng);
  return sign * log_uniform(rng, lo, hi);
}

}  // namespace graspcd::study::stress_cases
