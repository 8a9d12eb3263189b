// A scene for a user's object, generated from a template scene (graspcd grasp --object; README,
// "A new object"). The template is any MJCF scene with a pair config beside it
// (TEMPLATE.pairs.json) whose object is the body `object`, a child of <worldbody> with a free
// joint and one mesh geom. The new scene is the template read and written by tinyxml2 with:
//  - that mesh asset's file replaced by the user's mesh and its scale set (the asset is renamed
//    "object_mesh", the geom "object"); a closed mesh whose faces all point inward (negative
//    signed volume, io::turn_right_way_out) is written turned right way out as
//    STEM.meshes/object/STEM.outward.obj, which the asset names instead, with the warning
//    "mesh_inside_out"; a mesh in a format MuJoCo 2.2 does not read (anything but OBJ and binary
//    STL: io::load_mesh) is written as STEM.meshes/object/STEM.converted.obj (as graspcd read it,
//    in its file units);
//  - the object body turned (the file's `up` axis along -gravity, then `yaw` about it, or the
//    quaternion `pose`) and placed with its lowest point along gravity kSupportGap above the
//    support point, centred on it across gravity;
//  - the object's mesh copied into STEM.meshes/object/ beside the scene (its file name kept) and
//    named relative to the scene, so that the scene's folder can be moved or copied;
//  - every other file path (<include file>, <compiler texturedir>, and asset files when no
//    meshdir is set) made absolute: the hand stays where it is installed or shared; a meshdir
//    (or assetdir) becomes STEM.meshes/, which holds an absolute link to every file of the
//    template's mesh folder;
//  - <size nconmax njmax> raised to at least 1000 and 4000 (the contacts of a fine mesh);
//  - the template's comments replaced by a header saying what the scene is and how it was made.
// The template may carry its placement in <custom>: <numeric name="graspcd_support" data="x y z"/>
// (the support point, world frame; default: the object body's pos) and <numeric
// name="graspcd_fit" data="width height"/> (the room the hand has for an object: its width across
// gravity and its height along it, m; needed by `fit`).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/io/output_files.h"

namespace graspcd::grasp {

// How far above the support the object's lowest point is placed, m: clear of it by much less
// than the start check's tolerance (start_check.h), so that the object drops onto it at once.
inline constexpr double kSupportGap = 0.5e-3;

struct ObjectPlacement {
  std::string file;  // the user's mesh (any format io::load_mesh reads)
  double scale = 1;  // file units -> m; the file's units are kept by default
  bool fit = false;  // scale to the template's graspcd_fit instead
  // With `fit`: the fitted scale times this (0 < f <= 1), the margin the hand needs to close on
  // the object (docs/objects.md, "--fit and each hand's margin").
  double fit_fraction = 1;
  std::string up = "z";                       // the file axis pointing up: x, y, z, -x, -y or -z
  double yaw_degrees = 0;                     // then a turn about the up direction
  std::optional<std::array<double, 4>> pose;  // w x y z: the object's rotation, instead of up/yaw
};

// A template's file paths that begin with `from` (as the template writes them) name files under
// the folder `to` (its links resolved), not beside the template: e.g. the real hands'
// "../../shared/models/" of mjcf/real_*.xml when the templates are installed far from the models.
struct TemplatePath {
  std::string from;
  std::string to;
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
  // When the placed object is larger than 1 m (and not fitted): what that says about the file's
  // units, e.g. "the object is 60 m across at --scale 1: is the file in millimetres? try --scale
  // 0.001"; also the warning "mesh_units". A refusal of the scene adds it to its line.
  std::string units_hint;
};

// Writes the scene into `dir` (created). `hand` names the template in the header (e.g.
// "robotiq"). `default_fit` is used when the template has no graspcd_fit; `moved` says where the
// template's paths that begin with a TemplatePath's `from` are (first match). Throws
// io::InputError naming the mesh file for a bad mesh, naming the template (and its line) for a
// template that breaks the contract above; std::invalid_argument for a bad `up`.
ObjectScene write_object_scene(const ObjectPlacement& placement, const std::string& template_path,
                               const std::string& hand, const std::string& dir,
                               const std::optional<std::array<double, 2>>& default_fit = {},
                               const std::vector<TemplatePath>& moved = {});

// A temporary folder for a scene that the user keeps not (grasp --object without --write-scene,
// validate --objects): graspcd-object-XXXXXX created under the system's temporary folder ($TMPDIR,
// else /tmp), removed with everything in it when this goes out of scope, and on INT, TERM and HUP
// (io/output_files.h). Throws io::InputError naming the temporary folder when it cannot be
// created.
class TempFolder {
 public:
  TempFolder();
  const std::filesystem::path& path() const;

 private:
  io::CleanupGuard guard_;
};

}  // namespace graspcd::grasp
