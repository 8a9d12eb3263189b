// The options that place a user's mesh in a template scene (grasp/object_scene.h): --scale, --fit,
// --hand, --up, --yaw and, for one object, --pose and --write-scene. `graspcd grasp --object` and
// `graspcd validate --objects` add them with add_placement_options and check them with
// check_placement_options; each command keeps its own help texts.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "graspcd/grasp/hand_templates.h"
#include "graspcd/grasp/object_scene.h"

namespace graspcd::cli {

struct PlacementOptions {
  double scale = 1;  // --scale S (> 0): file units -> m; default 1 (metres)
  bool fit = false;  // --fit: scale to the template's room instead
  std::string hand = "project";
  std::string up = "z";
  double yaw = 0;
  std::vector<double> pose;    // --pose W X Y Z
  std::vector<double> offset;  // --offset DX DY, m
  std::string write_scene;     // --write-scene DIR: keep the generated scene there
};

// The range of --scale: file units to metres, from micrometres to kilometres per unit (beyond it
// the placed coordinates would overflow or vanish).
inline constexpr double kMinScale = 1e-6;
inline constexpr double kMaxScale = 1e3;

// One of the options, with its help text (the command's own).
enum class Placement { kScale, kFit, kHand, kUp, kYaw, kPose, kOffset, kWriteScene };
struct PlacementOption {
  Placement option;
  std::string help;
};

// Adds the given options to `app` in the given order (a command's --help lists them so), with
// their checks: --scale in [kMinScale, kMaxScale], --yaw in [-360, 360], --pose four finite
// numbers (each named: "--yaw: Value nan is not a finite number").
void add_placement_options(CLI::App& app, PlacementOptions& options,
                           const std::vector<PlacementOption>& added);

// The rules between them, after the parse: each goes with `owner` (the option naming the mesh or
// meshes; `owner_given`: whether it was given; the first given, in the order they were added, is
// named), --scale and --fit exclude each other, and so do --pose and --up/--yaw. Throws
// UsageError "COMMAND: ...".
void check_placement_options(const CLI::App& app, const std::string& command,
                             const std::string& owner, bool owner_given);

// The placement of `file` (empty for an object set, whose files are found later); --pose
// normalised. Throws UsageError "--pose: not a finite unit quaternion ..." when it is all zeros.
grasp::ObjectPlacement object_placement(const PlacementOptions& options, const std::string& file);

// The template of --hand (grasp/hand_templates.h). Throws UsageError "COMMAND: --hand must be
// ..." for a name that is no template, and the library's words when a real hand is not found.
grasp::HandTemplate hand_template(const std::string& hand, const std::string& command);

}  // namespace graspcd::cli
