// A batch of grasps of one object in one hand (`graspcd grasp --object FILE --placements N`): the
// object's scene is written and compiled once, graspcd's trees and the true meshes' surfaces are
// built once, and each grasp moves the object in the compiled model (GraspScene::place_free_body)
// and starts from a reset state. Grasp k of a batch gives the verdicts of its placement run alone
// (`graspcd grasp --object FILE --up U --yaw Y --offset DX DY`): the moved model is the one the
// compiler makes of the scene written with that placement.
//
// The placements are drawn from a seed (draw_placements): which side of the file is up, the yaw
// about it and an offset across gravity from the hand's centre (the support point); each is
// recorded with its grasp, so that a run is reproduced from its seed or one grasp from its
// placement. A placement whose start is not valid for the true meshes is skipped (and counted by
// the caller); one that only the geometry MuJoCo collides cannot start (--native's hulls,
// --decomposed's pieces) is that configuration's "cannot start".
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/grasp/object_run.h"
#include "graspcd/grasp/object_scene.h"

namespace graspcd::grasp {

struct BatchPlacementOptions {
  int count = 1;
  std::uint64_t seed = 1;
  // The file axes that may point up (x, y, z, -x, -y, -z), each drawn as likely; empty: all six.
  std::vector<std::string> ups;
  // A fixed yaw, degrees; none: drawn in [0, 360).
  std::optional<double> yaw_degrees;
  // The offsets are drawn uniformly in the disc of this radius across gravity, m (0: none).
  double max_offset = 0.005;
};

// `count` placements of `base`'s file at its scale, drawn from `seed` by a 64-bit Mersenne
// Twister (std::mt19937_64) with the draws made by hand (not by std's distributions, whose
// results differ between standard libraries): per placement, the up axis, the yaw, the offset's
// angle and radius (the square root of a uniform number times max_offset), in that order. The
// same options give the same placements everywhere. Throws std::invalid_argument for a count
// below 1, an unknown axis, a negative or non-finite max_offset.
std::vector<ObjectPlacement> draw_placements(const ObjectPlacement& base,
                                             const BatchPlacementOptions& options);

struct ObjectBatchOptions {
  ObjectRunOptions run;    // the mesh and the hand (write_scene: keep the first placement's scene)
  ObjectPlacement first;   // the placement the scene is written with (its scale for all; no fit)
  std::string decomposed;  // DIR (graspcd decompose): the object collides as its pieces
  GraspOptions grasp;
};

enum class BatchOutcome { kGrasped, kSkipped, kCannotStart };

struct BatchGrasp {
  ObjectPlacement placement;
  ObjectScene placed;  // its scale, size, pos and quat (object_scene.h, ObjectPlacer)
  BatchOutcome outcome = BatchOutcome::kGrasped;
  std::string refusal;  // skipped or cannot start: the refusal's line
  // The grasp (kGrasped); its cost holds the batch's own parts (scene, compile, trees) in the
  // batch's first grasp.
  GraspResult result;
};

class ObjectBatch {
 public:
  // Writes the scene of options.first (and, with `decomposed`, its decomposed copy), compiles it
  // and builds the trees. Throws as ObjectRun and run_grasp do (io::InputError naming the mesh,
  // the template or the decomposition), std::invalid_argument for `fit` (a batch keeps one scale).
  explicit ObjectBatch(const ObjectBatchOptions& options);
  ~ObjectBatch();
  ObjectBatch(const ObjectBatch&) = delete;
  ObjectBatch& operator=(const ObjectBatch&) = delete;

  // The grasp of `placement` (its up, yaw or pose, and offset; its scale must be the batch's).
  // Throws as run_grasp does for anything but a refused start.
  BatchGrasp grasp(const ObjectPlacement& placement);

  const ObjectRunDescription& description() const;
  // The decomposed scene, or null.
  const DecomposedScene* decomposed() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace graspcd::grasp
