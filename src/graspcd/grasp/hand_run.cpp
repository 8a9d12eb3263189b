#include "graspcd/grasp/hand_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "graspcd/core/clock.h"
#include "graspcd/mujoco/collision_pose.h"

namespace graspcd::grasp {

namespace {

// Whether two hand geoms push the object from opposing sides (grasp.h, "gripped"): per hand geom
// touching an object geom in d's contacts, the sum of its contact normals turned to point from
// the hand geom into the object (MuJoCo's frame[0..2] points from geom1 to geom2); two geoms whose
// sums have a negative dot product oppose. Hand geoms: neither the object's body tree, nor the
// world body (the floor), nor the support's body tree (support_root -1: none).
struct GripSides {
  int touching = 0;  // hand geoms touching the object
  bool opposing = false;
};

// The hand geom of contact `c` when it is between a hand geom and an object geom (as above), else
// -1.
int hand_geom(const mjModel* m, const mjContact& c, const std::vector<char>& is_object_geom,
              int support_root) {
  const bool object1 = is_object_geom[static_cast<std::size_t>(c.geom1)] != 0;
  const bool object2 = is_object_geom[static_cast<std::size_t>(c.geom2)] != 0;
  if (object1 == object2) return -1;
  const int hand = object1 ? c.geom2 : c.geom1;
  const int body = m->geom_bodyid[hand];
  if (body == 0 || m->body_rootid[body] == support_root) return -1;
  return hand;
}

GripSides grip_sides(const mjModel* m, const mjData* d, const std::vector<char>& is_object_geom,
                     int support_root) {
  std::vector<std::pair<int, Vec3>> pushes;  // hand geom, summed normal into the object
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const int hand = hand_geom(m, c, is_object_geom, support_root);
    if (hand < 0) continue;
    Vec3 n(c.frame[0], c.frame[1], c.frame[2]);
    if (c.geom2 == hand) n = -n;  // the frame's normal points from geom1 (the object) to geom2
    auto at = std::find_if(pushes.begin(), pushes.end(),
                           [hand](const std::pair<int, Vec3>& p) { return p.first == hand; });
    if (at == pushes.end()) {
      pushes.emplace_back(hand, n);
    } else {
      at->second += n;
    }
  }
  GripSides out;
  out.touching = static_cast<int>(pushes.size());
  for (std::size_t a = 0; a < pushes.size() && !out.opposing; ++a) {
    for (std::size_t b = a + 1; b < pushes.size(); ++b) {
      if (pushes[a].second.dot(pushes[b].second) < 0) {
        out.opposing = true;
        break;
      }
    }
  }
  return out;
}

// The object's grip point (grasp.h, "held"): the mean position of the contacts between hand geoms
// (as in grip_sides) and object geoms in d's contacts, in the world; nullopt without any.
std::optional<Vec3> grip_point(const mjModel* m, const mjData* d,
                               const std::vector<char>& is_object_geom, int support_root) {
  Vec3 sum(0, 0, 0);
  int n = 0;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if (hand_geom(m, c, is_object_geom, support_root) < 0) continue;
    sum += Vec3(c.pos[0], c.pos[1], c.pos[2]);
    ++n;
  }
  if (n == 0) return std::nullopt;
  return sum / n;
}

// Whether any hand geom (as in grip_sides) touches an object geom in d's contacts.
bool hand_touches_object(const mjModel* m, const mjData* d, const std::vector<char>& is_object_geom,
                         int support_root) {
  for (int i = 0; i < d->ncon; ++i) {
    if (hand_geom(m, d->contact[i], is_object_geom, support_root) >= 0) return true;
  }
  return false;
}

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

// One physics step (the hand's advance, timed), MuJoCo's non-finite check, then the scan of the
// segment-object contacts, the object's watch and, after the last physics step of each grasp
// step (of any phase), the true meshes' penetration (outside the timed step).
void HandRun::physics_step() {
  const Clock::time_point start = Clock::now();
  advance();
  wall_ns_ += static_cast<std::int64_t>(elapsed_ns(start));
  ++physics_steps_;
  throw_if_nonfinite(d_, scene_, phase_, physics_steps_);
  scan_contacts();
  watch_object();
  if (true_watch_ && physics_steps_ % grasp_step_length_ == 0) {
    const CostTimer timer(cost_, CostPart::kTruePenetration);
    const bool closing = phase_.rfind("grasp step ", 0) == 0;
    true_watch_->measure(d_, physics_steps_ / grasp_step_length_,
                         closing ? std::string("the closing") : phase_);
  }
}

