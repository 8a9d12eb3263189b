// `graspcd hand check`: what a template hand (docs/design.md, "Object scenes"), or a hand file
// with its drive (hand_wrapper.h), lacks to take a user's object, each missing piece named with
// how to add it (docs/hands.md). Checked in the order a run meets them:
//  1. the drive file, for a hand file: its "mount" and "grasp", the hand file loading alone and
//     leaving the wrapper's names free (the wrapper is then checked as a template);
//  2. the scene: the template contract (object_scene.h, template_problems);
//  3. the pair config beside it: found, parsed (the MuJoCo layer's fields), its "grasp" section
//     parsed (drive_config.h), or the project's hand (joints arm1 and finger1_A) without one;
//  4. with a 2 cm cube placed as an object run places a mesh: the scene loads in MuJoCo, every
//     pair pattern selects served geoms, the "grasp" section's bodies, actuators and touch
//     patterns exist, and the object collides with its support.
// Optional pieces are notes: graspcd_support (else the object goes where the object body stands)
// and graspcd_fit (else --fit has no room).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "graspcd/grasp/hand_templates.h"

namespace graspcd::grasp {

struct MissingPiece {
  std::string file;      // the file it belongs in (the scene, its pair config, the drive file)
  std::size_t line = 0;  // its line there, 0 for the file as a whole
  std::string what;
  std::string how;
};

struct HandCheck {
  std::string scene;     // what was checked, as given: the template, or the hand file
  std::string pairs;     // its pair config, or the drive file
  bool wrapped = false;  // a hand file with its drive
  std::vector<MissingPiece> missing;
  std::vector<std::string> notes;
  // When nothing is missing, what the template holds: "object body 'object' (mesh geom 'brick'),
  // gravity 0 0 9.81, 5 pairs, 12 closing actuators, lift 'lift' by 0.06".
  std::string summary;
  bool complete() const { return missing.empty(); }
};

// Checks `hand` (a template, or a hand file with hand.drive). Writes its trial scenes into a
// private folder under the system's temporary folder, removed at the end. A pair config or drive
// file that is not JSON is a missing piece (at its line); throws io::InputError naming the scene
// or the hand file when tinyxml2 cannot read it, MuJoCo cannot load a hand file alone, or a hand
// file already names a body or actuator as the wrapper does.
HandCheck check_hand(const HandTemplate& hand);

}  // namespace graspcd::grasp
