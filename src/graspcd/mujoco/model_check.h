// A compiled model's numbers, checked once before graspcd serves it (docs/bad-input.md).
// MuJoCo 2.2 compiles a NaN written in an MJCF attribute with only a warning; a model that holds
// one would make every pose of the geom below it meaningless from the first step.
#pragma once

#include <mujoco/mujoco.h>

#include <string>

namespace graspcd::mujoco {

// "" when every real number of `m` is finite: every mjtNum and float array of mjModel (mjxmacro.h,
// MJMODEL_POINTERS: positions, orientations, sizes, masses, mesh vertices, ...) and the physics
// options. Otherwise one line naming the first non-finite number: the array, the object it
// belongs to (by id and name) and the value, e.g.
//   "the model holds a non-finite number: geom_pos of geom 5 'object' is nan".
std::string find_non_finite(const mjModel* m);

}  // namespace graspcd::mujoco
