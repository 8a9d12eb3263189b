// What a grasp of the paper's section 9 (grasp.h) is asked and what it reports: its options, its
// record per grasp step, its result and verdicts, and the measures the verdicts use. Shared by
// run_grasp and the runs of each hand (hand_run.h).
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

#include "graspcd/core/contact_manifold.h"
#include "graspcd/core/separators.h"
#include "graspcd/grasp/true_penetration.h"
#include "graspcd/io/input_error.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::grasp {

inline constexpr double kGraspStepRad = 0.003;  // the paper's grasp step
inline constexpr int kFingerSegments = 12;      // finger{1..4}_{A,B,C}
// The verdicts (grasp.h): the share of the hand's travel the object's grip point must rise, and
// the most the object may move in the hand during the hold (m).
inline constexpr double kHeldRiseShare = 0.8;
inline constexpr double kHeldSlip = 0.01;
// The most the object may move from the start of the squeeze to the start of the lift before the
// verdict says it was pushed (grasp.h, "pushed"), m: the slip the hold allows. An object moved
// farther was not gripped where the fingers closed on it (thrown up, tipped over, slid), even if
// the hand then lifts it.
inline constexpr double kSqueezePush = 0.01;
// The speed past which an object has been thrown, not moved by the hand (grasp.h, "ejected"),
// m/s. The fastest the hands move an object in a grasp: the lift's peak, pi/2 * 6 cm / 1 s =
// 0.09 m/s, and the real hands' closing, up to 0.35 m/s on the shipped scenes (the Shadow hand);
// MuJoCo's push out of a convex hull throws objects at 50-60 m/s. 2 m/s leaves a margin of five
// below and twenty-five above.
inline constexpr double kEjectSpeed = 2.0;
// The verdict text names the object's final tilt from this many degrees on (grasp.h, "tilted").
inline constexpr double kTiltShownDeg = 2.0;

struct GraspOptions {
  std::string config_path;  // pair config; empty: SCENE.pairs.json beside the scene
  // How messages name the files of a scene graspcd wrote (mujoco/scene_names.h: an object's scene,
  // a decomposed scene); empty: as they are.
  mujoco::SceneNames names;
  std::optional<Method> method;
  std::optional<int> cap;               // perceptron pass cap override
  std::optional<int> switch_passes;     // Neuro-SAT switch override
  bool native = false;                  // MuJoCo's own collision, no registry
  std::optional<bool> front_list;       // overrides the config's "front_list" (registry.h)
  std::optional<double> contact_reuse;  // overrides the config's "contact_reuse" (registry.h)
  // Override the config's "reduction" and "max_contacts" (pair_config.h; parse_manifold_choice).
  std::optional<ManifoldReduction> reduction;
  std::optional<int> max_contacts;
  int max_steps = 400;  // most closing grasp steps
  // 5 steps of 2 ms per grasp step: a target ramp of 0.3 rad/s, tracked with the velocity
  // feed-forward within a few 1e-4 rad at omega = 40 rad/s.
  int physics_steps_per_grasp_step = 5;
  // The scene's time step divided by this, and this many times the physics steps per grasp step,
  // so that the drive is the same in time (a finer run of the same grasp: the object-set study's
  // reference runs at 4). 1: the scene's step.
  int timestep_divisor = 1;
  double omega = 40;  // eq. (15) critically damped, rad/s: kp = omega^2, kv = 2 omega
  double squeeze = 0.12;
  double squeeze_time = 0.1;
  double settle_time = 0.3;
  double lift_height = 0.06;
  double lift_time = 1.0;
  double hold_time = 2.0;
  // Measure the true meshes' penetration once per grasp step (true_penetration.h; GraspResult::
  // true_penetration). `graspcd grasp` always does; off by default in the library, where the
  // study's recordings and the tests that only need a verdict would pay its exact inside tests
  // (1 to 6 s of CPU per grasp on the shipped scenes, several times the grasp's own).
  bool true_penetration = false;
  // MuJoCo's noslip solver iterations (mjOption.noslip_iterations: after the main solver, a pass
  // that removes the contacts' slip); none: the scene's (MuJoCo's default 0, off).
  std::optional<int> noslip_iterations;
  // MuJoCo's multi-point convex collision (mjENBL_MULTICCD in mjOption.enableflags) for the run:
  // the pairs MuJoCo collides itself through its general convex routine (mesh-mesh, mesh-box,
  // cylinder and capsule pairs with a mesh; not spheres and ellipsoids, not plane-mesh, box-box
  // or capsule-box, which have their own routines) get, beside the first contact, up to four
  // more found by tilting the two geoms 1e-3 rad about the first contact's tangents. It applies
  // to whatever collides natively (native, decomposed, and the unserved pairs of a served run),
  // never to graspcd's served pairs. true: on, false: off; none: the scene's flag (MuJoCo's
  // default: off; MJCF <flag multiccd="enable"/>).
  std::optional<bool> multiccd;
  // Called after each closing grasp step with the model, the state after the step's last physics
  // step and the 1-based step number (the study records the poses it replays, src/graspcd/study).
  std::function<void(const mjModel*, const mjData*, int)> on_grasp_step;
};

