// What a grasp's verdicts are computed from, measured one state at a time (docs/design.md,
// "Semantics"; docs/run-record.md): the object's heights, speeds, energy, tilt, push and drift,
// the grip and the release on the true meshes (true_touch.h), the true meshes' penetration
// (true_penetration.h) and the ends of the six directions (six_directions.h). `graspcd grasp`
// feeds it the states of its own physics steps, `graspcd judge` the states of a run record, so
// that the verdicts (verdicts.h) of a run and of its judged record are the same.
//
// A state is handed over as an mjData whose kinematics are those of the state: xpos, xquat,
// xipos, geom_xpos and geom_xmat (mj_kinematics), subtree_com (mj_comPos), qM (mj_crb), cvel
// (mj_comVel); state_kinematics() computes them from qpos and qvel. After mj_step an mjData holds
// the kinematics of the state before the step (the step's forward pass): a live run hands over
// each state one physics step late, and the last one after state_kinematics().
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/grasp/grasp_result.h"
#include "graspcd/grasp/true_penetration.h"
#include "graspcd/grasp/true_touch.h"

namespace graspcd::grasp {

// The phases of a run, in order (docs/run-record.md); kDirection is each of the six directions.
enum class RunPhase { kStart, kClose, kSqueeze, kSettle, kLift, kHold, kDirection };

// The record's name of a phase: "start", "close", ..., and "dir+x" ... "dir-z" for kDirection
// with direction 0 .. 5.
std::string phase_record_name(RunPhase phase, int direction = -1);

// mj_kinematics, mj_comPos, mj_crb and mj_comVel on d's qpos and qvel: the kinematics the watch
// reads (the same functions, in the order mj_forward runs them).
void state_kinematics(const mjModel* m, mjData* d);

struct WatchOptions {
  // The touch tolerance (true_touch.h): kTouchDistance plus a simulator's inflation.
  double touch_tolerance = kTouchDistance;
  // Measure the true meshes' penetration on the start state and every `sample`-th state after it
  // (GraspOptions::true_penetration; the judge always does).
  bool true_penetration = false;
  int sample = 5;
  // The surfaces of the truth model's geoms, kept by the caller across runs (surface_cache.h;
  // null: the watch builds its own), and where the measure's time goes (its true_penetration
  // part; null: nowhere).
  SurfaceCache* surfaces = nullptr;
  GraspCost* cost = nullptr;
};

class MotionWatch {
 public:
  // `m`: the run's model (or the judged scene's); `truth`: the model of the true surfaces (m, or
  // a decomposed scene's true_object_model, with the same geom ids). `object`, `hand`,
  // `support`: body ids (support 0: the world).
  MotionWatch(const mjModel* m, const mjModel* truth, int object, int hand, int support,
              const WatchOptions& options);
  ~MotionWatch();
  MotionWatch(const MotionWatch&) = delete;
  MotionWatch& operator=(const MotionWatch&) = delete;

  // The state in d at simulated time t, of `phase` (`direction` 0 .. 5 for kDirection); `last`:
  // the phase's (the direction's) last state. States come in the run's order, from the start.
  void observe(const mjData* d, RunPhase phase, double t, bool last, int direction = -1);

  // The measures into `result`'s fields (grasp_result.h): heights, rise, travel, drift, slip,
  // tilts, speeds, energy, push, grip, release, fall, ejection, true penetration, directions.
  void fill(GraspResult& result) const;

  // The body heights are measured along (unit, -gravity; z without gravity) and from.
  const std::array<double, 3>& up() const { return up_; }
  int object() const { return object_; }
  int hand() const { return hand_; }

 private:
  double height(const mjData* d, int body) const;
  std::array<double, 3> object_in_hand(const mjData* d) const;
  double object_speed(const mjData* d) const;
  double fastest_other(const mjData* d) const;
  void watch_speed(const mjData* d, double t);
  void at_lift_start(const mjData* d, double t);
  void watch_direction(const mjData* d, bool last, int direction);
  void sample_penetration(const mjData* d, RunPhase phase, double t);

  const mjModel* m_;
  int object_, hand_, support_;
  WatchOptions options_;
  std::array<double, 3> up_{};
  std::vector<int> others_;  // bodies that can push the object: not the world, not its tree
  std::vector<double> others_reach_;  // how far each one's geoms reach from its centre of mass, m
  std::unique_ptr<TrueTouch> touch_;
  std::unique_ptr<TruePenetrationWatch> penetration_;

  // Everything measured so far (GraspResult's fields, filled by fill()).
  long states_ = 0;
  RunPhase phase_ = RunPhase::kStart;
  std::array<double, 3> start_{};       // the object's origin at the start, world
  std::array<double, 4> quat_start_{};  // its orientation then
  double start_height_ = 0;
  double drop_ = 0;           // how far below its start it can rest on its support, m
  double extent_ = 1;         // how far from its start it can go other than down, m
  double peak_com_ = 0;       // the highest its centre of mass has been along up, m (world)
  double fastest_other_ = 0;  // the fastest any point of another body has moved so far, m/s
  std::array<double, 3> last_position_{};  // its origin at the last state
  std::array<double, 3> squeeze_from_{};   // its origin at the start of the squeeze
  bool squeeze_seen_ = false;
  std::array<double, 4> quat_lift_{};
  std::array<double, 3> grip_local_{};  // the grip point in the object's frame
  double hand_at_lift_ = 0, grip_at_lift_ = 0;
  bool lifted_ = false;
  std::array<double, 3> hold_from_{};  // the object relative to the hand at the hold's start
  bool hold_started_ = false;
  bool hold_ended_ = false;
  GraspResult measured_;
  // The six directions: the object relative to the hand at the hold's end, the direction under
  // way (-1: none yet).
  std::array<double, 3> held_in_hand_{};
  int direction_ = -1;
};

}  // namespace graspcd::grasp
