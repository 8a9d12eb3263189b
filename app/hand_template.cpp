#include "hand_template.h"

#include <filesystem>
#include <system_error>

#include "command.h"
#include "graspcd/core/warnings.h"
#include "graspcd/io/output_files.h"
#include "graspcd/version/data_dirs.h"

namespace graspcd::cli {

namespace {

namespace fs = std::filesystem;

// How the real-hand templates of mjcf/ name the models folder (../shared/models beside the
// checkout, seen from mjcf/).
constexpr const char* kModelsInTemplates = "../../shared/models/";

// A real hand's template: `file` in mjcf/, its hand `model` below the models folder.
HandTemplate real_hand(const std::string& file, const std::string& who, const std::string& model) {
  const std::string models = models_dir();
  std::error_code ec;
  if (!fs::is_regular_file(fs::path(models) / model, ec)) {
    throw UsageError("the " + who + "'s models are not found at " + models +
                     ": set GRASPCD_MODELS_DIR to the folder that holds " + model);
  }
  return {(fs::path(mjcf_dir()) / file).string(), std::nullopt, {{kModelsInTemplates, models}}};
}

}  // namespace

HandTemplate hand_template(const std::string& hand, const std::string& command) {
  // Example 1: the project's arm and 4-finger hand over the cup (7 cm wide, 8 cm tall).
  if (hand == "project") {
    return {
        (fs::path(mjcf_dir()) / "example1.xml").string(), std::array<double, 2>{0.07, 0.08}, {}};
  }
  if (hand == "robotiq") {
    return real_hand("real_robotiq_mug.xml", "Robotiq hand", "hands/robotiq_2f85/2f85.xml");
  }
  if (hand == "shadow") {
    return real_hand("real_shadow_glass.xml", "Shadow hand", "hands/shadow_hand/right_hand.xml");
  }
  std::error_code ec;
  if (!fs::is_regular_file(hand, ec)) {
    throw UsageError(command +
                     ": --hand must be project, robotiq, shadow or a template scene file (" + hand +
                     " is none)");
  }
  return {hand, std::nullopt, {}};
}

double fit_fraction(const std::string& hand) {
  if (hand == "robotiq") return kRobotiqFitFraction;
  if (hand == "shadow") return kShadowFitFraction;
  return 1;
}

void name_user_files(const std::vector<std::pair<std::string, std::string>>& renames,
                     const std::string& hand) {
  const std::string hands = hand == "project" || hand == "robotiq" || hand == "shadow"
                                ? "the " + hand + " hand's "
                                : "the hand's ";
  warnings().edit([&](Warning& w) {
    for (const auto& [from, to] : renames) w.message = io::replace_all(w.message, from, to);
    for (const char* lead : {"mesh ", "(mesh "}) {
      const std::string key = std::string(lead);
      for (std::size_t at = w.message.find(key); at != std::string::npos;
           at = w.message.find(key, at + key.size())) {
        const std::size_t quote = w.message.find('\'', at);
        if (quote == std::string::npos || quote > at + key.size() + 12) continue;
        if (w.message.compare(quote, 13, "'object_mesh'") == 0) continue;
        if (at >= hands.size() && w.message.compare(at + (key[0] == '(' ? 1 : 0) - hands.size(),
                                                    hands.size(), hands) == 0) {
          continue;
        }
        w.message.insert(at + (key[0] == '(' ? 1 : 0), hands);
        at += hands.size();
      }
    }
  });
}

}  // namespace graspcd::cli
