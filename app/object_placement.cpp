#include "object_placement.h"

#include <array>

#include "command.h"

namespace graspcd::cli {

namespace {

constexpr const char* kPlacementOptions[] = {"--scale", "--fit",  "--hand",       "--up",
                                             "--yaw",   "--pose", "--write-scene"};

}  // namespace

void add_placement_options(CLI::App& app, PlacementOptions& options, const PlacementHelp& help) {
  app.add_option("--scale", options.scale, help.scale)->check(positive_number());
  app.add_flag("--fit", options.fit, help.fit);
  app.add_option("--hand", options.hand, help.hand)->capture_default_str();
  app.add_option("--up", options.up, help.up)->capture_default_str();
  app.add_option("--yaw", options.yaw, help.yaw)->check(CLI::Range(-360.0, 360.0));
  if (!help.pose.empty()) app.add_option("--pose", options.pose, help.pose)->expected(4);
  if (!help.write_scene.empty())
    app.add_option("--write-scene", options.write_scene, help.write_scene);
}

void check_placement_options(const CLI::App& app, const std::string& command,
                             const std::string& owner, bool owner_given) {
  const auto given = [&](const char* name) {
    return app.get_option_no_throw(name) != nullptr && app.count(name) > 0;
  };
  for (const char* o : kPlacementOptions) {
    if (!owner_given && given(o)) {
      throw UsageError(command + ": " + o + " goes with " + owner);
    }
  }
  if (given("--fit") && given("--scale")) {
    throw UsageError(command + ": --scale and --fit exclude each other");
  }
  if (given("--pose") && (given("--up") || given("--yaw"))) {
    throw UsageError(command + ": --pose and --up/--yaw exclude each other");
  }
}

grasp::ObjectPlacement object_placement(const PlacementOptions& options, const std::string& file) {
  grasp::ObjectPlacement placement;
  placement.file = file;
  placement.scale = options.scale;
  placement.fit = options.fit;
  placement.up = options.up;
  placement.yaw_degrees = options.yaw;
  if (!options.pose.empty()) {
    placement.pose =
        std::array<double, 4>{options.pose[0], options.pose[1], options.pose[2], options.pose[3]};
  }
  return placement;
}

}  // namespace graspcd::cli
