#include "graspcd/grasp/hand_templates.h"

#include <filesystem>
#include <system_error>

#include "graspcd/version/data_dirs.h"

namespace graspcd::grasp {

namespace {

namespace fs = std::filesystem;

// How the real-hand templates of mjcf/ name the models folder (../shared/models beside the
// checkout, seen from mjcf/).
constexpr const char* kModelsInTemplates = "../../shared/models/";

// A real hand's template: `file` in mjcf/, its hand `model` below the models folder.
HandTemplate real_hand(const std::string& name, const std::string& file, const std::string& who,
                       const std::string& model, double fit_fraction) {
  const std::string models = models_dir();
  std::error_code ec;
  if (!fs::is_regular_file(fs::path(models) / model, ec)) {
    throw HandModelsNotFound("the " + who + "'s models are not found at " + models +
                             ": set GRASPCD_MODELS_DIR to the folder that holds " + model);
  }
  return {name,         (fs::path(mjcf_dir()) / file).string(), std::nullopt,
          fit_fraction, {{kModelsInTemplates, models}},         {}};
}

bool built_in(const std::string& name) {
  return name == "project" || name == "robotiq" || name == "shadow" || name == "allegro";
}

}  // namespace

std::string HandTemplate::pairs() const {
  return fs::path(scene).replace_extension(".pairs.json").string();
}

std::string HandTemplate::mesh_owner() const {
  return built_in(name) ? "the " + name + " hand's " : "the hand's ";
}

HandTemplate hand_template(const std::string& hand) {
  // Example 1: the project's arm and 4-finger hand over the cup (7 cm wide, 8 cm tall).
  if (hand == "project") {
    return {hand,
            (fs::path(mjcf_dir()) / "example1.xml").string(),
            std::array<double, 2>{0.07, 0.08},
            1,
            {},
            {}};
  }
  if (hand == "robotiq") {
    return real_hand(hand, "real_robotiq_mug.xml", "Robotiq hand", "hands/robotiq_2f85/2f85.xml",
                     kRobotiqFitFraction);
  }
  if (hand == "shadow") {
    return real_hand(hand, "real_shadow_glass.xml", "Shadow hand",
                     "hands/shadow_hand/right_hand.xml", kShadowFitFraction);
  }
  if (hand == "allegro") {
    return real_hand(hand, "real_allegro_brick.xml", "Allegro hand",
                     "hands/wonik_allegro/right_hand.xml", kAllegroFitFraction);
  }
  std::error_code ec;
  if (!fs::is_regular_file(hand, ec)) {
    throw std::invalid_argument(
        "--hand must be project, robotiq, shadow, allegro or a template "
        "scene file (" +
        hand + " is none)");
  }
  return {hand, hand, std::nullopt, 1, {}, {}};
}

}  // namespace graspcd::grasp
