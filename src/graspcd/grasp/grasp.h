// The grasp of paper section 9 on our scenes (mjcf/, study/scenes/generate_scenes.py): the fingers
// close in grasp steps of 0.003 rad until their segments' detectors report contact with the
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
// Before phase 1 the start state is checked (start_check.h): an object that starts inside the
// hand, a finger or its support (by more than 0.5 mm), or wholly inside one, is bad input
// (GraspInputError naming the scene). The verdicts (docs/design.md, "Semantics"):
//  - gripped: at the end of the settling (just before the lift), two hand geoms touch the object
//    with opposing contact normals: the mean normals, from each geom into the object, of two
//    touching geoms have a negative dot product (kGripOpposing). One side pushing is no grip.
//  - held: gripped, the object rose at least kHeldRiseShare (80%) of the hand's travel from the
//    start of the lift to the end of the hold, and it moved by less than kHeldSlip (1 cm)
//    relative to the hand during the hold.
//  - reason: why a grasp was not gripped or not held, one phrase (empty when held): "no segment
//    reached the object", "no two touching segments push from opposing sides", "slipped at
//    t = 2.35 s", "rose 1.2 cm of the hand's 6.0 cm travel (less than 80%)".
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

#include <mujoco/mujoco.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspcd/core/separators.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::grasp {

inline constexpr double kGraspStepRad = 0.003;  // the paper's grasp step
inline constexpr int kFingerSegments = 12;      // finger{1..4}_{A,B,C}
// The verdicts (see above): the share of the hand's travel the object must rise, and the most it
// may move in the hand during the hold (m).
inline constexpr double kHeldRiseShare = 0.8;
inline constexpr double kHeldSlip = 0.01;

// A scene or config that cannot be used (model_loading.h): the file, the line and the message
// apart, printed as one line "FILE: MESSAGE" or "FILE:LINE: MESSAGE".
using GraspInputError = mujoco::InputError;

struct GraspOptions {
  std::string config_path;  // pair config; empty: SCENE.pairs.json beside the scene
  std::optional<Method> method;
  std::optional<int> cap;               // perceptron pass cap override
  std::optional<int> switch_passes;     // Neuro-SAT switch override
  bool native = false;                  // MuJoCo's own collision, no registry
  std::optional<bool> front_list;       // overrides the config's "front_list" (registry.h)
  std::optional<double> contact_reuse;  // overrides the config's "contact_reuse" (registry.h)
  int max_steps = 400;                  // most closing grasp steps
  // 5 steps of 2 ms per grasp step: a target ramp of 0.3 rad/s, tracked with the velocity
  // feed-forward within a few 1e-4 rad at omega = 40 rad/s.
  int physics_steps_per_grasp_step = 5;
  double omega = 40;  // eq. (15) critically damped, rad/s: kp = omega^2, kv = 2 omega
  double squeeze = 0.12;
  double squeeze_time = 0.1;
  double settle_time = 0.3;
  double lift_height = 0.06;
  double lift_time = 1.0;
  double hold_time = 2.0;
  // Called after each closing grasp step with the model, the state after the step's last physics
  // step and the 1-based step number (the study records the poses it replays, src/graspcd/study).
  std::function<void(const mjModel*, const mjData*, int)> on_grasp_step;
};

// One closing grasp step.
struct GraspStepRecord {
  int step = 0;                    // 1-based
  int contacts = 0;                // finger-object contacts after the step's last physics step
  std::vector<bool> touching;      // by GraspResult::segments: those with such a contact then
  std::uint64_t detection_ns = 0;  // tree query time over the step's physics steps (bridge)
  std::uint64_t box_tests = 0;
  std::uint64_t front_skips = 0;  // front pairs kept apart by their gap, untested
  std::uint64_t triangle_tests = 0;
  std::uint64_t served_calls = 0;
  std::uint64_t contained = 0;        // served calls that found a segment wholly inside the object
  std::uint64_t nonfinite_skips = 0;  // served calls skipped on a non-finite placement
  double object_z = 0;                // object body height after the step, m
};

