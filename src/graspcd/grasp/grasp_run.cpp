#include "graspcd/grasp/grasp_run.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace graspcd::grasp {

namespace {

constexpr int kArmJoints = 3;

std::vector<std::string> joint_names() {
  std::vector<std::string> names = {"arm1", "arm2", "arm3"};
  for (const std::string& s : finger_segment_names()) names.push_back(s);
  return names;
}

}  // namespace

GraspRun::GraspRun(const mjModel* m, mjData* d, mujoco::Registry* registry,
                   const GraspOptions& options, const std::string& scene)
    : HandRun(m, d, registry, scene),
      options_(options),
      scene_(scene),
      controller_(m, joint_names(), PdGains::critically_damped(options.omega)) {
  const std::size_t n = controller_.size();
  q_d_.resize(n);
  for (std::size_t i = 0; i < n; ++i) q_d_[i] = m->qpos0[controller_.drives()[i].qpos_adr];
  qd_d_.assign(n, 0);
  qdd_d_.assign(n, 0);
  for (int s = 0; s < kFingerSegments; ++s) {
    const std::string& name = finger_segment_names()[static_cast<std::size_t>(s)];
    add_segment_geom(require_id(m, mjOBJ_GEOM, name, scene, "geom"), add_segment(name));
    const int joint = require_id(m, mjOBJ_JOINT, name, scene, "joint");
    upper_[static_cast<std::size_t>(s)] = m->jnt_limited[joint] ? m->jnt_range[2 * joint + 1] : 10;
  }
  set_object(require_id(m, mjOBJ_BODY, "object", scene, "body"));
  hand_ = require_id(m, mjOBJ_BODY, "palm", scene, "body");
}

// One physics step: mj_step1 -> computed torque -> mj_step2 (controllers.h).
void GraspRun::advance() {
  controller_.set_target(q_d_, qd_d_, qdd_d_);
  mj_step1(m_, d_);
  controller_.apply(m_, d_);
  mj_step2(m_, d_);
}

double GraspRun::object_height() const { return d_->xpos[3 * object_ + 2]; }

// Grasp step k raises the target of every segment that has not stopped by kGraspStepRad, up to
// its joint's upper limit, in equal parts over the step's physics steps.
void GraspRun::begin_grasp_step(int) {
  for (int s = 0; s < kFingerSegments; ++s) {
    const auto i = static_cast<std::size_t>(s);
    step_start_[i] = q_d_[kArmJoints + i];
    step_end_[i] =
        stopped_[i] ? step_start_[i] : std::min(step_start_[i] + kGraspStepRad, upper_[i]);
  }
}

// The target ramp with its velocity feed-forward (zero at the step's last physics step).
void GraspRun::grasp_step_targets(int p, int n) {
  const double dt = m_->opt.timestep;
  const double f = static_cast<double>(p) / n;
  for (std::size_t i = 0; i < kFingerSegments; ++i) {
    q_d_[kArmJoints + i] = step_start_[i] + f * (step_end_[i] - step_start_[i]);
    qd_d_[kArmJoints + i] = p < n ? (step_end_[i] - step_start_[i]) / (n * dt) : 0.0;
  }
}

// A touching segment stops, and so do the ones proximal to it on its finger (GraspIt's autoGrasp
// rule): a proximal joint that kept closing would push the object with the touching segment. A
// segment also stops at its joint's upper limit. The closing is done when every finger has a
// segment that touched, or every segment stopped.
bool GraspRun::closing_done(int k, const std::vector<bool>& touched, const GraspResult& result) {
  for (std::size_t i = 0; i < kFingerSegments; ++i) {
    if (touched[i] && result.first_contact[i] == k) {
      const std::size_t base = i - i % kSegmentsPerFinger;
      for (std::size_t j = base; j <= i; ++j) stopped_[j] = true;
    }
    if (q_d_[kArmJoints + i] >= upper_[i]) stopped_[i] = true;
  }
  bool all_stopped = true;
  for (std::size_t i = 0; i < kFingerSegments; ++i) all_stopped = all_stopped && stopped_[i];
  bool every_finger = true;
  for (int finger = 0; finger < kFingers; ++finger) {
    bool any = false;
    for (int seg = 0; seg < kSegmentsPerFinger; ++seg) {
      any = any ||
            result.first_contact[static_cast<std::size_t>(finger * kSegmentsPerFinger + seg)] > 0;
    }
    every_finger = every_finger && any;
  }
  return every_finger || all_stopped;
}

void GraspRun::end_closing() {
  for (std::size_t i = 0; i < kFingerSegments; ++i) qd_d_[kArmJoints + i] = 0;
}

// Every finger target rises by `squeeze` rad over squeeze_time, up to its joint's upper limit.
void GraspRun::begin_squeeze() { closed_.assign(q_d_.begin(), q_d_.end()); }

void GraspRun::squeeze_targets(long i, long) {
  const double f = std::min(1.0, phase_time(i) / options_.squeeze_time);
  for (std::size_t j = kArmJoints; j < closed_.size(); ++j) {
    const double hi = upper_[j - kArmJoints];
    q_d_[j] = std::min(hi, closed_[j] + f * options_.squeeze);
  }
}

// The lift: arm2 -> -a and arm3 -> +a, a = asin(lift_height / L) with L the arm2-arm3 distance,
// so that the wrist rises by lift_height and the hand keeps its orientation.
void GraspRun::begin_lift() {
  const int arm2 = mj_name2id(m_, mjOBJ_JOINT, "arm2");
  const int arm3 = mj_name2id(m_, mjOBJ_JOINT, "arm3");
  if (arm2 < 0 || arm3 < 0) throw std::runtime_error(scene_ + ": no joints arm2 and arm3");
  double link = 0;
  for (int k = 0; k < 3; ++k) {
    const double dx = d_->xanchor[3 * arm3 + k] - d_->xanchor[3 * arm2 + k];
    link += dx * dx;
  }
  link = std::sqrt(link);
  lift_angle_ = std::asin(std::clamp(options_.lift_height / std::max(link, 1e-9), 0.0, 0.9));
  arm2_start_ = q_d_[1];
  arm3_start_ = q_d_[2];
}

// A cosine ramp, arm2 = -a s(t), arm3 = +a s(t), with velocity and acceleration feed-forward.
void GraspRun::lift_targets(long i, long) {
  const double a = lift_angle_;
  const double period = options_.lift_time;
  const double t = phase_time(i);
  const double w = M_PI / period;
  const double s = 0.5 * (1 - std::cos(w * t));
  const double sd = 0.5 * w * std::sin(w * t);
  const double sdd = 0.5 * w * w * std::cos(w * t);
  q_d_[1] = arm2_start_ - a * s;
  q_d_[2] = arm3_start_ + a * s;
  qd_d_[1] = -a * sd;
  qd_d_[2] = a * sd;
  qdd_d_[1] = -a * sdd;
  qdd_d_[2] = a * sdd;
}

void GraspRun::end_lift() { qd_d_[1] = qd_d_[2] = qdd_d_[1] = qdd_d_[2] = 0; }

}  // namespace graspcd::grasp
