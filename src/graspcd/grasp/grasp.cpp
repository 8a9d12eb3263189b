#include "graspcd/grasp/grasp.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>

#include "graspcd/core/clock.h"
#include "graspcd/grasp/controllers.h"
#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/start_check.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/model_check.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

namespace {

constexpr int kArmJoints = 3;
constexpr int kFingers = 4;
constexpr int kSegmentsPerFinger = 3;

// Whether two hand geoms push the object from opposing sides (grasp.h, "gripped"): per hand geom
// touching an object geom in d's contacts, the sum of its contact normals turned to point from
// the hand geom into the object (MuJoCo's frame[0..2] points from geom1 to geom2); two geoms whose
// sums have a negative dot product oppose. Hand geoms: neither the object's body tree, nor the
// world body (the floor), nor the support's body tree (support_root -1: none).
struct GripSides {
  int touching = 0;  // hand geoms touching the object
  bool opposing = false;
};

GripSides grip_sides(const mjModel* m, const mjData* d, const std::vector<char>& is_object_geom,
                     int support_root) {
  std::vector<std::pair<int, Vec3>> pushes;  // hand geom, summed normal into the object
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const bool object1 = is_object_geom[static_cast<std::size_t>(c.geom1)] != 0;
    const bool object2 = is_object_geom[static_cast<std::size_t>(c.geom2)] != 0;
    if (object1 == object2) continue;
    const int hand = object1 ? c.geom2 : c.geom1;
    const int body = m->geom_bodyid[hand];
    if (body == 0 || m->body_rootid[body] == support_root) continue;
    Vec3 n(c.frame[0], c.frame[1], c.frame[2]);
    if (object1) n = -n;
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

// The verdicts after the hold (grasp.h): held, and the reason of a failure. `ever_touched`: some
// segment touched the object during the closing; `grip`: the grip before the lift.
void judge(bool ever_touched, const GripSides& grip, GraspResult& result) {
  result.gripped = grip.opposing;
  const bool rose =
      result.hand_travel > 0 && result.object_rise >= kHeldRiseShare * result.hand_travel;
  const bool slipped = result.hold_drift >= kHeldSlip;
  result.held = result.gripped && rose && !slipped;
  char text[160];
  if (!ever_touched) {
    result.reason = "no segment reached the object";
  } else if (grip.touching == 0) {
    result.reason = "no segment touched the object after the squeeze";
  } else if (!grip.opposing) {
    result.reason = "no two touching segments push from opposing sides (" +
                    std::to_string(grip.touching) + " touching)";
  } else if (slipped) {
    std::snprintf(text, sizeof text, "slipped at t = %.3f s (moved %.1f cm in the hand)",
                  result.slip_time, 100 * result.hold_drift);
    result.reason = text;
  } else if (!rose) {
    std::snprintf(text, sizeof text, "rose %.1f cm of the hand's %.1f cm travel (less than %.0f%%)",
                  100 * result.object_rise, 100 * result.hand_travel, 100 * kHeldRiseShare);
    result.reason = text;
  } else {
    result.reason.clear();
  }
}

// Counts the longest run of one geom pair among the counted contacts of a step (MuJoCo writes
// each geom pair's contacts consecutively): the most contacts one pair handed the solver.
struct PairRun {
  int last = -2, g1 = -1, g2 = -1, run = 0, most = 0;
  void start() { last = -2; }
  void add(int i, int geom1, int geom2) {
    run = i == last + 1 && geom1 == g1 && geom2 == g2 ? run + 1 : 1;
    last = i;
    g1 = geom1;
    g2 = geom2;
    most = std::max(most, run);
  }
};

int require_id(const mjModel* m, mjtObj type, const std::string& name, const std::string& scene,
               const char* what) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::runtime_error(scene + ": no " + what + " named " + name);
  return id;
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

// The bridge's counters summed over a whole grasp (every phase), as GraspResult reports them.
struct BridgeTotals {
  std::uint64_t detection_ns = 0, contained = 0, nonfinite_skips = 0, reused = 0;
  void add(const mujoco::BridgeStats& s) {
    detection_ns += s.detection_ns;
    contained += s.contained;
    nonfinite_skips += s.nonfinite_skips;
    reused += s.reused;
  }
};

// The state the phases share: the model, the controller's targets, the contact scan and the
// accumulated statistics.
class GraspRun {
 public:
  GraspRun(const mjModel* m, mjData* d, mujoco::Registry* registry, const GraspOptions& options,
           const std::string& scene)
      : m_(m),
        d_(d),
        registry_(registry),
        scene_(scene),
        controller_(m, joint_names(), PdGains::critically_damped(options.omega)) {
    const std::size_t n = controller_.size();
    q_d_.resize(n);
    for (std::size_t i = 0; i < n; ++i) q_d_[i] = m->qpos0[controller_.drives()[i].qpos_adr];
    qd_d_.assign(n, 0);
    qdd_d_.assign(n, 0);
    segment_of_geom_.assign(static_cast<std::size_t>(m->ngeom), -1);
    for (int s = 0; s < kFingerSegments; ++s) {
      const std::string& name = finger_segment_names()[static_cast<std::size_t>(s)];
      segment_of_geom_[static_cast<std::size_t>(require_id(m, mjOBJ_GEOM, name, scene, "geom"))] =
          s;
      const int joint = require_id(m, mjOBJ_JOINT, name, scene, "joint");
      upper_[static_cast<std::size_t>(s)] =
          m->jnt_limited[joint] ? m->jnt_range[2 * joint + 1] : 10;
    }
    object_ = require_id(m, mjOBJ_BODY, "object", scene, "body");
    palm_ = require_id(m, mjOBJ_BODY, "palm", scene, "body");
    is_object_geom_.assign(static_cast<std::size_t>(m->ngeom), 0);
    for (int g = 0; g < m->ngeom; ++g) {
      is_object_geom_[static_cast<std::size_t>(g)] = m->body_rootid[m->geom_bodyid[g]] == object_;
    }
  }

  static std::vector<std::string> joint_names() {
    std::vector<std::string> names = {"arm1", "arm2", "arm3"};
    for (const std::string& s : finger_segment_names()) names.push_back(s);
    return names;
  }

  double object_z() const { return d_->xpos[3 * object_ + 2]; }
  std::array<double, 3> object_in_palm() const {
    return {d_->xpos[3 * object_] - d_->xpos[3 * palm_],
            d_->xpos[3 * object_ + 1] - d_->xpos[3 * palm_ + 1],
            d_->xpos[3 * object_ + 2] - d_->xpos[3 * palm_ + 2]};
  }

  // One physics step: mj_step1 -> computed torque -> mj_step2 (controllers.h), then the scan of
  // the finger-object contacts.
  void physics_step() {
    controller_.set_target(q_d_, qd_d_, qdd_d_);
    const Clock::time_point start = Clock::now();
    mj_step1(m_, d_);
    controller_.apply(m_, d_);
    mj_step2(m_, d_);
    wall_ns_ += static_cast<std::int64_t>(elapsed_ns(start));
    ++physics_steps_;
    check_finite();
    touching_.fill(false);
    contacts_ = 0;
    pair_run_.start();
    for (int i = 0; i < d_->ncon; ++i) {
      const int g1 = d_->contact[i].geom1;
      const int g2 = d_->contact[i].geom2;
      int s = -1;
      if (is_object_geom_[static_cast<std::size_t>(g2)])
        s = segment_of_geom_[static_cast<std::size_t>(g1)];
      if (s < 0 && is_object_geom_[static_cast<std::size_t>(g1)])
        s = segment_of_geom_[static_cast<std::size_t>(g2)];
      if (s < 0) continue;
      touching_[static_cast<std::size_t>(s)] = true;
      ++contacts_;
      pair_run_.add(i, g1, g2);
    }
    max_contacts_ = std::max(max_contacts_, contacts_);
    contacts_sum_ += contacts_;
  }

  void check_finite() const { throw_if_nonfinite(d_, scene_, phase_, physics_steps_); }

  // The bridge's statistics since the last call (zero with native collision).
  mujoco::BridgeStats take_stats() {
    if (!registry_) return mujoco::BridgeStats{};
    mujoco::BridgeStats s = registry_->take_stats();
    totals_.add(s);
    return s;
  }

  // Runs `seconds` of physics steps with targets from `at(t)` (t from 0 to seconds); `observe`
  // sees the state after each step.
  template <class Targets, class Observe>
  void run_phase(double seconds, Targets at, Observe observe) {
    const double dt = m_->opt.timestep;
    const long steps = std::max(1L, std::lround(seconds / dt));
    for (long i = 1; i <= steps; ++i) {
      at(static_cast<double>(i) * dt);
      physics_step();
      observe();
    }
  }

  const mjModel* m_;
  mjData* d_;
  mujoco::Registry* registry_;
  std::string scene_;
  std::string phase_ = "the closing";  // for messages
  ComputedTorqueController controller_;
  std::vector<double> q_d_, qd_d_, qdd_d_;
  std::vector<int> segment_of_geom_;
  std::vector<char> is_object_geom_;
  std::array<double, kFingerSegments> upper_{};
  int object_ = -1;
  int palm_ = -1;
  std::array<bool, kFingerSegments> touching_{};
  int contacts_ = 0;
  int max_contacts_ = 0;
  long contacts_sum_ = 0;
  PairRun pair_run_;
  long physics_steps_ = 0;
  std::int64_t wall_ns_ = 0;
  BridgeTotals totals_;
};

// Appends grasp step k's record (its contacts, segments touching, the bridge's counters over the
// step, the object's height) to the result, and adds its detection time to the closing's.
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

// Phase 1, paper section 9 (docs/design.md "Semantics"): grasp steps of 0.003 rad until each finger
// has a segment in contact; a segment stops at its first contact.
void close_fingers(GraspRun& run, const GraspOptions& options, GraspResult& result) {
  const int n = std::max(1, options.physics_steps_per_grasp_step);
  const double dt = run.m_->opt.timestep;
  std::array<bool, kFingerSegments> stopped{};
  result.segments.assign(finger_segment_names().begin(), finger_segment_names().end());
  result.first_contact.assign(kFingerSegments, -1);
  for (int k = 1; k <= options.max_steps; ++k) {
    std::array<double, kFingerSegments> start{};
    std::array<double, kFingerSegments> end{};
    for (int s = 0; s < kFingerSegments; ++s) {
      const auto i = static_cast<std::size_t>(s);
      start[i] = run.q_d_[kArmJoints + i];
      end[i] = stopped[i] ? start[i] : std::min(start[i] + kGraspStepRad, run.upper_[i]);
    }
    std::array<bool, kFingerSegments> touched{};
    run.phase_ = "grasp step " + std::to_string(k) + " of the closing";
    for (int p = 1; p <= n; ++p) {
      const double f = static_cast<double>(p) / n;
      for (std::size_t i = 0; i < kFingerSegments; ++i) {
        run.q_d_[kArmJoints + i] = start[i] + f * (end[i] - start[i]);
        run.qd_d_[kArmJoints + i] = p < n ? (end[i] - start[i]) / (n * dt) : 0.0;
      }
      run.physics_step();
      for (std::size_t i = 0; i < kFingerSegments; ++i) touched[i] = touched[i] || run.touching_[i];
    }
    add_step_record(k, run.contacts_, std::vector<bool>(run.touching_.begin(), run.touching_.end()),
                    run.take_stats(), run.object_z(), result);
    if (options.on_grasp_step) options.on_grasp_step(run.m_, run.d_, k);

    bool every_finger = true;
    bool all_stopped = true;
    for (std::size_t i = 0; i < kFingerSegments; ++i) {
      if (touched[i] && result.first_contact[i] < 0) {
        result.first_contact[i] = k;
        // The segment and the ones proximal to it on its finger stop (GraspIt's autoGrasp rule):
        // a proximal joint that kept closing would push the object with the touching segment.
        const std::size_t base = i - i % kSegmentsPerFinger;
        for (std::size_t j = base; j <= i; ++j) stopped[j] = true;
      }
      if (run.q_d_[kArmJoints + i] >= run.upper_[i]) stopped[i] = true;
    }
    for (std::size_t i = 0; i < kFingerSegments; ++i) all_stopped = all_stopped && stopped[i];
    for (int finger = 0; finger < kFingers; ++finger) {
      bool any = false;
      for (int seg = 0; seg < kSegmentsPerFinger; ++seg) {
        any = any ||
              result.first_contact[static_cast<std::size_t>(finger * kSegmentsPerFinger + seg)] > 0;
      }
      every_finger = every_finger && any;
    }
    if (every_finger) break;
    if (all_stopped) break;
  }
  for (std::size_t i = 0; i < kFingerSegments; ++i) run.qd_d_[kArmJoints + i] = 0;
}

// After the hold, the same for our hands (GraspRun) and a driven one (DrivenRun): the final
// height, the verdict held, and the run's totals.
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

template <class Run>
void finish_result(const Run& run, const mjData* d, double final_z, GraspResult& result) {
  result.object_z_final = final_z;
  result.physics_steps = run.physics_steps_;
  result.sim_time = d->time;
  result.step_wall_ms = run.physics_steps_ > 0 ? static_cast<double>(run.wall_ns_) / 1e6 /
                                                     static_cast<double>(run.physics_steps_)
                                               : 0.0;
  result.detection_ns_total = run.totals_.detection_ns;
  result.contained_calls = run.totals_.contained;
  result.nonfinite_skips = run.totals_.nonfinite_skips;
  result.reused_calls = run.totals_.reused;
  result.max_contacts = run.max_contacts_;
  result.mean_contacts = run.physics_steps_ > 0 ? static_cast<double>(run.contacts_sum_) /
                                                      static_cast<double>(run.physics_steps_)
                                                : 0.0;
  result.max_pair_contacts = run.pair_run_.most;
  result.contact_buffer_full = d->warning[mjWARN_CONTACTFULL].number;
  result.constraint_buffer_full = d->warning[mjWARN_CNSTRFULL].number;
}

// A hand that is not ours, driven through its own actuators by the config's "grasp" section
// (registry.h, DriveConfig; grasp.h, run_grasp). Grasp step k adds each closing actuator's step
// to its control (clamped to its ctrlrange) and runs physics_steps_per_grasp_step physics steps
// (mj_step: the hand's own position servos track the controls); an actuator stops when a geom
// of each of its touch patterns has touched the object, or at the end of its ctrlrange. Then the
// squeeze (each actuator's squeeze over squeeze_time, then settle_time), the lift (the lift
// actuator's control moves by `by` along a cosine ramp over lift_time) and the hold, judged as on
// our hands with heights along -gravity measured from the support body.
class DrivenRun {
 public:
  DrivenRun(const mjModel* m, mjData* d, mujoco::Registry* registry, const DriveConfig& drive,
            const std::string& scene, const std::string& config)
      : m_(m), d_(d), registry_(registry), drive_(drive), scene_(scene) {
    const auto bad = [&](const std::string& what) { return GraspInputError(config, what); };
    const auto body = [&](const std::string& name) {
      const int id = mj_name2id(m, mjOBJ_BODY, name.c_str());
      if (id < 0) throw bad("'grasp': the scene has no body named '" + name + "'");
      return id;
    };
    const auto actuator = [&](const std::string& name) {
      const int id = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str());
      if (id < 0) throw bad("'grasp': the scene has no actuator named '" + name + "'");
      return id;
    };
    object_ = body(drive.object);
    hand_ = body(drive.hand);
    support_ = drive.support.empty() ? 0 : body(drive.support);
    lift_ = actuator(drive.lift_actuator);
    const double g = mju_norm3(m->opt.gravity);
    for (int k = 0; k < 3; ++k) up_[k] = g > 0 ? -m->opt.gravity[k] / g : (k == 2 ? 1.0 : 0.0);
    segments_of_geom_.resize(static_cast<std::size_t>(m->ngeom));
    for (const CloseDrive& c : drive.close) {
      close_.push_back(actuator(c.actuator));
      std::vector<int> segments;
      for (const std::string& pattern : c.touch) {
        const std::vector<int> geoms = mujoco::match_geoms(m, pattern);
        if (geoms.empty()) {
          throw bad("'grasp': touch pattern '" + pattern + "' matches no collidable geom");
        }
        const int s = static_cast<int>(names_.size());
        names_.push_back(pattern);
        for (int geom : geoms) segments_of_geom_[static_cast<std::size_t>(geom)].push_back(s);
        segments.push_back(s);
      }
      segments_of_drive_.push_back(segments);
    }
    is_object_geom_.resize(static_cast<std::size_t>(m->ngeom));
    for (int geom = 0; geom < m->ngeom; ++geom) {
      is_object_geom_[static_cast<std::size_t>(geom)] =
          m->body_rootid[m->geom_bodyid[geom]] == object_;
    }
    touching_.assign(names_.size(), false);
  }

  // The height of a body along -gravity above the support body.
  double height_of(int body) const {
    double h = 0;
    for (int k = 0; k < 3; ++k) h += (d_->xpos[3 * body + k] - d_->xpos[3 * support_ + k]) * up_[k];
    return h;
  }
  double height() const { return height_of(object_); }
  double hand_height() const { return height_of(hand_); }
  // The support's body tree (-1 for the world: the world body is never a hand geom's).
  int support_root() const { return support_ > 0 ? m_->body_rootid[support_] : -1; }
  double drift_from(const std::array<double, 3>& rel0) const {
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const double e =
          d_->xpos[3 * object_ + k] - d_->xpos[3 * hand_ + k] - rel0[static_cast<std::size_t>(k)];
      s += e * e;
    }
    return std::sqrt(s);
  }
  std::array<double, 3> object_in_hand() const {
    return {d_->xpos[3 * object_] - d_->xpos[3 * hand_],
            d_->xpos[3 * object_ + 1] - d_->xpos[3 * hand_ + 1],
            d_->xpos[3 * object_ + 2] - d_->xpos[3 * hand_ + 2]};
  }
  // The control of actuator a clamped to its ctrlrange.
  double clamp_ctrl(int a, double u) const {
    if (!m_->actuator_ctrllimited[a]) return u;
    return std::clamp(u, m_->actuator_ctrlrange[2 * a], m_->actuator_ctrlrange[2 * a + 1]);
  }

