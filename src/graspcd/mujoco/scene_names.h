// The names a user knows the files of a scene by when graspcd wrote that scene for them (a
// user's mesh in a template hand, grasp/object_scene.h; an object's convex pieces beside its
// scene, grasp/decomposed_scene.h). The loader (model_loading.h), the registry (registry.h) and
// the grasp make their messages with these names: no message names a file the user never gave.
// Empty names change nothing.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/io/input_error.h"

namespace graspcd::mujoco {

struct SceneNames {
  // The written scene, and what a refusal of it says instead: `scene` (the user's file), line 0,
  // `scene_context` before the message ("in the template scene: ") and `note` after it (what the
  // object's size says about its units, "; the object is 60 m across ...").
  std::string written_scene;
  std::string scene;
  std::string scene_context;
  std::string note;
  // Other written files and the files the user knows them by (a copied pair config -> the
  // template's, the copied mesh -> the user's mesh).
  std::vector<std::pair<std::string, std::string>> files;
  // What a warning calls a mesh of the hand, any named mesh but `object_mesh`: "the robotiq
  // hand's " (empty: nothing).
  std::string hand;
  std::string object_mesh;
  // A decomposed scene's pieces (grasp/decomposed_scene.h): piece K's file as the user knows it
  // (DIR/NAME_piece_K.obj), for a refusal that names a piece (empty: none).
  std::vector<std::string> pieces;
  // After a refusal of the start state only (grasp/start_check.h), before `note`: what the
  // object's size says against the hand's room ("; the object is ... m, the robotiq hand's room
  // ...: too tall; try --fit ...").
  std::string start_note;

  // The file a message names for `path`.
  std::string file(const std::string& path) const;
  // `message` with every written file it quotes (MuJoCo's errors quote the mesh file they read)
  // replaced by the file the user knows it by.
  std::string named(const std::string& message) const;
  // The refusal of `path` (at `line`, 0 for the whole file) with these names, in its message too.
  io::InputError refusal(const std::string& path, std::size_t line,
                         const std::string& message) const;
  // "the robotiq hand's " for a mesh of the hand named `mesh_name`, else "".
  std::string mesh_owner(const std::string& mesh_name) const;
};

}  // namespace graspcd::mujoco
