// A hand of the user's as it comes (a Menagerie-style hand file: an MJCF whose <worldbody> holds
// the hand, fixed in the world, its meshes under its own meshdir) and a drive file: graspcd writes
// the template scene around it (`grasp --object FILE --hand HAND.xml --drive DRIVE`, `hand check
// HAND.xml --drive DRIVE`; docs/hands.md). The wrapper includes the hand file unchanged, as the
// shipped real-hand templates do (mjcf/real_*.xml: MuJoCo 2.2's <include> cannot put a hand under
// a driven body, so the world is the hand's frame), and adds:
//  - <option gravity> and the hand's mesh folder as meshdir (MuJoCo 2.2 reads an included file's
//    meshdir relative to the main scene);
//  - the object: body "object" with a free joint and one mesh geom (a 2 cm cube until the object
//    run puts the user's mesh in its place), density 1000, friction 1 0.01 0.001, contype and
//    conaffinity 3;
//  - the support: body "support", a 20 x 20 x 2 cm box of 2 kg whose face is at the support point,
//    facing against gravity, on a slide joint along gravity (damping 50), contype and conaffinity
//    2 (it collides with the object, not with a hand whose geoms keep MuJoCo's 1);
//  - the lift: the position actuator "lift" on that joint (kp 4000, ctrlrange -0.1 0.1): moving
//    the support along gravity is lifting the hand against it;
//  - <custom> graspcd_support (and graspcd_fit with a room), as a template file has them.
// The drive file (JSON; the pair config the wrapper gets, and where the object goes):
//   {
//     "mount": {"gravity": [0, 0, 9.81],      // required: along it the object hangs from the hand
//               "support": [0.02, -0.015, 0.08],  // required: where the object's lowest point
//                                                 // (along gravity) goes, on the support's face
//               "room": [0.085, 0.05]},       // optional: width and height --fit scales to
//     "grasp": {"hand": "palm", "close": [...]},  // the pair config's "grasp" section
//                                                 // (drive_config.h); "object", "support" and
//                                                 // "lift" default to the wrapper's (lift by 0.06)
//     "pairs": [...]                              // optional: default, every body of the hand file
//                                                 // that has a collidable geom against body:object
//     ... any other field of a pair config ("method", "contact_reuse", ...)
//   }
#pragma once

#include <array>
#include <optional>
#include <string>

#include "graspcd/core/geometry.h"
#include "graspcd/grasp/hand_templates.h"

namespace graspcd::grasp {

// Where the object goes in a wrapped hand (the drive file's "mount").
struct HandMount {
  Vec3 gravity = Vec3(0, 0, -9.81);
  Vec3 support = Vec3::Zero();
  std::optional<std::array<double, 2>> room;
};

// The names the wrapper gives what it adds (a hand file that already uses one is refused).
inline constexpr const char* kWrapperObject = "object";
inline constexpr const char* kWrapperSupport = "support";
inline constexpr const char* kWrapperLift = "lift";
// How far the lift moves the support along gravity by default, m (the shipped templates' 6 cm).
inline constexpr double kWrapperLiftBy = 0.06;

// Writes the placeholder object (a 2 cm cube centred on its origin, faces outward) as an OBJ.
// Throws io::InputError naming `path` when it cannot.
void write_placeholder_object(const std::string& path);

// The hand of `--hand HAND --drive DRIVE`: HAND a hand file (not a built-in template's name),
// DRIVE its drive file. Throws std::invalid_argument "--drive goes with a hand file ..." for a
// built-in name, io::InputError naming HAND or DRIVE when it is not a regular file.
HandTemplate hand_with_drive(const std::string& hand_file, const std::string& drive);

// Writes the wrapper of `hand.scene` (a hand file) with the drive `hand.drive` into `dir`
// (created): DIR/hand.xml, DIR/hand.pairs.json and the placeholder object DIR/object.obj. Returns
// the template to place objects in: its scene the wrapper, its name the hand file, its room the
// mount's, its drive the drive file (messages name the drive for the wrapper's pair config).
// Throws io::InputError naming the drive file (bad JSON, a bad or missing "mount", a "grasp" that
// is not an object) or the hand file (MuJoCo cannot load it, it has no <worldbody>, or it already
// has a body, joint or actuator of the wrapper's names).
HandTemplate write_hand_wrapper(const HandTemplate& hand, const std::string& dir);

}  // namespace graspcd::grasp
