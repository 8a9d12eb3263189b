#include "hand_template.h"

#include <filesystem>
#include <system_error>

#include "command.h"

#ifndef GRASPCD_MJCF_DIR
#error "GRASPCD_MJCF_DIR must name the repository's mjcf folder"
#endif

namespace graspcd::cli {

HandTemplate hand_template(const std::string& hand, const std::string& command) {
  const std::string mjcf = GRASPCD_MJCF_DIR;
  // Example 1: the project's arm and 4-finger hand over the cup (7 cm wide, 8 cm tall).
  if (hand == "project") return {mjcf + "/example1.xml", std::array<double, 2>{0.07, 0.08}};
  if (hand == "robotiq") return {mjcf + "/real_robotiq_mug.xml", std::nullopt};
  if (hand == "shadow") return {mjcf + "/real_shadow_glass.xml", std::nullopt};
  std::error_code ec;
  if (!std::filesystem::is_regular_file(hand, ec)) {
    throw UsageError(command +
                     ": --hand must be project, robotiq, shadow or a template scene file (" + hand +
                     " is none)");
  }
  return {hand, std::nullopt};
}

}  // namespace graspcd::cli
