// Oriented bounding boxes: the box type, its corners, and the two fits.
#pragma once

#include <array>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd {

// The box c + R diag(e) u, |u|_inf <= 1. The columns of `axes` are the box axes in the world (or
// parent) frame; `half` holds the non-negative half-extents (zero allowed: a flat box).
struct Obb {
  Vec3 center = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  Vec3 half = Vec3::Zero();
};

// The 8 corners in the order of sign bits, x fastest: corner k = c + sum_i s_i e_i axis_i with
// s_i = +1 if bit i of k is set, else -1.
std::array<Vec3, 8> obb_corners(const Obb& box);

// The box placed by a pose: centre R c + t, axes R axes, same half-extents.
Obb transform(const Pose& pose, const Obb& box);

// True when p lies in the box grown by `slack` metres on every side (computed in floating point).
bool obb_contains(const Obb& box, const Vec3& p, double slack = 0.0);

enum class ObbFit {
  kCovariance,  // paper eq. (1)-(3): mean and covariance of the triangle vertices
  kHullArea,    // Gottschalk, Lin, Manocha 1996 (OBBTree): area-weighted covariance of the hull
};

// Fits a box to the given triangles (at least one). The frame is orthonormal and right-handed;
// the half-extents come from the extreme projections of the vertices, padded by tol::kObbFitPad so
// that every vertex lies inside. Degenerate input (one triangle, collinear or coplanar or repeated
// points) still gives an orthonormal right-handed frame and non-negative extents. kHullArea falls
// back to kCovariance when the points have no 3D hull (flat or collinear). No triangles: the
// default Obb (a point at the origin). Units: those of the input (metres in graspcd). No throw.
Obb fit_obb(const std::vector<Triangle>& triangles, ObbFit method = ObbFit::kCovariance);

}  // namespace graspcd
