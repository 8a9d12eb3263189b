#include "graspcd/grasp/driven_run.h"

#include <algorithm>
#include <cmath>

namespace graspcd::grasp {

DrivenRun::DrivenRun(const mjModel* m, mjData* d, mujoco::Registry* registry,
                     const DriveConfig& drive, const std::string& scene, const std::string& config)
    : HandRun(m, d, registry, scene), drive_(drive) {
  const auto bad = [&](const std::string& what) { return io::InputError(config, 0, what); };
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
  const int object = body(drive.object);
  hand_ = body(drive.hand);
  support_ = drive.support.empty() ? 0 : body(drive.support);
  lift_ = actuator(drive.lift_actuator);
  const double g = mju_norm3(m->opt.gravity);
  for (int k = 0; k < 3; ++k) up_[k] = g > 0 ? -m->opt.gravity[k] / g : (k == 2 ? 1.0 : 0.0);
  for (const CloseDrive& c : drive.close) {
    close_.push_back(actuator(c.actuator));
    std::vector<int> segments;
    for (const std::string& pattern : c.touch) {
      const std::vector<int> geoms = mujoco::match_geoms(m, pattern);
      if (geoms.empty()) {
        throw bad("'grasp': touch pattern '" + pattern + "' matches no collidable geom");
      }
      const int s = add_segment(pattern);
      for (int geom : geoms) add_segment_geom(geom, s);
      segments.push_back(s);
    }
    segments_of_drive_.push_back(segments);
  }
  stopped_.assign(close_.size(), false);
  set_object(object);
}

// One physics step: the hand's own servos track the controls.
void DrivenRun::advance() { mj_step(m_, d_); }

double DrivenRun::height_of(int body) const {
  double h = 0;
  for (int k = 0; k < 3; ++k) h += (d_->xpos[3 * body + k] - d_->xpos[3 * support_ + k]) * up_[k];
  return h;
}

double DrivenRun::clamp_ctrl(int a, double u) const {
  if (!m_->actuator_ctrllimited[a]) return u;
  return std::clamp(u, m_->actuator_ctrlrange[2 * a], m_->actuator_ctrlrange[2 * a + 1]);
}

// Each closing actuator that has not stopped moves by its step; one at the end of its ctrlrange
// stops.
void DrivenRun::begin_grasp_step(int) {
  for (std::size_t i = 0; i < close_.size(); ++i) {
    if (stopped_[i]) continue;
    const int a = close_[i];
    const double next = clamp_ctrl(a, d_->ctrl[a] + drive_.close[i].step);
    if (next == d_->ctrl[a]) stopped_[i] = true;
    d_->ctrl[a] = next;
  }
}

// An actuator stops when each of its touch patterns has touched; the closing is done when every
// actuator stopped.
bool DrivenRun::closing_done(int, const std::vector<bool>&, const GraspResult& result) {
  bool all_stopped = true;
  for (std::size_t i = 0; i < close_.size(); ++i) {
    bool every = true;
    for (int s : segments_of_drive_[i])
      every = every && result.first_contact[static_cast<std::size_t>(s)] > 0;
    if (every) stopped_[i] = true;
    all_stopped = all_stopped && stopped_[i];
  }
  return all_stopped;
}

void DrivenRun::begin_squeeze() {
  closed_.resize(close_.size());
  for (std::size_t i = 0; i < close_.size(); ++i) closed_[i] = d_->ctrl[close_[i]];
}

void DrivenRun::squeeze_targets(long i, long steps) {
  const double f = static_cast<double>(i) / static_cast<double>(steps);
  for (std::size_t j = 0; j < close_.size(); ++j) {
    const int a = close_[j];
    d_->ctrl[a] = clamp_ctrl(a, closed_[j] + f * drive_.close[j].squeeze);
  }
}

void DrivenRun::begin_lift() { lift_start_ = d_->ctrl[lift_]; }

// The lift actuator's control along a cosine ramp.
void DrivenRun::lift_targets(long i, long steps) {
  const double f = static_cast<double>(i) / static_cast<double>(steps);
  d_->ctrl[lift_] =
      clamp_ctrl(lift_, lift_start_ + drive_.lift_by * 0.5 * (1 - std::cos(M_PI * f)));
}

}  // namespace graspcd::grasp
