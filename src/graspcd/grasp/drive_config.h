// The "grasp" section of a pair config (the rest of the file belongs to the MuJoCo layer,
// graspcd/mujoco/pair_config.h): how the grasp experiment drives a hand through its own actuators.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "graspcd/mujoco/scene_names.h"

namespace graspcd::grasp {

// How `graspcd grasp` drives a hand that is not ours (the "grasp" section of the pair config,
// e.g. a real hand of ../shared/models): the hand's own actuators close it, one more
// actuator lifts. Fields, in JSON:
//   "grasp": {
//     "object": "object",         // the grasped body (a free joint); default "object"
//     "hand": "base",             // the body the hold drift is measured against (required)
//     "support": "table",         // the body heights are measured from; default: the world
//     "close": [ {"actuator": "fingers_actuator",  // an actuator that closes the hand
//                 "step": 0.96,   // ctrl added per grasp step (> 0): about 0.003 rad of its joint
//                 "squeeze": 20,  // ctrl added after the closing (default 0)
//                 "touch": ["body:left_pad", "body:right_pad"]} ],  // patterns (as "pairs");
//                 // the actuator stops when a geom of each touches the object
//     "lift": {"actuator": "lift", "by": 0.06}  // ctrl change that lifts the object (> 0 or < 0)
//   }
struct CloseDrive {
  std::string actuator;
  double step = 0;
  double squeeze = 0;
  std::vector<std::string> touch;
};
struct DriveConfig {
  std::string object = "object";
  std::string hand;
  std::string support;
  std::vector<CloseDrive> close;
  std::string lift_actuator;
  double lift_by = 0;
};

// The "grasp" section of the config text, when it has one. `source` (a file name) starts every
// error message; throws a mujoco::InputError naming `source` for a bad section, std::runtime_error
// for bad JSON (the rest of the config is checked by parse_registry_config).
std::optional<DriveConfig> parse_drive_config(const std::string& json_text,
                                              const std::string& source);
// The same, from a file (named as `names` has it). Throws std::runtime_error naming the file when
// it cannot be read.
std::optional<DriveConfig> load_drive_config(const std::string& path,
                                             const mujoco::SceneNames& names = {});

}  // namespace graspcd::grasp
