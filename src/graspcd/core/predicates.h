// Exact geometric predicates on doubles: a floating-point filter with a proven error bound, and
// exact expansion arithmetic when the sign falls inside the bound.
//
// Source: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
// Predicates", Discrete & Computational Geometry 18(3), 1997. The filter constants are his
// (ccwerrboundA, o3derrboundA); the expansion routines (Two-Sum, Two-Product with Dekker's split,
// Grow-Expansion, Scale-Expansion) follow his Section 2. Written for this project.
//
// Exact for every coordinate that is 0 or of magnitude within [tol::kMinCoordinate,
// tol::kMaxCoordinate] (no intermediate underflow or overflow there). A NaN or infinite coordinate
// has no orientation: every predicate answers 0 for it at once (the exact variants too), so no
// expansion ever holds a NaN (whose sign and zero elimination mean nothing).
#pragma once

#include "graspcd/core/geometry.h"

namespace graspcd::predicates {

// Sign (-1, 0, +1) of det[b-a; c-a; d-a] = ((b-a) x (c-a)) . (d-a): positive when d lies on the
// side of plane abc that the normal (b-a) x (c-a) points to. Filtered, exact.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// The same sign, always computed with expansions (no filter). For tests and for the filter's
// own verification.
int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Sign of the z component of (b-a) x (c-a) after dropping coordinate `drop` (0, 1 or 2) of each
// point; the two kept coordinates keep their cyclic order (drop x -> (y,z), y -> (z,x), z ->
// (x,y)), so the sign equals the sign of component `drop` of the 3D cross product. Filtered, exact.
int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop);
int orient2d_exact(const Vec3& a, const Vec3& b, const Vec3& c, int drop);

// How many calls fell through the filter to exact arithmetic (per thread, since start or reset).
// For statistics and tests only.
struct FilterStats {
  std::uint64_t orient3d_exact_calls = 0;
  std::uint64_t orient2d_exact_calls = 0;
};
FilterStats& filter_stats();

}  // namespace graspcd::predicates