  // One physics step, then the scan of the segment-object contacts.
  void physics_step() {
    const Clock::time_point start = Clock::now();
    mj_step(m_, d_);
    wall_ns_ += static_cast<std::int64_t>(elapsed_ns(start));
    ++physics_steps_;
    throw_if_nonfinite(d_, scene_, phase_, physics_steps_);
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
  // `seconds` of physics steps, the controls set by at(fraction of the phase) before each.
  template <class Controls, class Observe>
  void run_phase(double seconds, Controls at, Observe observe) {
    const long steps = std::max(1L, std::lround(seconds / m_->opt.timestep));
    for (long i = 1; i <= steps; ++i) {
      at(static_cast<double>(i) / static_cast<double>(steps));
      physics_step();
      observe();
    }
  }
  mujoco::BridgeStats take_stats() {
    if (!registry_) return mujoco::BridgeStats{};
    const mujoco::BridgeStats s = registry_->take_stats();
    totals_.add(s);
    return s;
  }

  const mjModel* m_;
  mjData* d_;
  mujoco::Registry* registry_;
  const DriveConfig& drive_;
  std::string scene_;
  std::string phase_ = "the closing";
  int object_ = -1, hand_ = -1, support_ = 0, lift_ = -1;
  std::array<double, 3> up_{};
  std::vector<int> close_;                           // actuator ids, by drive
  std::vector<std::vector<int>> segments_of_drive_;  // segment ids, by drive
  std::vector<std::string> names_;                   // segment names (touch patterns)
  std::vector<std::vector<int>> segments_of_geom_;
  std::vector<char> is_object_geom_;
  std::vector<bool> touching_;
  int contacts_ = 0, max_contacts_ = 0;
  long contacts_sum_ = 0;
  PairRun pair_run_;
  long physics_steps_ = 0;
  std::int64_t wall_ns_ = 0;
  BridgeTotals totals_;
};

void run_driven_grasp(DrivenRun& run, const GraspOptions& options, GraspResult& result) {
  mjData* d = run.d_;
  const std::size_t drives = run.close_.size();
  const std::size_t segments = run.names_.size();
  result.segments = run.names_;
  result.first_contact.assign(segments, -1);
  result.object_z_initial = run.height();

  // Phase 1: close in grasp steps.
  std::vector<bool> stopped(drives, false);
  const int n = std::max(1, options.physics_steps_per_grasp_step);
  for (int k = 1; k <= options.max_steps; ++k) {
    run.phase_ = "grasp step " + std::to_string(k) + " of the closing";
    for (std::size_t i = 0; i < drives; ++i) {
      if (stopped[i]) continue;
      const int a = run.close_[i];
      const double next = run.clamp_ctrl(a, d->ctrl[a] + run.drive_.close[i].step);
      if (next == d->ctrl[a]) stopped[i] = true;  // the end of its ctrlrange
      d->ctrl[a] = next;
    }
    std::vector<bool> touched(segments, false);
    for (int p = 0; p < n; ++p) {
      run.physics_step();
      for (std::size_t s = 0; s < segments; ++s) touched[s] = touched[s] || run.touching_[s];
    }
    add_step_record(k, run.contacts_, run.touching_, run.take_stats(), run.height(), result);
    if (options.on_grasp_step) options.on_grasp_step(run.m_, d, k);
    for (std::size_t s = 0; s < segments; ++s) {
      if (touched[s] && result.first_contact[s] < 0) result.first_contact[s] = k;
    }
    bool all_stopped = true;
    for (std::size_t i = 0; i < drives; ++i) {
      bool every = true;
      for (int s : run.segments_of_drive_[i])
        every = every && result.first_contact[static_cast<std::size_t>(s)] > 0;
      if (every) stopped[i] = true;
      all_stopped = all_stopped && stopped[i];
    }
    if (all_stopped) break;
  }

  // Phase 2: squeeze, then settle.
  std::vector<double> closed(drives);
  for (std::size_t i = 0; i < drives; ++i) closed[i] = d->ctrl[run.close_[i]];
  const auto nothing = [] {};
  run.phase_ = "the squeeze";
  run.run_phase(
      options.squeeze_time,
      [&](double f) {
        for (std::size_t i = 0; i < drives; ++i) {
          const int a = run.close_[i];
          d->ctrl[a] = run.clamp_ctrl(a, closed[i] + f * run.drive_.close[i].squeeze);
        }
      },
      nothing);
  run.phase_ = "the settling";
  run.run_phase(
      options.settle_time, [](double) {}, nothing);
  result.object_z_gripped = run.height();
  const GripSides grip = grip_sides(run.m_, d, run.is_object_geom_, run.support_root());
  const double hand_at_lift = run.hand_height();

  // Phase 3: lift along a cosine ramp.
  run.phase_ = "the lift";
  const double lift0 = d->ctrl[run.lift_];
  run.run_phase(
      options.lift_time,
      [&](double f) {
        d->ctrl[run.lift_] =
            run.clamp_ctrl(run.lift_, lift0 + run.drive_.lift_by * 0.5 * (1 - std::cos(M_PI * f)));
      },
      nothing);

  // Phase 4: hold, watching the object against the hand.
  const std::array<double, 3> rel0 = run.object_in_hand();
  result.hold_min_z = run.height();
  run.phase_ = "the hold";
  const long hold_steps = std::max(1L, std::lround(options.hold_time / run.m_->opt.timestep));
  long hold_step = 0;
  run.run_phase(
      options.hold_time, [](double) {},
      [&] {
        result.hold_min_z = std::min(result.hold_min_z, run.height());
        result.hold_drift = std::max(result.hold_drift, run.drift_from(rel0));
        if (result.slip_time < 0 && result.hold_drift >= kHeldSlip) result.slip_time = d->time;
        watch_rest(run.m_, d, run.object_, run.is_object_geom_, ++hold_step, hold_steps, result);
      });
  run.take_stats();
  finish_result(run, d, run.height(), result);
  result.hand_travel = run.hand_height() - hand_at_lift;
  result.object_rise = result.object_z_final - result.object_z_gripped;
  bool ever_touched = false;
  for (int step : result.first_contact) ever_touched = ever_touched || step > 0;
  judge(ever_touched, grip, result);
}

}  // namespace

