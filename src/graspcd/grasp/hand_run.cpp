#include "graspcd/grasp/hand_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "graspcd/grasp/grasp_cost.h"
#include "graspcd/grasp/six_directions.h"
#include "graspcd/grasp/verdicts.h"
#include "graspcd/mujoco/mujoco_ptr.h"

namespace graspcd::grasp {

namespace {

// Stops the grasp when MuJoCo found a bad number in the state or the controls during the last
// physics step (grasp.h, "Non-finite state"): it has reset the state or zeroed the controls.
void throw_if_nonfinite(const mjData* d, const std::string& scene, const std::string& phase,
                        long physics_steps) {
  static const std::array<std::pair<int, const char*>, 4> kBad = {{
      {mjWARN_BADQPOS, "qpos"},
      {mjWARN_BADQVEL, "qvel"},
      {mjWARN_BADQACC, "qacc"},
      {mjWARN_BADCTRL, "ctrl"},
  }};
  for (const auto& [warning, what] : kBad) {
    const mjWarningStat& w = d->warning[warning];
    if (w.number == 0) continue;
    throw std::runtime_error(
        scene + ": the simulation went non-finite in " + phase + " (physics step " +
        std::to_string(physics_steps) + "): MuJoCo found a bad number (NaN or beyond 1e10) in " +
        what + " at index " + std::to_string(w.lastinfo) +
        (warning == mjWARN_BADCTRL ? " and zeroed the controls" : " and reset the state") +
        "; the grasp stops");
  }
}

// Appends grasp step k's record (its contacts, segments touching, the MuJoCo layer's counters over
// the step, the object's height) to the result, and adds its detection time to the closing's.
void add_step_record(int k, int contacts, std::vector<bool> touching,
                     const mujoco::BridgeStats& stats, double object_z, GraspResult& result) {
  GraspStepRecord record;
  record.step = k;
  record.contacts = contacts;
  record.touching = std::move(touching);
  record.detection_ns = stats.detection_ns;
  record.box_tests = stats.counters.box_tests;
  record.front_skips = stats.counters.front_skips;
  record.triangle_tests = stats.counters.tri_tests;
  record.served_calls = stats.calls;
  record.contained = stats.contained;
  record.nonfinite_skips = stats.nonfinite_skips;
  record.object_z = object_z;
  result.steps.push_back(std::move(record));
  result.detection_ns_close += stats.detection_ns;
}

// One physics step of the hold: when it lies in the last second of the hold ("at rest",
// grasp.h), the object's speed, the deepest contact of an object geom and the system's kinetic
// energy go into the result's rest fields. `step` counts from 1 to `steps`.
void watch_rest(const mjModel* m, mjData* d, int object, const std::vector<char>& is_object_geom,
                long step, long steps, GraspResult& result) {
  const long window = std::min(steps, std::lround(1.0 / m->opt.timestep));
  const long first = steps - window + 1;
  if (step < first) return;
  mjtNum velocity[6];
  mj_objectVelocity(m, d, mjOBJ_BODY, object, velocity, 0);
  const double speed =
      std::sqrt(velocity[3] * velocity[3] + velocity[4] * velocity[4] + velocity[5] * velocity[5]);
  result.rest_max_speed = std::max(result.rest_max_speed, speed);
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if (is_object_geom[static_cast<std::size_t>(c.geom1)] ||
        is_object_geom[static_cast<std::size_t>(c.geom2)]) {
      result.rest_max_penetration = std::max(result.rest_max_penetration, -c.dist);
    }
  }
  const double energy = kinetic_energy(m, d);
  const long half = window / 2;
  const double share = energy / static_cast<double>(std::max(1L, half));
  if (step < first + half) {
    result.rest_energy_early += share;
  } else if (step < first + 2 * half) {
    result.rest_energy_late += share;
  }
}

}  // namespace

int require_id(const mjModel* m, mjtObj type, const std::string& name, const std::string& scene,
               const char* what) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::runtime_error(scene + ": no " + what + " named " + name);
  return id;
}

