// The template hands of `grasp --object` and `validate --objects` (--hand): the scene whose
// object the user's mesh replaces (grasp/object_scene.h; README, "A new object").
#pragma once

#include <array>
#include <optional>
#include <string>

namespace graspcd::cli {

struct HandTemplate {
  std::string scene;
  std::optional<std::array<double, 2>> fit;  // when the scene has no graspcd_fit
};

// project, robotiq, shadow or a template scene file; throws UsageError naming `command` for
// anything else.
HandTemplate hand_template(const std::string& hand, const std::string& command);

}  // namespace graspcd::cli