const std::array<std::string, kFingerSegments>& finger_segment_names() {
  static const std::array<std::string, kFingerSegments> names = [] {
    std::array<std::string, kFingerSegments> out;
    for (int f = 0; f < kFingers; ++f) {
      for (int s = 0; s < kSegmentsPerFinger; ++s) {
        out[static_cast<std::size_t>(f * kSegmentsPerFinger + s)] =
            "finger" + std::to_string(f + 1) + "_" + static_cast<char>('A' + s);
      }
    }
    return out;
  }();
  return names;
}

double kinetic_energy(const mjModel* m, const mjData* d) {
  thread_local std::vector<mjtNum> mv;
  mv.resize(static_cast<std::size_t>(m->nv));
  mj_mulM(m, d, mv.data(), d->qvel);
  return 0.5 * mju_dot(d->qvel, mv.data(), m->nv);
}

// A config's error as a GraspInputError. One that already is (drive_config.h) keeps its file and
// line; the registry's messages start with the config's name (registry.h), which the
// GraspInputError carries apart, and a message "CONFIG:LINE: ..." (json_config.h) keeps its line
// apart too.
GraspInputError config_error(const std::string& config_path, const std::runtime_error& e) {
  if (const auto* input = dynamic_cast<const GraspInputError*>(&e)) {
    return GraspInputError(input->file(), mujoco::join_lines(input->message()), input->line());
  }
  std::string message = mujoco::join_lines(e.what());
  std::size_t line = 0;
  if (message.rfind(config_path + ":", 0) == 0) {
    std::size_t at = config_path.size() + 1;
    std::size_t digits = at;
    while (digits < message.size() && std::isdigit(static_cast<unsigned char>(message[digits]))) {
      ++digits;
    }
    if (digits > at && message.compare(digits, 2, ": ") == 0) {
      line = std::stoul(message.substr(at, digits - at));
      at = digits;
    }
    if (message.compare(at, 1, " ") == 0 || message.compare(at, 2, ": ") == 0) {
      message = message.substr(message.compare(at, 1, " ") == 0 ? at + 1 : at + 2);
    }
  }
  return GraspInputError(config_path, message, line);
}