void HandRun::PairRun::add(int i, int geom1, int geom2) {
  run = i == last + 1 && geom1 == g1 && geom2 == g2 ? run + 1 : 1;
  last = i;
  g1 = geom1;
  g2 = geom2;
  most = std::max(most, run);
}

void HandRun::BridgeTotals::add(const mujoco::BridgeStats& s) {
  detection_ns += s.detection_ns;
  contained += s.contained;
  nonfinite_skips += s.nonfinite_skips;
  reused += s.reused;
}

HandRun::HandRun(const mjModel* m, mjData* d, mujoco::Registry* registry, const std::string& scene)
    : m_(m),
      d_(d),
      registry_(registry),
      scene_(scene),
      segments_of_geom_(static_cast<std::size_t>(m->ngeom)) {}

void HandRun::set_object(int body) {
  object_ = body;
  is_object_geom_.assign(static_cast<std::size_t>(m_->ngeom), 0);
  for (int g = 0; g < m_->ngeom; ++g) {
    is_object_geom_[static_cast<std::size_t>(g)] = m_->body_rootid[m_->geom_bodyid[g]] == body;
  }
}

int HandRun::add_segment(const std::string& name) {
  segments_.push_back(name);
  touching_.push_back(false);
  return static_cast<int>(segments_.size()) - 1;
}

void HandRun::add_segment_geom(int geom, int segment) {
  segments_of_geom_[static_cast<std::size_t>(geom)].push_back(segment);
}

long HandRun::phase_steps(double seconds) const {
  return std::max(1L, std::lround(seconds / m_->opt.timestep));
}

// One physics step (the hand's advance, timed), MuJoCo's non-finite check, the scan of the
// segment-object contacts, then the state before the step (whose kinematics d_ holds after it,
// motion_watch.h) to the watch, and the state after it to the run record.
void HandRun::physics_step() {
  const CostInstant start = CostInstant::now();
  advance();
  step_time_ += CostInstant::now().since(start);
  ++physics_steps_;
  throw_if_nonfinite(d_, scene_, phase_, physics_steps_);
  scan_contacts();
  if (!before_seen_) {
    const bool last = before_phase_ != phase_kind_ || before_direction_ != direction_;
    watch_->observe(d_, before_phase_, before_time_, last, before_direction_);
  }
  before_seen_ = false;
  before_phase_ = phase_kind_;
  before_direction_ = direction_;
  before_time_ = d_->time;
  if (record_) record_->step(m_, d_, phase_kind_, grasp_step_, direction_, object_);
}

void HandRun::observe_now() {
  state_kinematics(m_, d_);
  watch_->observe(d_, before_phase_, before_time_, true, before_direction_);
  before_seen_ = true;
}

// The contacts between a segment's geom and an object geom: the segments they touch, how many,
// and the most one geom pair had.
void HandRun::scan_contacts() {
  std::fill(touching_.begin(), touching_.end(), false);
  contacts_ = 0;
  pair_run_.start();
  for (int i = 0; i < d_->ncon; ++i) {
    const auto g1 = static_cast<std::size_t>(d_->contact[i].geom1);
    const auto g2 = static_cast<std::size_t>(d_->contact[i].geom2);
    const std::vector<int>* segments = nullptr;
    if (is_object_geom_[g2] && !segments_of_geom_[g1].empty()) segments = &segments_of_geom_[g1];
    if (is_object_geom_[g1] && !segments_of_geom_[g2].empty()) segments = &segments_of_geom_[g2];
    if (segments == nullptr) continue;
    for (int s : *segments) touching_[static_cast<std::size_t>(s)] = true;
    ++contacts_;
    pair_run_.add(i, d_->contact[i].geom1, d_->contact[i].geom2);
  }
  max_contacts_ = std::max(max_contacts_, contacts_);
  contacts_sum_ += contacts_;
}