// The object at the start (grasp.h, "ejected"): resting on its support, its origin lies at most R
// above its lowest point, R the farthest any of its geoms reaches from the origin; resting in any
// pose on a support no lower, the origin lies at most 2 R below where it started. Out of the
// scene: farther from the start than the scene's extent (MuJoCo's stat.extent), at least 1 m.
void HandRun::start_watch() {
  watch_ = ObjectWatch{};
  for (int k = 0; k < 3; ++k) watch_.start[static_cast<std::size_t>(k)] = d_->xpos[3 * object_ + k];
  watch_.start_height = object_height();
  double reach = 0;
  for (int g = 0; g < m_->ngeom; ++g) {
    if (!is_object_geom_[static_cast<std::size_t>(g)]) continue;
    double offset = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = d_->geom_xpos[3 * g + k] - d_->xpos[3 * object_ + k];
      offset += e * e;
    }
    reach = std::max(reach, std::sqrt(offset) + m_->geom_rbound[g]);
  }
  watch_.drop = 2 * reach + kHeldSlip;
  watch_.away = std::max(1.0, static_cast<double>(m_->stat.extent));
}

// After each physics step: the object's speed, whether it has been thrown out (the first time:
// faster than kEjectSpeed, below its support, out of the scene), and after the start of the lift
// the angle of its rotation since then (2 acos |q0 . q| for unit quaternions).
void HandRun::watch_object() {
  mjtNum velocity[6];
  mj_objectVelocity(m_, d_, mjOBJ_BODY, object_, velocity, 0);
  const double speed =
      std::sqrt(velocity[3] * velocity[3] + velocity[4] * velocity[4] + velocity[5] * velocity[5]);
  watch_.max_speed = std::max(watch_.max_speed, speed);
  watch_.kinetic_energy_max =
      std::max(watch_.kinetic_energy_max, object_kinetic_energy(m_, d_, object_, energy_scratch_));
  if (!watch_.ejected) {
    double away = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = d_->xpos[3 * object_ + k] - watch_.start[static_cast<std::size_t>(k)];
      away += e * e;
    }
    const char* cause = nullptr;
    if (speed > kEjectSpeed) {
      cause = "speed";
    } else if (object_height() < watch_.start_height - watch_.drop) {
      cause = "below";
    } else if (std::sqrt(away) > watch_.away) {
      cause = "away";
    }
    if (cause != nullptr) watch_.ejected = Ejection{d_->time, speed, cause};
  }
  if (watch_.contact_on) {
    if (hand_touches_object(m_, d_, is_object_geom_, support_root())) {
      watch_.release_time = -1;
    } else if (watch_.release_time < 0) {
      watch_.release_time = d_->time;
    }
  }
  if (watch_.tilt_on) {
    double dot = 0;
    for (int k = 0; k < 4; ++k) {
      dot += watch_.quat_lift[static_cast<std::size_t>(k)] * d_->xquat[4 * object_ + k];
    }
    watch_.tilt = 2 * std::acos(std::min(1.0, std::abs(dot)));
    watch_.max_tilt = std::max(watch_.max_tilt, watch_.tilt);
  }
}