namespace {

// The start-state check (start_check.h) as bad input naming the scene.
void throw_if_bad_start(const mjModel* m, const mjData* d, int object, const std::string& scene) {
  const std::string problem = check_start_state(m, d, object);
  if (!problem.empty()) {
    throw GraspInputError(scene, "the start state is not valid: " + problem);
  }
}

}  // namespace

// Paper section 9 (the grasp) with the computed-torque law of section 7, eq. (12)-(16); the
// phases are described in grasp.h.
GraspResult run_grasp(const std::string& scene_path, const GraspOptions& options) {
  const auto model = mujoco::load_model(scene_path);
  const mjModel* m = model.get();

  std::unique_ptr<mujoco::ScopedInstall> install_guard;
  std::unique_ptr<mujoco::Registry> registry;
  mujoco::RegistryConfig config;
  const std::string config_path =
      options.config_path.empty() ? mujoco::pair_config_path(scene_path) : options.config_path;
  // How to drive the hand (the config's "grasp" section, drive_config.h); with native collision
  // that is all the config says.
  std::optional<DriveConfig> drive;
  std::error_code exists_ec;
  if (std::filesystem::is_regular_file(config_path, exists_ec)) {
    try {
      if (options.native) config = mujoco::load_registry_config(config_path);
      drive = load_drive_config(config_path);
    } catch (const std::runtime_error& e) {
      throw config_error(config_path, e);
    }
  }
  if (!options.native) {
    try {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(config_path, ec))
        throw GraspInputError(config_path, "cannot open the pair config");
      config = mujoco::load_registry_config(config_path);
      if (options.method) config.method = *options.method;
      if (options.cap) config.detector.cap = *options.cap;
      if (options.switch_passes) config.detector.switch_passes = *options.switch_passes;
      if (options.front_list) config.front_list = *options.front_list;
      if (options.contact_reuse) config.contact_reuse = *options.contact_reuse;
      registry = std::make_unique<mujoco::Registry>(m, config, config_path);
    } catch (const GraspInputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw config_error(config_path, e);
    }
    install_guard = std::make_unique<mujoco::ScopedInstall>();
    mujoco::attach(*registry);
  }
  GraspResult result;
  if (registry) result.warnings = registry->warnings();

  mujoco::DataPtr data(mj_makeData(m));
  mjData* d = data.get();
  result.scene = scene_path;
  result.native = options.native;
  result.method = options.native ? "native" : method_name(config.method);

  if (drive) {
    // A hand driven through its own actuators (the config's "grasp" section).
    DrivenRun run(m, d, registry.get(), *drive, scene_path, config_path);
    mj_forward(m, d);
    throw_if_bad_start(m, d, run.object_, scene_path);
    if (registry) registry->reset_stats();
    run_driven_grasp(run, options, result);
    registry.reset();  // detaches before the model goes
    return result;
  }
  GraspRun run(m, d, registry.get(), options, scene_path);
  mj_forward(m, d);
  throw_if_bad_start(m, d, run.object_, scene_path);
  if (registry) registry->reset_stats();
  result.object_z_initial = run.object_z();

  close_fingers(run, options, result);

  // Phase 2: squeeze, then settle.
  run.phase_ = "the squeeze";
  std::vector<double> closed(run.q_d_.begin(), run.q_d_.end());
  const auto observe_nothing = [] {};
  run.run_phase(
      options.squeeze_time,
      [&](double t) {
        const double f = std::min(1.0, t / options.squeeze_time);
        for (std::size_t i = kArmJoints; i < closed.size(); ++i) {
          const double hi = run.upper_[i - kArmJoints];
          run.q_d_[i] = std::min(hi, closed[i] + f * options.squeeze);
        }
      },
      observe_nothing);
  run.phase_ = "the settling";
  run.run_phase(
      options.settle_time, [](double) {}, observe_nothing);
  result.object_z_gripped = run.object_z();
  const GripSides grip = grip_sides(m, d, run.is_object_geom_, -1);
  const double palm_at_lift = d->xpos[3 * run.palm_ + 2];

  // Phase 3: lift along a cosine ramp, arm2 = -a s(t), arm3 = +a s(t).
  const int arm2 = mj_name2id(m, mjOBJ_JOINT, "arm2");
  const int arm3 = mj_name2id(m, mjOBJ_JOINT, "arm3");
  if (arm2 < 0 || arm3 < 0) throw std::runtime_error(scene_path + ": no joints arm2 and arm3");
  double link = 0;
  for (int k = 0; k < 3; ++k) {
    const double dx = d->xanchor[3 * arm3 + k] - d->xanchor[3 * arm2 + k];
    link += dx * dx;
  }
  link = std::sqrt(link);
  const double a = std::asin(std::clamp(options.lift_height / std::max(link, 1e-9), 0.0, 0.9));
  const double q2 = run.q_d_[1];
  const double q3 = run.q_d_[2];
  const double period = options.lift_time;
  run.phase_ = "the lift";
  run.run_phase(
      period,
      [&](double t) {
        const double w = M_PI / period;
        const double s = 0.5 * (1 - std::cos(w * t));
        const double sd = 0.5 * w * std::sin(w * t);
        const double sdd = 0.5 * w * w * std::cos(w * t);
        run.q_d_[1] = q2 - a * s;
        run.q_d_[2] = q3 + a * s;
        run.qd_d_[1] = -a * sd;
        run.qd_d_[2] = a * sd;
        run.qdd_d_[1] = -a * sdd;
        run.qdd_d_[2] = a * sdd;
      },
      observe_nothing);
  run.qd_d_[1] = run.qd_d_[2] = run.qdd_d_[1] = run.qdd_d_[2] = 0;

  // Phase 4: hold, watching the object against the palm.
  const std::array<double, 3> rel0 = run.object_in_palm();
  result.hold_min_z = run.object_z();
  result.hold_drift = 0;
  run.phase_ = "the hold";
  const long hold_steps = std::max(1L, std::lround(options.hold_time / m->opt.timestep));
  long hold_step = 0;
  run.run_phase(
      options.hold_time, [](double) {},
      [&] {
        watch_rest(m, d, run.object_, run.is_object_geom_, ++hold_step, hold_steps, result);
        result.hold_min_z = std::min(result.hold_min_z, run.object_z());
        const std::array<double, 3> rel = run.object_in_palm();
        const double drift = std::sqrt((rel[0] - rel0[0]) * (rel[0] - rel0[0]) +
                                       (rel[1] - rel0[1]) * (rel[1] - rel0[1]) +
                                       (rel[2] - rel0[2]) * (rel[2] - rel0[2]));
        result.hold_drift = std::max(result.hold_drift, drift);
        if (result.slip_time < 0 && result.hold_drift >= kHeldSlip) result.slip_time = d->time;
      });
  run.take_stats();

  finish_result(run, d, run.object_z(), result);
  result.hand_travel = d->xpos[3 * run.palm_ + 2] - palm_at_lift;
  result.object_rise = result.object_z_final - result.object_z_gripped;
  bool ever_touched = false;
  for (int step : result.first_contact) ever_touched = ever_touched || step > 0;
  judge(ever_touched, grip, result);
  registry.reset();  // detaches before the model goes
  return result;
}

}  // namespace graspcd::grasp
