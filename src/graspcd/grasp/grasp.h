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
// The start is the scene's first keyframe, else qpos0 with zero controls. It is checked first
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

#include <string>

#include "graspcd/grasp/grasp_result.h"
#include "graspcd/mujoco/model_loading.h"

namespace graspcd::grasp {

// Loads `scene_path` and runs the grasp. Throws io::InputError for a missing or bad scene or pair
// config, a refused start and an error of MuJoCo's, each naming its file (as options.names has
// it for a scene graspcd wrote); std::runtime_error for a scene that breaks the scene contract
// and for a simulation that goes non-finite.
GraspResult run_grasp(const std::string& scene_path, const GraspOptions& options = {});

}  // namespace graspcd::grasp