// The MuJoCo layer's statistics since the last call (zero with native collision).
mujoco::BridgeStats HandRun::take_stats() {
  if (!registry_) return mujoco::BridgeStats{};
  const mujoco::BridgeStats s = registry_->take_stats();
  totals_.add(s);
  return s;
}

// Runs `steps` physics steps of `phase`; at(i) sets the targets before step i (1 to steps),
// observe() sees the state after each.
template <class Targets, class Observe>
void HandRun::run_phase(RunPhase phase, long steps, Targets at, Observe observe) {
  static const char* const kNames[] = {"the start",         "the closing", "the squeeze",
                                       "the settling",      "the lift",    "the hold",
                                       "the six directions"};
  phase_ = kNames[static_cast<int>(phase)];
  phase_kind_ = phase;
  const bool call =
      on_physics_step_ != nullptr && *on_physics_step_ && phase != RunPhase::kDirection;
  const std::string name = call ? phase_record_name(phase) : std::string();
  for (long i = 1; i <= steps; ++i) {
    at(i);
    physics_step();
    observe();
    if (call) {
      const CostTimer timer(cost_, CostPart::kJudge);
      (*on_physics_step_)(m_, d_, name, i);
    }
  }
}

// Phase 1, paper section 9 (docs/design.md "Semantics"): grasp steps until the hand says the
// closing is done; a segment's first contact is the grasp step in which it first touched.
void HandRun::close(const GraspOptions& options, GraspResult& result) {
  const int n = std::max(1, options.physics_steps_per_grasp_step);
  const std::size_t segments = segments_.size();
  phase_kind_ = RunPhase::kClose;
  result.closing = "max_steps";
  result.max_steps = options.max_steps;
  for (int k = 1; k <= options.max_steps; ++k) {
    phase_ = "grasp step " + std::to_string(k) + " of the closing";
    grasp_step_ = k;
    begin_grasp_step(k);
    std::vector<bool> touched(segments, false);
    for (int p = 1; p <= n; ++p) {
      grasp_step_targets(p, n);
      physics_step();
      for (std::size_t s = 0; s < segments; ++s) touched[s] = touched[s] || touching_[s];
    }
    add_step_record(k, contacts_, touching_, take_stats(), object_height(), result);
    if (options.on_grasp_step) {
      const CostTimer timer(cost_, CostPart::kJudge);
      options.on_grasp_step(m_, d_, k);
    }
    for (std::size_t s = 0; s < segments; ++s) {
      if (touched[s] && result.first_contact[s] < 0) result.first_contact[s] = k;
    }
    if (closing_done(k, touched, result)) {
      result.closing = "touched";
      break;
    }
  }
  end_closing();
}

// Phase 4: hold, watching the object at rest in the last second.
void HandRun::hold(const GraspOptions& options, GraspResult& result) {
  const long steps = phase_steps(options.hold_time);
  long step = 0;
  run_phase(
      RunPhase::kHold, steps, [](long) {},
      [&] { watch_rest(m_, d_, object_, is_object_geom_, ++step, steps, result); });
}

// The six-direction test (six_directions.h) from the state d_ holds after the hold, which d_
// holds again after it.
void HandRun::six_directions() {
  mujoco::DataPtr held(mj_copyData(nullptr, m_, d_));
  const mujoco::Registry::PairStates states =
      registry_ ? registry_->snapshot(d_) : mujoco::Registry::PairStates{};
  std::array<std::array<double, 3>, kSixDirections> pull{};
  for (int k = 0; k < kSixDirections; ++k) {
    pull[static_cast<std::size_t>(k)] = six_direction(d_, hand_, k);
  }
  const SixDirectionsModel model(mutable_m_, object_, support_body());
  const long steps = phase_steps(kSixDirectionsDuration);
  for (int k = 0; k < kSixDirections; ++k) {
    mj_copyData(d_, m_, held.get());
    if (registry_) registry_->restore(d_, states);
    for (int i = 0; i < 3; ++i) {
      d_->xfrc_applied[6 * object_ + i] = model.weight() * pull[static_cast<std::size_t>(k)][i];
    }
    direction_ = k;
    before_phase_ = RunPhase::kDirection;
    before_direction_ = k;
    before_seen_ = true;  // the hold's last state, seen
    run_phase(
        RunPhase::kDirection, steps, [](long) {}, [] {});
    observe_now();
  }
  mj_copyData(d_, m_, held.get());
  if (registry_) registry_->restore(d_, states);
  direction_ = -1;
}

