// The template hands an object run places a user's mesh in (`grasp --object` and
// `validate --objects`, --hand; object_scene.h, object_run.h): the scene, the room it has for the
// object, the share of that room a --fit object fills, and where its real hand's models are.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace graspcd::grasp {

// A template's file paths that begin with `from` (as the template writes them) name files under
// the folder `to`: the real hands' "../../shared/models/" of mjcf/real_*.xml, wherever the
// templates were installed.
struct TemplatePath {
  std::string from;
  std::string to;
};

// The share of its room a --fit object fills in a real hand's template (docs/objects.md, "--fit
// and each hand's margin"): the margin the hand needs to close on the object. The project's
// hand and a template file of the user's: 1.
inline constexpr double kRobotiqFitFraction = 0.9;
inline constexpr double kShadowFitFraction = 0.9;
inline constexpr double kAllegroFitFraction = 0.9;

struct HandTemplate {
  std::string name;   // project, robotiq, shadow, allegro, or the template file the user gave
  std::string scene;  // the template scene (its pair config beside it)
  std::optional<std::array<double, 2>> fit;  // width, height of its room, when the scene has no
                                             // graspcd_fit
  double fit_fraction = 1;
  std::vector<TemplatePath> moved;
  // --drive FILE: `scene` is a hand file, which an object run wraps into a template
  // (hand_wrapper.h), and messages name FILE for the template's pair config.
  std::string drive;

  // SCENE.pairs.json.
  std::string pairs() const;
  // What messages call a mesh of its hand: "the robotiq hand's ", or "the hand's " for a file.
  std::string mesh_owner() const;
};

// A built-in template whose real hand is not where graspcd looks for it: what() says where it
// looked and how to point graspcd at the models.
class HandModelsNotFound : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// project (mjcf/example1.xml), robotiq (mjcf/real_robotiq_mug.xml), shadow
// (mjcf/real_shadow_glass.xml) or allegro (mjcf/real_allegro_brick.xml), found in
// graspcd::mjcf_dir(), or a template scene file. Throws std::invalid_argument "--hand must be
// ..." for anything else, HandModelsNotFound when a real hand is not under
// graspcd::models_dir().
HandTemplate hand_template(const std::string& hand);

}  // namespace graspcd::grasp
