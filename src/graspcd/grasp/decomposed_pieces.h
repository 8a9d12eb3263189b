// The pieces of a decomposed scene (decomposed_scene.h, write_decomposed_scene) in the model
// MuJoCo compiled from it: which geoms are pieces, and the model with the object as it was. Apart
// from decomposed_scene.h so that run_grasp (grasp.cpp), which decomposed_scene.h calls, can check
// a decomposed start on the true object.
#pragma once

#include <mujoco/mujoco.h>

#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::grasp {

// Whether geom `g` of a model compiled from a written scene is one of the pieces (its mesh asset
// is named MESH__piece_K, whether the geom has a name or not).
bool is_piece(const mjModel* m, int g);

// A copy of `m` (compiled from a written scene) with the object as it was: every piece out of
// collision (contype = conaffinity = 0) and every replaced geom colliding again as its pieces did.
// Geom ids are `m`'s, so a registry built on the copy checks the true meshes at the poses of a
// grasp run on `m` (validate --decomposed).
mujoco::ModelPtr true_object_model(const mjModel* m);

}  // namespace graspcd::grasp
