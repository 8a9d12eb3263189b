// The grasp of paper section 9: the fingers close in grasp steps of 0.003 rad until their segments
// touch the object, the hand squeezes, the arm lifts the object with gravity on, and holds it.
//
// Scene contract (the header comment of mjcf/example1.xml): hinge joints arm1..arm3 and
// finger{1..4}_{A,B,C}, one motor per joint named after it, finger geoms named after their
// segment, increasing a finger angle closes it, the object is the body `object` (free joint). A
// hand driven through its own actuators follows its pair config's "grasp" section instead
// (drive_config.h, driven_run.h).
//
// Phases, under one ComputedTorqueController on every joint (eq. (12)-(16)):
//   1. Close: each grasp step raises the target of every segment that has not stopped by 0.003
//      rad and runs `physics_steps_per_grasp_step` physics steps. A segment that touches the object
//      stops, and so do the segments proximal to it on its finger (GraspIt's autoGrasp rule);
//      one also stops at its joint's limit. Closing ends when every finger has touched, or after
//      `max_steps` grasp steps.
//   2. Squeeze: the finger targets rise by `squeeze` rad over `squeeze_time` s, then `settle_time`.
//   3. Lift: the wrist rises by `lift_height` over `lift_time` s, the hand keeping its orientation.
//   4. Hold `hold_time` s.
//
// The start is the scene's first keyframe, else qpos0 with zero controls. The keyframe's time is
// where MuJoCo's clock starts: the events (ejected, dropped, slipped, the deepest penetration) are
// times on that clock and sim_time the seconds simulated since; a time before 0 is bad input
// naming the scene. The start is checked first
// (start_check.h): on the true meshes, then, under native collision, on the convex hulls MuJoCo
// collides; a start beyond kStartPenetration is bad input naming the scene ("the start state is
// not valid: ...", "cannot start with --native: ...").
//
// The verdicts (GraspResult; docs/design.md, "Semantics"): computed from the motion by
// verdicts.h's judge_grasp on what the motion watch measured (motion_watch.h), the same function
// `graspcd judge` calls on a run record: held (carried with the hand, whatever touched it),
// gripped (two hand geoms touching it from opposing sides at the start of the lift, true
// meshes), ejected (a speed or a path gravity and the hand cannot give), dropped (it fell off its
// support, or left the hand behind its path), pushed over, tilted, pushed, and a closing cut
// short by --max-steps; `reason` says why a grasp was not held, and is empty when it was.
//
// Non-finite state: MuJoCo 2.2 resets a state with a bad number (NaN or beyond 1e10) in qpos,
// qvel or qacc and zeroes bad controls; run_grasp stops instead with a std::runtime_error "SCENE:
// the simulation went non-finite ..." naming the phase, the step and the warning.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "graspcd/grasp/grasp_result.h"
#include "graspcd/mujoco/model_loading.h"

namespace graspcd::grasp {

// A scene loaded once and grasped from its start as often as asked: a batch of grasps of one
// object in one hand (object_batch.h) compiles the model, builds the trees and the surfaces once,
// and moves the object between grasps. Each grasp starts from the state mj_makeData makes (the
// first keyframe when the scene has one), its served pairs' state forgotten, so that a grasp gives
// what run_grasp gives on the scene as it stands. The scene's own cost (compile, trees) goes with
// its first grasp (GraspResult::cost). Not thread-safe; one thread grasps a scene. Throws as
// run_grasp does.
class GraspScene {
 public:
  GraspScene(const std::string& scene_path, const GraspOptions& options);
  ~GraspScene();
  GraspScene(const GraspScene&) = delete;
  GraspScene& operator=(const GraspScene&) = delete;

  const std::string& scene() const { return scene_path_; }
  const GraspOptions& options() const { return options_; }
  mjModel* model();

  // Moves the start of `body`, which has one free joint, to `pos` and `quat` (w x y z, a unit
  // quaternion) as if the scene had been compiled with the body there: its body_pos, body_quat,
  // qpos0 (and qpos_spring) and the constants MuJoCo computes from qpos0 (mj_setConst). The
  // model is then the one the compiler makes of the scene with that body's pos and quat (the
  // quaternion normalised as the compiler does; a decomposed scene's true object moved alike).
  // Its time is the next grasp's "placement" part. Throws std::invalid_argument for another
  // body, and in a scene with a keyframe (which sets the start).
  void place_free_body(int body, const std::array<double, 3>& pos,
                       const std::array<double, 4>& quat);

  // The grasp from the start. A refused start throws the io::InputError naming the scene.
  GraspResult grasp();
  // Why a start was refused: its error, and whether only the geometry MuJoCo collides refused it
  // (`hull`: --native's hulls, --decomposed's pieces; the true meshes' start is valid) or the
  // true meshes did.
  struct Refusal {
    std::optional<io::InputError> error;
    bool hull = false;
    GraspCost cost;  // the time it took (with the scene's own parts on a first grasp)
  };
  // The same, but a refused start returns none and says why in `refusal`.
  std::optional<GraspResult> grasp_if_valid(Refusal* refusal);

 private:
  struct Loaded;
  GraspOptions options_;
  std::string scene_path_;
  GraspCost setup_cost_;
  std::unique_ptr<Loaded> loaded_;
};

// Loads `scene_path` and runs the grasp. Throws io::InputError for a missing or bad scene or pair
// config, a refused start and an error of MuJoCo's, each naming its file (as options.names has
// it for a scene graspcd wrote); std::runtime_error for a scene that breaks the scene contract
// and for a simulation that goes non-finite.
GraspResult run_grasp(const std::string& scene_path, const GraspOptions& options = {});

}  // namespace graspcd::grasp
