// One grasp run (grasp.h, run_grasp) on either hand: the phases of paper section 9 (close in grasp
// steps, squeeze, settle, lift, hold) and, when asked, the six-direction test (six_directions.h),
// the physics steps with their contact scan and non-finite check, the MuJoCo layer's statistics,
// the run record (run_record.h) and the verdicts: every state goes to the motion watch
// (motion_watch.h), whose measures the one verdict function judges (verdicts.h). HandRun holds
// that structure once; a hand says how it moves through the hooks below: our four-finger hand
// (grasp_run.h, joint targets of the computed-torque controller) and a driven real hand
// (driven_run.h, the controls of its own actuators). Phase lengths are counted in physics steps:
// phase_steps converts a phase's seconds.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/grasp/grasp_result.h"
#include "graspcd/grasp/motion_watch.h"
#include "graspcd/grasp/run_record.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

class HandRun {
 public:
  HandRun(const mjModel* m, mjData* d, mujoco::Registry* registry, const std::string& scene);
  virtual ~HandRun() = default;
  HandRun(const HandRun&) = delete;
  HandRun& operator=(const HandRun&) = delete;

  int object() const { return object_; }
  int hand() const { return hand_; }
  // The body heights are measured from (0: the world).
  virtual int support_body() const { return 0; }

  // The model whose geoms are the true surfaces the verdicts' touch and the run's penetration
  // are measured on (true_touch.h, true_penetration.h): for a decomposed scene its
  // true_object_model (decomposed_pieces.h); by default the run's own model. Must outlive the run.
  void set_truth(const mjModel* truth) { truth_ = truth; }
  // The surfaces of the truth model's geoms (surface_cache.h), kept across runs by the caller
  // (without: the run builds its own). Must outlive the run.
  void set_surfaces(SurfaceCache* surfaces) { surfaces_ = surfaces; }
  // Where the run's states go (GraspOptions::write_run): the start state, every physics step.
  // Must outlive the run.
  void set_record(RunRecordWriter* record) { record_ = record; }
  // The run's model as the six-direction test changes it for its runs (gravity off, the support
  // out of collision; restored after): the model the run was built on. Without it the test is
  // not run.
  void set_mutable_model(mjModel* m) { mutable_m_ = m; }

  // Runs the phases and fills `result`'s grasp fields (the caller fills scene, method, warnings).
  void run(const GraspOptions& options, GraspResult& result);

 protected:
  // One physics step's MuJoCo calls (and the control law between them), timed.
  virtual void advance() = 0;
  // The object's height along -gravity (GraspStepRecord::object_z).
  virtual double object_height() const = 0;

  // Phase 1, grasp step k: begin_grasp_step(k), then for p = 1..n grasp_step_targets(p, n) before
  // physics step p; after the step's record, whether the closing is done (`touched`: the segments
  // that touched in one of the step's physics steps; result.first_contact is up to date).
  virtual void begin_grasp_step(int k) = 0;
  virtual void grasp_step_targets(int p, int n) = 0;
  virtual bool closing_done(int k, const std::vector<bool>& touched, const GraspResult& result) = 0;
  virtual void end_closing() {}
  // Phase 2, the squeeze: step i of `steps`.
  virtual void begin_squeeze() = 0;
  virtual void squeeze_targets(long i, long steps) = 0;
  // Phase 3, the lift: step i of `steps`.
  virtual void begin_lift() = 0;
  virtual void lift_targets(long i, long steps) = 0;
  virtual void end_lift() {}

  // The physics steps of a phase `seconds` long, at least one.
  long phase_steps(double seconds) const;
  // The time since the phase's start after physics step i of it, s.
  double phase_time(long i) const { return static_cast<double>(i) * m_->opt.timestep; }
  // The object body (its body tree's geoms are the object's) and the segments: segment s (added
  // s-th, reported under `name`) touches when one of its geoms touches an object geom.
  void set_object(int body);
  int add_segment(const std::string& name);
  void add_segment_geom(int geom, int segment);

  const mjModel* m_;
  mjData* d_;
  int object_ = -1;
  int hand_ = -1;  // the body the object's drift in the hand is measured against

 private:
  // Counts the longest run of one geom pair among the counted contacts of a step (MuJoCo writes
  // each geom pair's contacts consecutively): the most contacts one pair handed the solver.
  struct PairRun {
    int last = -2, g1 = -1, g2 = -1, run = 0, most = 0;
    void start() { last = -2; }
    void add(int i, int geom1, int geom2);
  };
  // The MuJoCo layer's counters summed over a whole grasp (every phase), as GraspResult reports
  // them.
  struct BridgeTotals {
    std::uint64_t detection_ns = 0, contained = 0, nonfinite_skips = 0, reused = 0;
    void add(const mujoco::BridgeStats& s);
  };

  void physics_step();
  mujoco::BridgeStats take_stats();
  template <class Targets, class Observe>
  void run_phase(RunPhase phase, long steps, Targets at, Observe observe);
  void close(const GraspOptions& options, GraspResult& result);
  void hold(const GraspOptions& options, GraspResult& result);
  void six_directions();
  // The state d_ holds now (after state_kinematics) to the watch as its phase's last.
  void observe_now();
  void scan_contacts();
  void finish(GraspResult& result) const;

  mujoco::Registry* registry_;
  std::string scene_;
  std::string phase_ = "the closing";  // for messages
  std::vector<std::string> segments_;
  std::vector<std::vector<int>> segments_of_geom_;
  std::vector<char> is_object_geom_;
  std::vector<bool> touching_;  // by segment, in the last physics step
  int contacts_ = 0, max_contacts_ = 0;
  long contacts_sum_ = 0;
  PairRun pair_run_;
  long physics_steps_ = 0;
  PartTime step_time_;     // of the physics steps: the thread's CPU time and the wall time
  double start_time_ = 0;  // MuJoCo's clock at the start: the first keyframe's time, else 0
  BridgeTotals totals_;
  const mjModel* truth_ = nullptr;
  SurfaceCache* surfaces_ = nullptr;
  GraspCost* cost_ = nullptr;  // the running grasp's (GraspResult::cost)
  // The running grasp's GraspOptions::on_physics_step (none outside run()).
  const std::function<void(const mjModel*, const mjData*, const std::string&, long)>*
      on_physics_step_ = nullptr;
  mjModel* mutable_m_ = nullptr;
  RunRecordWriter* record_ = nullptr;
  std::unique_ptr<MotionWatch> watch_;
  // The physics step under way: its phase, grasp step (the closing's) and direction (the six
  // directions'); and the state before it, which d_'s kinematics are of after the step: its
  // phase, direction and time, and whether the watch has seen it already (a direction's first
  // step starts from the hold's last state).
  RunPhase phase_kind_ = RunPhase::kStart;
  int grasp_step_ = 0;
  int direction_ = -1;
  RunPhase before_phase_ = RunPhase::kStart;
  int before_direction_ = -1;
  double before_time_ = 0;
  bool before_seen_ = false;
};

// Looks up a named element of the scene; a missing one breaks the scene contract.
int require_id(const mjModel* m, mjtObj type, const std::string& name, const std::string& scene,
               const char* what);

}  // namespace graspcd::grasp
