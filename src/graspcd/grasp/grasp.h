// The grasp of paper section 9 on our scenes (mjcf/, mjcf/generator/generate_scenes.py): the
// fingers close in grasp steps of 0.003 rad until their segments' detectors report contact with the
// object, the hand squeezes, the arm lifts the object with gravity on, and holds it.
//
// Scene contract (the header comment of mjcf/example1.xml): hinge joints arm1..arm3 and
// finger{1..4}_{A,B,C}, one motor per joint named after it, finger geoms named after their
// segment, increasing a finger angle closes it, the object is the body `object` (free joint).
//
// Phases, all under one ComputedTorqueController on every joint (eq. (12)-(16)), physics steps as
// mj_step1 -> apply -> mj_step2:
//   1. Close (docs/design.md "Semantics"): grasp step k raises the target of every segment that has
//   not
//      stopped by 0.003 rad (with the matching velocity feed-forward) and runs
//      `physics_steps_per_grasp_step` physics steps. A segment touches when a contact between its
//      geom and an object geom appears in any physics step of the grasp step (with the bridge those
//      contacts are the output of the segment's served pairs, which get no native contacts; with
//      `native` they are MuJoCo's own). A touching segment stops, and so do the segments proximal
//      to it on its finger (GraspIt's autoGrasp rule; the paper does not say: a proximal joint
//      that kept closing pushes the object away with the touching segment, which on the C-block
//      drove the object 2.5 cm off); distal segments keep closing. A segment also stops at its
//      joint's upper limit. Closing ends when every finger has a segment that touched (the grip)
//      or after `max_steps` grasp steps.
//   2. Squeeze: every finger target rises by `squeeze` rad over `squeeze_time` s and is then held
//      (the grip force is D kp e of eq. (12)-(13) on the blocked joints), then `settle_time` s.
//   3. Lift: arm2 -> -a and arm3 -> +a along a cosine ramp over `lift_time` s (with velocity and
//      acceleration feed-forward), a = asin(lift_height / L) with L the arm2-arm3 distance: the
//      wrist rises by lift_height and the hand keeps its orientation (arm2 + arm3 = 0).
//   4. Hold `hold_time` s.
//
// The start state is the scene's first keyframe (<keyframe><key .../>: qpos, qvel, act, ctrl) when
// it has one, else MuJoCo's reference configuration qpos0 with zero controls; a driven hand's
// closing starts from the keyframe's controls. Before phase 1 the start state is checked
// (start_check.h), against the geometry each configuration collides. First the scene itself, on the
// true meshes (for --decomposed, the object as it was): an object that starts inside the hand, a
// finger or its support (by more than 0.5 mm), or wholly inside one, is bad input (GraspInputError
// naming the scene, "the start state is not valid: ..."). Then, under native collision (--native,
// --decomposed), the meshes as MuJoCo collides them, their convex hulls (check_hull_start): a hull
// that holds another geom more than 0.5 mm deep is a start that geometry cannot represent, refused
// as bad input with "cannot start with --native: MuJoCo collides mesh 'M' as its convex hull, which
// geom 'G' lies D mm inside at the start (a limit of the hull, not of the scene; graspcd's contacts
// start this scene)" ("--decomposed", "a limit of the pieces" for the pieces). The verdicts
// (docs/design.md, "Semantics"):
//  - gripped: at the end of the settling (just before the lift), two hand geoms touch the object
//    with opposing contact normals: the mean normals, from each geom into the object, of two
//    touching geoms have a negative dot product (kGripOpposing). One side pushing is no grip.
//  - held: gripped, not ejected, the object's grip point rose at least kHeldRiseShare (80%) of the
//    hand's travel from the start of the lift to the end of the hold, and the object moved by less
//    than kHeldSlip (1 cm) relative to the hand during the hold. The grip point is the mean of the
//    hand-object contacts at the start of the lift, carried with the object: a held object
//    hangs from the grip, and the point it hangs from rises with the hand however the object
//    turns about it (a bowl pinched at its rim hangs tilted and its origin rises less than the
//    hand; an object that slides down or falls takes its grip point with it).
//  - tilted: the object's rotation from its orientation at the start of the lift, the angle of
//    the relative rotation (2 acos |q0 . q|): tilt_deg the largest over the lift and the hold,
//    tilt_final_deg at the end. A held object whose final tilt is kTiltShownDeg (2 degrees) or
//    more is "held, tilted N°" (tilt_note): steady but not as it stood.
//  - ejected: after any physics step of any phase, the object was faster than kEjectSpeed
//    (2 m/s: no hand here moves an object faster than 0.4 m/s; MuJoCo's push out of a convex
//    hull throws objects at tens of m/s), its origin fell more than 2 R + 1 cm below where it
//    started (R: how far its geoms reach from its origin; resting on its support in any pose it
//    lies at most 2 R lower: it passed below its support), or it went farther from its start
//    than the scene's extent (at least 1 m). The first such step gives the time and the speed;
//    the run goes on, but the verdict is the ejection: never held, and its reason comes first.
//  - pushed: the object moved more than kSqueezePush (1 cm) from its place at the start of the
//    squeeze, at any physics step up to the start of the lift (squeeze_push, the largest move;
//    pushed_during_squeeze). It stays held when the rules above hold, but the verdict of a held
//    object says "held, pushed 12.0 cm during the squeeze" (push_note).
//  - dropped: gripped (and a segment touched in the closing), then from some physics step of the
//    lift or the hold on no hand geom touched the object for the rest of the run (release_time),
//    and at the end the object's rise fell short of the hand's travel by more than kHeldSlip: it
//    left the hand and fell. Never held; dropped_at is release_time. An ejection comes first: an
//    ejected object is never dropped.
//  - reason: why a grasp was not gripped or not held, one phrase (empty when held), the first
//    that applies: "ejected at t = 0.412 s (57.3 m/s)", "no segment reached the object", "no
//    segment touched the object after the squeeze", "no two touching segments push from opposing
//    sides", "dropped at t = 2.206 s", "slipped at t = 2.35 s" (still touched, moved 1 cm or more
//    in the hand), "its grip rose 1.2 cm of the hand's 6.0 cm travel (less than 80%)".
//
// Non-finite state: after every physics step the driver reads MuJoCo's warnings for a bad number
// (NaN, or beyond mjMAXVAL = 1e10) in qpos, qvel, qacc or ctrl (mjWARN_BADQPOS, mjWARN_BADQVEL,
// mjWARN_BADQACC, mjWARN_BADCTRL). MuJoCo 2.2 answers the first three by resetting the state to
// qpos0 (mj_checkPos, mj_checkVel, mj_checkAcc) and the last by zeroing the controls, so a grasp
// that went on would silently start over or drop its torques: run_grasp stops instead with a
// std::runtime_error, "SCENE: the simulation went non-finite ...", naming the phase, the grasp
// step or time, and the warning (the command line prints it on one line and exits with code 2).
// Served pairs that reach graspcd's callback with a bad placement are skipped and counted
// (BridgeStats::nonfinite_skips, per grasp step and in total).
#pragma once

#include <stdexcept>
#include <string>

#include "graspcd/grasp/grasp_result.h"
#include "graspcd/mujoco/model_loading.h"

namespace graspcd::grasp {

// Loads `scene_path` and runs the grasp. Throws GraspInputError for a missing or bad MJCF (the
// message "FILE: <MuJoCo's message on one line>"), or a missing or bad pair config (the
// registry's message, which starts with the config's name); std::runtime_error for a scene that
// breaks the scene contract, and for a simulation that goes non-finite (see above).
GraspResult run_grasp(const std::string& scene_path, const GraspOptions& options = {});

// A pair config's error as a GraspInputError with the file, line and message apart: the
// InputError of the pair config, the registry (mujoco/input_error.h) or the drive config as it
// is, any other std::runtime_error named by `config_path`.
GraspInputError config_error(const std::string& config_path, const std::runtime_error& e);

}  // namespace graspcd::grasp
