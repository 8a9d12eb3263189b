// Loading an MJCF scene: graspcd's checks before MuJoCo reads it (scene_check.h), MuJoCo's reader
// with its messages captured, then the compiled numbers (model_check.h).
#pragma once

#include <string>

#include "graspcd/mujoco/input_error.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::mujoco {

// Loads an MJCF file. Throws InputError for a missing file, a refused scene or MuJoCo's error
// ("FILE: <MuJoCo's message on one line>", docs/mujoco.md, "Loading a scene"); a scene graspcd
// wrote is named as `names` says.
ModelPtr load_model(const std::string& path, const SceneNames& names = {});

// The one-line rule, io::one_line, under its name before 0.5.
inline std::string join_lines(const std::string& text) { return io::one_line(text); }

}  // namespace graspcd::mujoco
