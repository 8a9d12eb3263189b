// The template hands of `grasp --object` and `validate --objects` (--hand): the scene whose
// object the user's mesh replaces (grasp/object_scene.h; README, "A new object").
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/grasp/object_scene.h"

namespace graspcd::cli {

struct HandTemplate {
  std::string scene;
  std::optional<std::array<double, 2>> fit;  // when the scene has no graspcd_fit
  // Where the scene's real hand is (robotiq, shadow): its "../../shared/models/" paths name the
  // models folder (graspcd::models_dir()), wherever the templates were installed.
  std::vector<grasp::TemplatePath> moved;
};

// project, robotiq, shadow (found in graspcd::mjcf_dir()) or a template scene file; throws
// UsageError naming `command` for anything else, and one saying where the models were looked for
// when robotiq's or shadow's hand is not found.
HandTemplate hand_template(const std::string& hand, const std::string& command);

// The fraction of its room a --fit object fills in the hand's template (grasp::ObjectPlacement::
// fit_fraction), measured per hand (docs/objects.md, "--fit and each hand's margin"): project 1,
// robotiq kRobotiqFitFraction, shadow kShadowFitFraction; 1 for a template file of the user's.
inline constexpr double kRobotiqFitFraction = 0.9;
inline constexpr double kShadowFitFraction = 0.9;
double fit_fraction(const std::string& hand);

// The run's warnings with the temporary files named as the user knows them (`renames`: from ->
// to, in order), and a mesh of the hand (any mesh but the object's 'object_mesh') called the
// hand's: "the shadow hand's mesh 12 'th_distal_pst' is not closed" (`hand`: --hand).
void name_user_files(const std::vector<std::pair<std::string, std::string>>& renames,
                     const std::string& hand);

}  // namespace graspcd::cli