// The run's totals after the hold.
void HandRun::finish(GraspResult& result) const {
  result.physics_steps = physics_steps_;
  result.sim_time = d_->time - start_time_;
  const double steps = static_cast<double>(std::max(physics_steps_, 1L));
  result.step_wall_ms = 1e3 * step_time_.wall_s / steps;
  result.step_cpu_ms = 1e3 * step_time_.cpu_s / steps;
  result.detection_ns_total = totals_.detection_ns;
  result.contained_calls = totals_.contained;
  result.nonfinite_skips = totals_.nonfinite_skips;
  result.reused_calls = totals_.reused;
  result.max_contacts = max_contacts_;
  result.mean_contacts =
      physics_steps_ > 0 ? static_cast<double>(contacts_sum_) / static_cast<double>(physics_steps_)
                         : 0.0;
  result.max_pair_contacts = pair_run_.most;
  result.contact_buffer_full = d_->warning[mjWARN_CONTACTFULL].number;
  result.constraint_buffer_full = d_->warning[mjWARN_CNSTRFULL].number;
}

// Paper section 9: close, squeeze, settle, lift, hold (grasp.h), the six directions when asked,
// then the verdicts from the watch's measures.
void HandRun::run(const GraspOptions& options, GraspResult& result) {
  start_time_ = d_->time;
  result.segments = segments_;
  result.first_contact.assign(segments_.size(), -1);
  WatchOptions watch;
  watch.true_penetration = options.true_penetration;
  watch.sample = std::max(1, options.physics_steps_per_grasp_step);
  watch.surfaces = surfaces_;
  watch.cost = &result.cost;
  {
    const CostTimer timer(&result.cost, CostPart::kTrees);
    watch_ = std::make_unique<MotionWatch>(m_, truth_ ? truth_ : m_, object_, hand_, support_body(),
                                           watch);
  }
  // The start state: the watch sees it with the first step's kinematics, the record now.
  before_phase_ = RunPhase::kStart;
  before_time_ = d_->time;
  if (record_) record_->start(m_, d_);
  // The physics part is the phases' time less the parts measured inside them.
  cost_ = &result.cost;
  on_physics_step_ = &options.on_physics_step;
  const GraspCost before = result.cost;
  const CostInstant phases_start = CostInstant::now();
  close(options, result);

  // Phase 2: squeeze, then settle.
  begin_squeeze();
  const long squeeze = phase_steps(options.squeeze_time);
  const auto nothing = [] {};
  run_phase(
      RunPhase::kSqueeze, squeeze, [&](long i) { squeeze_targets(i, squeeze); }, nothing);
  run_phase(
      RunPhase::kSettle, phase_steps(options.settle_time), [](long) {}, nothing);

  // Phase 3: lift.
  begin_lift();
  const long lift = phase_steps(options.lift_time);
  run_phase(
      RunPhase::kLift, lift, [&](long i) { lift_targets(i, lift); }, nothing);
  end_lift();

  hold(options, result);
  observe_now();
  take_stats();
  finish(result);
  if (options.six_directions && mutable_m_ != nullptr) six_directions();
  PartTime physics = CostInstant::now().since(phases_start);
  for (CostPart inside : {CostPart::kTruePenetration, CostPart::kJudge}) {
    physics -= result.cost[inside];
    physics += before[inside];
  }
  result.cost[CostPart::kPhysics] += physics;
  cost_ = nullptr;
  on_physics_step_ = nullptr;
  watch_->fill(result);
  judge_grasp(result);
}

}  // namespace graspcd::grasp
