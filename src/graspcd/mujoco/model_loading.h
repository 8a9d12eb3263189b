// Loading an MJCF scene for graspcd: the checks before MuJoCo reads it (scene_check.h), MuJoCo's
// own reader with its messages captured, and the compiled numbers (model_check.h). Every refusal
// is an InputError that carries the file, the line and the message apart and prints as one line.
#pragma once

#include <string>

#include "graspcd/mujoco/input_error.h"
#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::mujoco {

// Loads an MJCF file. A missing file or MuJoCo's error become an InputError whose message is
// "FILE: <MuJoCo's message on one line>" (docs/mujoco.md, "Loading a scene").
ModelPtr load_model(const std::string& path);

// Joins MuJoCo's multi-line error text into one line (line breaks become "; ", blanks trimmed).
std::string join_lines(const std::string& text);

}  // namespace graspcd::mujoco
