// What graspcd checks in a scene before MuJoCo reads it (docs/bad-input.md). MuJoCo 2.2 accepts a
// NaN in an MJCF attribute with only a warning ("XML contains a 'NaN'") and reads "nan" in an OBJ
// vertex as 0, so a scene with a non-finite number would run, answer nonsense and, on the paths
// that do not skip non-finite poses, spin in the exact predicates. Both are bad input here.
#pragma once

#include <string>
#include <vector>

#include "graspcd/mujoco/scene_names.h"

namespace graspcd::mujoco {

// Reads the MJCF file `path` with tinyxml2 (MuJoCo's own XML parser) and the files it includes,
// and refuses, with an InputError (model_loading.h) naming the file and the attribute's line:
//  - an attribute that holds numbers one of which is not finite (nan, inf, or a literal that
//    overflows a double), except the attributes that name things (name, class, mesh, ...);
//  - a mesh file the scene names (resolved as MuJoCo does: meshdir or assetdir of <compiler>,
//    relative to the main file's folder) that io::check_mesh_file refuses: an OBJ with a
//    byte-order mark, a non-finite or unreadable vertex, a bad face; a bad binary STL;
//  - an included file, or a file an asset names (a height field, a skin, a texture), that is a
//    FIFO, a folder or a device, before anything opens it: reading a FIFO waits for a writer.
// An XML syntax error, a missing include or a missing mesh file is left to MuJoCo, whose message
// the caller reports. Refusals of a scene graspcd wrote are named by `names`.
void check_scene_file(const std::string& path, const SceneNames& names = {});

// The files MuJoCo reads for the scene `path` that exist: the scene, the files it includes
// (recursively) and the files its assets name (meshes, height fields, skins, textures; an
// asset's file where MuJoCo may look for it). Outputs of a run that reads the scene must not
// replace any of them (io/output_files.h). Throws as check_scene_file does for a FIFO.
std::vector<std::string> scene_files(const std::string& path);

}  // namespace graspcd::mujoco