double HandRun::point_height(const std::array<double, 3>& p) const {
  const std::array<double, 3> u = up();
  double h = object_height();
  for (int k = 0; k < 3; ++k) {
    h += (p[static_cast<std::size_t>(k)] - d_->xpos[3 * object_ + k]) *
         u[static_cast<std::size_t>(k)];
  }
  return h;
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

// Runs `steps` physics steps named `name` in messages; at(i) sets the targets before step i (1 to
// steps), observe() sees the state after each.
template <class Targets, class Observe>
void HandRun::run_phase(const char* name, long steps, Targets at, Observe observe) {
  phase_ = name;
  for (long i = 1; i <= steps; ++i) {
    at(i);
    physics_step();
    observe();
  }
}

std::array<double, 3> HandRun::object_in_hand() const {
  return {d_->xpos[3 * object_] - d_->xpos[3 * hand_],
          d_->xpos[3 * object_ + 1] - d_->xpos[3 * hand_ + 1],
          d_->xpos[3 * object_ + 2] - d_->xpos[3 * hand_ + 2]};
}

// Phase 1, paper section 9 (docs/design.md "Semantics"): grasp steps until the hand says the
// closing is done; a segment's first contact is the grasp step in which it first touched.
void HandRun::close(const GraspOptions& options, GraspResult& result) {
  const int n = std::max(1, options.physics_steps_per_grasp_step);
  const std::size_t segments = segments_.size();
  for (int k = 1; k <= options.max_steps; ++k) {
    phase_ = "grasp step " + std::to_string(k) + " of the closing";
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
    if (closing_done(k, touched, result)) break;
  }
  end_closing();
}

// Phase 4: hold, watching the object against the hand and, in the last second, at rest.
void HandRun::hold(const GraspOptions& options, GraspResult& result) {
  const std::array<double, 3> rel0 = object_in_hand();
  result.hold_min_z = object_height();
  result.hold_drift = 0;
  const long steps = phase_steps(options.hold_time);
  long step = 0;
  run_phase(
      "the hold", steps, [](long) {},
      [&] {
        watch_rest(m_, d_, object_, is_object_geom_, ++step, steps, result);
        result.hold_min_z = std::min(result.hold_min_z, object_height());
        const std::array<double, 3> rel = object_in_hand();
        const double drift = std::sqrt((rel[0] - rel0[0]) * (rel[0] - rel0[0]) +
                                       (rel[1] - rel0[1]) * (rel[1] - rel0[1]) +
                                       (rel[2] - rel0[2]) * (rel[2] - rel0[2]));
        result.hold_drift = std::max(result.hold_drift, drift);
        if (result.slip_time < 0 && result.hold_drift >= kHeldSlip) result.slip_time = d_->time;
      });
}

// The run's totals after the hold.
void HandRun::finish(GraspResult& result) const {
  result.object_z_final = object_height();
  result.physics_steps = physics_steps_;
  result.sim_time = d_->time;
  result.step_wall_ms =
      physics_steps_ > 0 ? static_cast<double>(wall_ns_) / 1e6 / static_cast<double>(physics_steps_)
                         : 0.0;
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

// Paper section 9: close, squeeze, settle, lift, hold (grasp.h), then the verdicts.
void HandRun::run(const GraspOptions& options, GraspResult& result) {
  result.segments = segments_;
  result.first_contact.assign(segments_.size(), -1);
  result.object_z_initial = object_height();
  start_watch();
  grasp_step_length_ = std::max(1, options.physics_steps_per_grasp_step);
  if (options.true_penetration) {
    const CostTimer timer(&result.cost, CostPart::kTrees);
    true_watch_ = std::make_unique<TruePenetrationWatch>(truth_ ? truth_ : m_, object_,
                                                         support_root(), surfaces_);
  }
  // The physics part is the phases' time less the parts measured inside them.
  cost_ = &result.cost;
  const GraspCost before = result.cost;
  const CostInstant phases_start = CostInstant::now();
  close(options, result);

  // Phase 2: squeeze, then settle, watching how far the object is pushed from where it was.
  begin_squeeze();
  const long squeeze = phase_steps(options.squeeze_time);
  const auto nothing = [] {};
  const Vec3 before_squeeze(d_->xpos[3 * object_], d_->xpos[3 * object_ + 1],
                            d_->xpos[3 * object_ + 2]);
  result.squeeze_push = 0;
  const auto pushed = [&] {
    const Vec3 o(d_->xpos[3 * object_], d_->xpos[3 * object_ + 1], d_->xpos[3 * object_ + 2]);
    result.squeeze_push = std::max(result.squeeze_push, (o - before_squeeze).norm());
  };
  run_phase(
      "the squeeze", squeeze, [&](long i) { squeeze_targets(i, squeeze); }, pushed);
  run_phase(
      "the settling", phase_steps(options.settle_time), [](long) {}, pushed);
  result.object_z_gripped = object_height();
  const GripSides grip = grip_sides(m_, d_, is_object_geom_, support_root());
  const double hand_at_lift = hand_height();
  // The grip point in the object's frame (the object's origin without contacts), and its height.
  const Vec3 origin(d_->xpos[3 * object_], d_->xpos[3 * object_ + 1], d_->xpos[3 * object_ + 2]);
  const Mat3 rotation = mujoco::from_row_major(d_->xmat + 9 * object_);
  const Vec3 grip_local =
      rotation.transpose() *
      (grip_point(m_, d_, is_object_geom_, support_root()).value_or(origin) - origin);
  const auto grip_world = [&] {
    const Vec3 o(d_->xpos[3 * object_], d_->xpos[3 * object_ + 1], d_->xpos[3 * object_ + 2]);
    const Vec3 p = o + mujoco::from_row_major(d_->xmat + 9 * object_) * grip_local;
    return std::array<double, 3>{p.x(), p.y(), p.z()};
  };
  const double grip_at_lift = point_height(grip_world());
  for (int k = 0; k < 4; ++k) {
    watch_.quat_lift[static_cast<std::size_t>(k)] = d_->xquat[4 * object_ + k];
  }
  watch_.tilt_on = true;
  watch_.contact_on = true;

  // Phase 3: lift.
  begin_lift();
  const long lift = phase_steps(options.lift_time);
  run_phase(
      "the lift", lift, [&](long i) { lift_targets(i, lift); }, nothing);
  end_lift();

  hold(options, result);
  PartTime physics = CostInstant::now().since(phases_start);
  for (CostPart inside : {CostPart::kTruePenetration, CostPart::kJudge}) {
    physics -= result.cost[inside];
    physics += before[inside];
  }
  result.cost[CostPart::kPhysics] += physics;
  cost_ = nullptr;
  take_stats();
  finish(result);
  result.hand_travel = hand_height() - hand_at_lift;
  result.object_rise = result.object_z_final - result.object_z_gripped;
  result.grip_rise = point_height(grip_world()) - grip_at_lift;
  constexpr double kDegrees = 180.0 / 3.14159265358979323846;
  result.tilt_deg = watch_.max_tilt * kDegrees;
  result.tilt_final_deg = watch_.tilt * kDegrees;
  result.max_speed = watch_.max_speed;
  result.kinetic_energy_max = watch_.kinetic_energy_max;
  if (true_watch_) result.true_penetration = true_watch_->result();
  result.ejected = watch_.ejected;
  bool ever_touched = false;
  for (int step : result.first_contact) ever_touched = ever_touched || step > 0;
  result.release_time = watch_.release_time;
  judge_grasp(ever_touched, grip.touching, grip.opposing, result);
}

}  // namespace graspcd::grasp
