// MuJoCo placements (d->geom_xpos, row-major d->geom_xmat) as graspcd poses, and the check for
// numbers MuJoCo calls bad.
#pragma once

#include <mujoco/mujoco.h>

#include "graspcd/core/geometry.h"

namespace graspcd::mujoco {

// A row-major 3x3 of MuJoCo as an Eigen matrix.
Mat3 from_row_major(const mjtNum* x);
// d->geom_xpos of geom `g`.
Vec3 geom_position(const mjData* d, int g);

// True when geom_xpos or geom_xmat of geom `g` in `d` holds a number MuJoCo calls bad
// (mju_isBad: NaN, or |x| > mjMAXVAL = 1e10, which covers the infinities).
bool bad_geom_placement(const mjData* d, int g);

// geom2 placed in geom1's frame from d->geom_xpos / d->geom_xmat (row-major):
// R = R1^T R2, t = R1^T (p2 - p1), so that x_1 = R x_2 + t.
Pose relative_pose(const mjData* d, int g1, int g2);

}  // namespace graspcd::mujoco
