// The true surfaces of a scene's geoms as the grasp's measures see them (true_penetration.h,
// true_touch.h): a geom's triangles in its own frame, whether two geoms may collide, and how a
// geom is named in a message.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd::grasp {

// The geom's triangles in its frame: a mesh's faces (MuJoCo's float vertices), a primitive's
// tessellation (the MuJoCo layer's, primitives.h); empty for planes, height fields and anything
// else.
std::vector<Triangle> geom_triangles(const mjModel* m, int g);

// Whether the contype/conaffinity filter lets geoms a and b collide.
bool may_collide(const mjModel* m, int a, int b);

// "geom 'NAME'", or for an unnamed geom "geom N (mesh 'M' of body 'B')" (its type for a
// primitive), as the start check names geoms.
std::string geom_label(const mjModel* m, int g);

}  // namespace graspcd::grasp