// One closing grasp step.
struct GraspStepRecord {
  int step = 0;                    // 1-based
  int contacts = 0;                // finger-object contacts after the step's last physics step
  std::vector<bool> touching;      // by GraspResult::segments: those with such a contact then
  std::uint64_t detection_ns = 0;  // tree query time over the step's physics steps
  std::uint64_t box_tests = 0;
  std::uint64_t front_skips = 0;  // front pairs kept apart by their gap, untested
  std::uint64_t triangle_tests = 0;
  std::uint64_t served_calls = 0;
  std::uint64_t contained = 0;        // served calls that found a segment wholly inside the object
  std::uint64_t nonfinite_skips = 0;  // served calls skipped on a non-finite placement
  double object_z = 0;                // object body height after the step, m
};

// Where and how fast the object left the grasp (grasp.h, "ejected"): the simulated time of the
// first physics step that saw it, the object's speed then (m/s), and what was seen: "speed"
// (faster than kEjectSpeed), "below" (below its support) or "away" (out of the scene).
struct Ejection {
  double time = 0;
  double speed = 0;
  std::string cause;
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
  // The rise of the object's grip point (the mean of its contacts with the hand before the lift,
  // carried with the object) over the hand's travel, m (grasp.h, "held").
  double grip_rise = 0;
  // The angle between the object's orientation at the start of the lift and its orientation at
  // any later step (the largest) and at the end of the hold, degrees.
  double tilt_deg = 0;
  double tilt_final_deg = 0;
  double max_speed = 0;  // the object's largest linear speed over all phases, m/s
  // The object's largest kinetic energy over all phases (every physics step): 0.5 v^T M v over
  // the degrees of freedom of its body tree (object_kinetic_energy), J.
  double kinetic_energy_max = 0;
  // The true meshes' penetration over the run, measured once per grasp step whatever geometry
  // collided (true_penetration.h), with GraspOptions::true_penetration; else measures == 0.
  TruePenetration true_penetration;
  int noslip_iterations = 0;        // MuJoCo's noslip iterations the run used (GraspOptions)
  bool multiccd = false;            // whether the run's model had mjENBL_MULTICCD on (GraspOptions)
  std::optional<Ejection> ejected;  // the first sign that the object was thrown out, if any
  // The object's largest move (its origin, in the world) from where it was at the start of the
  // squeeze, over the squeeze and the settling, m; more than kSqueezePush: pushed (grasp.h).
  double squeeze_push = 0;
  bool pushed_during_squeeze = false;
  // From the start of the lift: the simulated time after which no hand geom touched the object
  // for the rest of the run, s; -1 when one touched it at the end.
  double release_time = -1;
  // When a gripped object left the hand and fell (grasp.h, "dropped"): release_time; else none.
  std::optional<double> dropped_at;
  std::string reason;  // why not gripped or not held (see above); empty when held
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
  double timestep = 0;  // MuJoCo's time step the run took, s (the scene's / timestep_divisor)
  int physics_steps_per_grasp_step = 0;
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

// What the verdict of a held object adds: "tilted 12°" for a final tilt of kTiltShownDeg or
// more, else "".
std::string tilt_note(const GraspResult& result);

// What the verdict of a held object adds when the squeeze pushed it (grasp.h, "pushed"): "pushed
// 12.0 cm during the squeeze", else "".
std::string push_note(const GraspResult& result);

// The verdicts (grasp.h) from the run's measures in `result` (hand_travel, grip_rise, hold_drift,
// slip_time, ejected, squeeze_push, release_time, object_rise): sets gripped, held,
// pushed_during_squeeze, dropped_at and reason. `ever_touched`: a segment touched the object in
// the closing; `touching`: the hand geoms that touched it at the start of the lift; `opposing`:
// two of them pushed from opposing sides then.
void judge_grasp(bool ever_touched, int touching, bool opposing, GraspResult& result);

// A manifold choice of `grasp --manifold`: "support", "moment" or "force" (pair_config.h,
// "reduction"), optionally followed by the contacts per pair, 1 .. mjMAXCONPAIR ("force4"); the
// count is absent when not given. std::nullopt for anything else.
struct ManifoldChoice {
  ManifoldReduction reduction = ManifoldReduction::kSupport;
  std::optional<int> max_contacts;
};
std::optional<ManifoldChoice> parse_manifold_choice(const std::string& text);

// The segment names in record order: finger1_A, finger1_B, ..., finger4_C.
const std::array<std::string, kFingerSegments>& finger_segment_names();

// The system's kinetic energy, 0.5 qvel^T M qvel with the joint-space inertia of the last step
// (mj_energyVel's formula; MuJoCo 2.2 fills d->energy only with the energy flag enabled), J.
double kinetic_energy(const mjModel* m, const mjData* d);

// The kinetic energy of the body tree of `body` alone: 0.5 v^T M v with v the velocities of the
// degrees of freedom of that tree (the others zero) and M the joint-space inertia of the last
// step, J. For a free object (its own kinematic tree) this is its kinetic energy exactly: M has
// no coupling between separate trees. `scratch` (resized as needed) avoids an allocation per call.
double object_kinetic_energy(const mjModel* m, const mjData* d, int body,
                             std::vector<mjtNum>& scratch);

}  // namespace graspcd::grasp
