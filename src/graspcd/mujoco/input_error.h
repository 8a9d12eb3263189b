// graspcd::mujoco's name for the one input error, io::InputError (graspcd/io/input_error.h):
// constructed as (file, line, message), what() one line "FILE:LINE: MESSAGE".
#pragma once

#include "graspcd/io/input_error.h"

namespace graspcd::mujoco {

using InputError = io::InputError;

}  // namespace graspcd::mujoco
