// The options that place a user's mesh in a template scene (grasp/object_scene.h): --scale, --fit,
// --hand, --up, --yaw and, for one object, --pose and --write-scene. `graspcd grasp --object` and
// `graspcd validate --objects` add them with add_placement_options and check them with
// check_placement_options; each command keeps its own help texts.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "graspcd/grasp/object_scene.h"

namespace graspcd::cli {

struct PlacementOptions {
  double scale = 1;  // --scale S (> 0): file units -> m; default 1 (metres)
  bool fit = false;  // --fit: scale to the template's room instead
  std::string hand = "project";
  std::string up = "z";
  double yaw = 0;
  std::vector<double> pose;  // --pose W X Y Z
  std::string write_scene;   // --write-scene DIR: keep the generated scene there
};

// The help of each option. An empty `pose` or `write_scene` leaves that option out.
struct PlacementHelp {
  std::string scale, fit, hand, up, yaw;
  std::string pose, write_scene;
};

// Adds the options to `app` in the order --scale, --fit, --hand, --up, --yaw, --pose,
// --write-scene, with their checks: --scale > 0, --yaw in [-360, 360], --pose four numbers.
void add_placement_options(CLI::App& app, PlacementOptions& options, const PlacementHelp& help);

// The rules between them, after the parse: each goes with `owner` (the option naming the mesh or
// meshes; `owner_given`: whether it was given), --scale and --fit exclude each other, and so do
// --pose and --up/--yaw. Throws UsageError "COMMAND: ...".
void check_placement_options(const CLI::App& app, const std::string& command,
                             const std::string& owner, bool owner_given);

// The placement of `file` (empty for an object set, whose files are found later).
grasp::ObjectPlacement object_placement(const PlacementOptions& options, const std::string& file);

}  // namespace graspcd::cli