struct GraspResult {
  std::string scene;
  bool native = false;
  std::string method;  // method name, or "native"
  std::vector<GraspStepRecord> steps;
  // What "touching" is reported for: the finger segments (finger_segment_names()) on our hands,
  // the "touch" patterns of the config's "grasp" section on a driven real hand (registry.h).
  std::vector<std::string> segments;
  std::vector<int> first_contact;  // by segments: grasp step, -1 when never
  // Two hand geoms touch the object with opposing contact normals before the lift (see above).
  bool gripped = false;
  // Heights are along -gravity (z for gravity along -z), relative to the support body of a
  // driven real hand (the world on our hands).
  double object_z_initial = 0;
  double object_z_gripped = 0;  // after the squeeze and settle
  double object_z_final = 0;
  double hold_min_z = 0;  // lowest object height during the final hold
  double hold_drift = 0;  // largest move of the object relative to the palm in the hold, m
  bool held = false;
  double hand_travel = 0;  // the hand's rise from the start of the lift to the end of the hold, m
  double object_rise = 0;  // the object's over the same time, m
  double slip_time = -1;   // simulated time at which the object had moved kHeldSlip in the hand
  std::string reason;      // why not gripped or not held (see above); empty when held
  // The last second of the hold (or the whole hold when shorter), "at rest": the object's largest
  // linear speed (m/s), the deepest contact of an object geom (-dist, m; 0 without contacts), and
  // the whole system's kinetic energy (J, 0.5 qvel^T M qvel) averaged over that window's first
  // and second halves.
  double rest_max_speed = 0;
  double rest_max_penetration = 0;
  double rest_energy_early = 0;
  double rest_energy_late = 0;
  // MuJoCo's warning counters of the grasp's mjData at the end (d->warning[].number): the contact
  // buffer (nconmax) and the constraint buffer (njmax) were full in this many steps.
  int contact_buffer_full = 0;
  int constraint_buffer_full = 0;
  double sim_time = 0;  // simulated seconds, all phases
  long physics_steps = 0;
  double step_wall_ms = 0;  // mean wall time per physics step (mj_step1 + control + mj_step2)
  std::uint64_t detection_ns_close = 0;  // summed over the closing grasp steps
  std::uint64_t detection_ns_total = 0;  // all phases
  int max_contacts = 0;                  // most finger-object contacts in one physics step
  double mean_contacts = 0;              // finger-object contacts per physics step, all phases
  int max_pair_contacts = 0;             // most of them one geom pair had in one physics step
  std::uint64_t contained_calls = 0;     // containment findings over all phases (registry.h)
  std::uint64_t nonfinite_skips = 0;  // served calls skipped on a non-finite placement, all phases
  std::uint64_t reused_calls = 0;     // served calls answered by reused contacts, all phases
  // The registry's warnings (registry.h, Registry::warnings()), one line each.
  std::vector<std::string> warnings;
};

// The segment names in record order: finger1_A, finger1_B, ..., finger4_C.
const std::array<std::string, kFingerSegments>& finger_segment_names();

// Loads `scene_path` and runs the grasp. Throws GraspInputError for a missing or bad MJCF (the
// message "FILE: <MuJoCo's message on one line>"), or a missing or bad pair config (the
// registry's message, which starts with the config's name); std::runtime_error for a scene that
// breaks the scene contract, and for a simulation that goes non-finite (see above).
GraspResult run_grasp(const std::string& scene_path, const GraspOptions& options = {});

// The system's kinetic energy, 0.5 qvel^T M qvel with the joint-space inertia of the last step
// (mj_energyVel's formula; MuJoCo 2.2 fills d->energy only with the energy flag enabled), J.
double kinetic_energy(const mjModel* m, const mjData* d);

// A pair config's error as a GraspInputError with the file, line and message apart: a
// GraspInputError of drive_config.h as it is, a std::runtime_error of registry.h or json_config.h
// (whose message starts "CONFIG: " or "CONFIG:LINE: ") taken apart.
GraspInputError config_error(const std::string& config_path, const std::runtime_error& e);

}  // namespace graspcd::grasp
