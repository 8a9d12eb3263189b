// A scene for a user's object, written from a template hand's scene (hand_templates.h; the
// contract of a template: docs/design.md, "Object scenes"). The template is read and written by
// tinyxml2 with:
//  - the object body's mesh asset replaced by the user's mesh, copied into STEM.meshes/object/
//    beside the scene and named relative to it (asset "object_mesh", geom "object"); a closed
//    mesh whose faces all point inward is written turned right way out (STEM.outward.obj,
//    warning "mesh_inside_out"), one in a format MuJoCo 2.2 does not read as
//    STEM.converted.obj;
//  - the object turned (the file's `up` axis against gravity, then `yaw` about it, or `pose`),
//    scaled (given, or fitted to the template's room) and placed with its lowest point
//    kSupportGap above the support point, centred on it across gravity (then moved by the
//    placement's offset);
//  - every other path made absolute, a meshdir made STEM.meshes/ holding links to the hand's
//    meshes, so that the scene's folder can be moved;
//  - <size nconmax njmax> raised to at least 1000 and 4000, the template's comments replaced by
//    a header that says how the scene was made.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/grasp/hand_templates.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::grasp {

// How far above the support the object's lowest point is placed, m: clear of it by much less
// than the start check's tolerance (start_check.h), so that the object drops onto it at once.
inline constexpr double kSupportGap = 0.5e-3;

struct ObjectPlacement {
  std::string file;      // the user's mesh (any format io::load_mesh reads)
  double scale = 1;      // file units -> m; the file's units are kept by default
  bool fit = false;      // scale to the template's room instead (times HandTemplate::fit_fraction)
  std::string up = "z";  // the file axis pointing up: x, y, z, -x, -y or -z
  double yaw_degrees = 0;                     // then a turn about the up direction
  std::optional<std::array<double, 4>> pose;  // w x y z: the object's rotation, instead of up/yaw
  // Then moved across gravity from the support point by this, m: along e1 (the world x axis made
  // perpendicular to up; y when up is near x) and e2 = up x e1.
  std::array<double, 2> offset{};
};

// The marker line of a generated scene's header comment: graspcd recognises its own scenes by it
// (grasp --write-scene replaces a scene only when it carries the marker, or with --force).
inline constexpr const char* kGeneratedMarker = "graspcd-generated: object scene";

struct ObjectScene {
  std::string scene;   // DIR/STEM.xml
  std::string pairs;   // DIR/STEM.pairs.json
  std::string meshes;  // DIR/STEM.meshes: the object's mesh, links to the hand's
  double scale = 1;
  bool fitted = false;
  std::array<double, 3> size{};  // the placed object's extent: across gravity (2), along it, m
  std::array<double, 3> pos{};   // the object body's position
  std::array<double, 4> quat{};  // and rotation (w x y z)
  std::size_t faces = 0;         // the object's triangles, as read (before MuJoCo compiles them)
  // How far the support (and the object on it) was raised toward the hand: the template's
  // graspcd_reach less the object's height, for an object shorter than the reach; 0 otherwise.
  double support_raised = 0;
  // When the placed object is larger than 1 m (and not fitted): what that says about the file's
  // units, e.g. "the object is 60 m across at --scale 1: is the file in millimetres? try --scale
  // 0.001"; also the warning "mesh_units". A refusal of the scene adds it to its line.
  std::string units_hint;
  // Without a units hint, what a refused start adds about the object's size against the
  // template's room (graspcd_fit) and what to try, e.g. "the object is 0.07 x 0.07 x 0.15 m
  // (across, across, up), the robotiq hand's room 0.075 across and 0.06 up: too tall; try --fit
  // (scale 0.36) or --up x (0.15 across, 0.07 up)"; SceneNames::start_note carries it.
  std::string size_hint;
  // How messages name the written files: the scene as the user's mesh ("in the template scene"),
  // the pair config as the template's, the mesh copy as the user's mesh, the hand's meshes as
  // the hand's (mujoco/scene_names.h).
  mujoco::SceneNames names;
};

// A piece of the template contract (docs/design.md, "Object scenes") that a scene lacks: its line
// (0: the file), what is missing and how to add it.
struct TemplateProblem {
  std::size_t line = 0;
  std::string what;
  std::string how;
  std::string file;  // the file `line` is in, when not the template itself (a file it includes)
};

// The pieces of the contract the scene `template_path` lacks, in the order write_object_scene
// meets them (it refuses the first): <mujoco>, no <keyframe>, the object body, its free joint,
// its one mesh geom and that geom's asset, then a non-zero gravity. Throws io::InputError naming
// the file when tinyxml2 cannot read it.
std::vector<TemplateProblem> template_problems(const std::string& template_path);

// Writes the scene of `placement` in `hand` into `dir` (created). Throws io::InputError naming
// the mesh file for a bad mesh, naming the template (and its line) for a template that breaks
// the contract; std::invalid_argument for a bad `up`.
ObjectScene write_object_scene(const ObjectPlacement& placement, const HandTemplate& hand,
                               const std::string& dir);

// The places write_object_scene gives one mesh in one hand, without writing a scene: the mesh
// and the template are read once, then each placement's scale, size, pos and quat (and units
// hint) come out exactly as write_object_scene's (the other fields empty). Used by a batch of
// grasps (object_batch.h), which compiles one scene and moves its object. `support_raised`: the
// raise the compiled scene gave its support (ObjectScene::support_raised, graspcd_reach): every
// placement stands on that support, raised by it whatever its own height. Throws as
// write_object_scene does.
class ObjectPlacer {
 public:
  ObjectPlacer(const std::string& file, const HandTemplate& hand, double support_raised = 0);
  ~ObjectPlacer();
  ObjectPlacer(const ObjectPlacer&) = delete;
  ObjectPlacer& operator=(const ObjectPlacer&) = delete;
  // `placement.file` is ignored (the placer's file is placed).
  ObjectScene place(const ObjectPlacement& placement) const;

 private:
  struct Read;
  std::unique_ptr<Read> read_;
};

}  // namespace graspcd::grasp
