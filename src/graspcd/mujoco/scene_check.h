// What graspcd checks in a scene before MuJoCo reads it (docs/bad-input.md). MuJoCo 2.2 accepts a
// NaN in an MJCF attribute with only a warning ("XML contains a 'NaN'") and reads "nan" in an OBJ
// vertex as 0, so a scene with a non-finite number would run, answer nonsense and, on the paths
// that do not skip non-finite poses, spin in the exact predicates. Both are bad input here.
#pragma once

#include <string>

#include "graspcd/mujoco/scene_names.h"

namespace graspcd::mujoco {

// Reads the MJCF file `path` with tinyxml2 (MuJoCo's own XML parser) and the files it includes,
// and refuses, with an InputError (model_loading.h) naming the file and the attribute's line:
//  - an attribute that holds numbers one of which is not finite (nan, inf, or a literal that
//    overflows a double), except the attributes that name things (name, class, mesh, ...);
//  - a mesh file the scene names (resolved as MuJoCo does: meshdir or assetdir of <compiler>,
//    relative to the main file's folder) that io::check_mesh_file refuses: an OBJ with a
//    byte-order mark, a non-finite or unreadable vertex, a bad face; a bad binary STL.
// An XML syntax error, a missing include or a missing mesh file is left to MuJoCo, whose message
// the caller reports. Refusals of a scene graspcd wrote are named by `names`.
void check_scene_file(const std::string& path, const SceneNames& names = {});

}  // namespace graspcd::mujoco
