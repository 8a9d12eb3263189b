#include "graspcd/grasp/motion_watch.h"

#include <algorithm>
#include <cmath>

#include "graspcd/grasp/six_directions.h"
#include "graspcd/mujoco/collision_pose.h"

namespace graspcd::grasp {

namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

// The angle of the rotation between two unit quaternions, 2 acos |q0 . q|, radians.
double rotation_angle(const std::array<double, 4>& q0, const mjtNum* q) {
  double dot = 0;
  for (std::size_t k = 0; k < 4; ++k) dot += q0[k] * q[k];
  return 2 * std::acos(std::min(1.0, std::abs(dot)));
}

// How far an object tipped from orientation q0 to q, radians: the angle between the world's up
// direction and where the object's axis that pointed up at q0 points at q. A turn about the up
// direction (a parallel gripper squaring a yawed block to its pads) is no tip.
double tip_angle(const std::array<double, 4>& q0, const mjtNum* q,
                 const std::array<double, 3>& up) {
  mjtNum r0[9], r[9];
  const mjtNum start[4] = {q0[0], q0[1], q0[2], q0[3]};
  mju_quat2Mat(r0, start);
  mju_quat2Mat(r, q);
  mjtNum axis[3], now[3];
  const mjtNum world_up[3] = {up[0], up[1], up[2]};
  mju_mulMatTVec(axis, r0, world_up, 3, 3);  // up in the object's frame at q0
  mju_mulMatVec(now, r, axis, 3, 3);         // that axis in the world at q
  return std::acos(std::clamp(mju_dot3(now, world_up), -1.0, 1.0));
}

double norm3(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  double s = 0;
  for (std::size_t k = 0; k < 3; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(s);
}

std::array<double, 3> position(const mjData* d, int body) {
  return {d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]};
}

// The linear speed of a body's centre of mass and its angular speed.
std::array<double, 2> speeds(const mjModel* m, const mjData* d, int body) {
  mjtNum v[6];
  mj_objectVelocity(m, d, mjOBJ_BODY, body, v, 0);
  return {std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]),
          std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])};
}

// The name TruePenetration gives a phase.
const char* penetration_phase(RunPhase phase) {
  switch (phase) {
    case RunPhase::kStart:
      return "the start";
    case RunPhase::kClose:
      return "the closing";
    case RunPhase::kSqueeze:
      return "the squeeze";
    case RunPhase::kSettle:
      return "the settling";
    case RunPhase::kLift:
      return "the lift";
    case RunPhase::kHold:
      return "the hold";
    case RunPhase::kDirection:
      break;
  }
  return "the six directions";
}

}  // namespace

std::string phase_record_name(RunPhase phase, int direction) {
  switch (phase) {
    case RunPhase::kStart:
      return "start";
    case RunPhase::kClose:
      return "close";
    case RunPhase::kSqueeze:
      return "squeeze";
    case RunPhase::kSettle:
      return "settle";
    case RunPhase::kLift:
      return "lift";
    case RunPhase::kHold:
      return "hold";
    case RunPhase::kDirection:
      break;
  }
  return "dir" + six_direction_name(direction);
}

void state_kinematics(const mjModel* m, mjData* d) {
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_crb(m, d);
  mj_comVel(m, d);
}

MotionWatch::~MotionWatch() = default;

MotionWatch::MotionWatch(const mjModel* m, const mjModel* truth, int object, int hand, int support,
                         const WatchOptions& options)
    : m_(m), object_(object), hand_(hand), support_(support), options_(options) {
  const double g = mju_norm3(m->opt.gravity);
  for (std::size_t k = 0; k < 3; ++k) {
    up_[k] = g > 0 ? -m->opt.gravity[k] / g : (k == 2 ? 1.0 : 0.0);
  }
  const int root = m->body_rootid[object];
  for (int b = 1; b < m->nbody; ++b) {
    if (m->body_rootid[b] == root) continue;
    double reach = 0;
    for (int g2 = m->body_geomadr[b]; g2 >= 0 && g2 < m->body_geomadr[b] + m->body_geomnum[b];
         ++g2) {
      double offset = 0;
      for (int k = 0; k < 3; ++k) {
        const double e = m->geom_pos[3 * g2 + k] - m->body_ipos[3 * b + k];
        offset += e * e;
      }
      reach = std::max(reach, std::sqrt(offset) + m->geom_rbound[g2]);
    }
    others_.push_back(b);
    others_reach_.push_back(reach);
  }
  const int support_root = support > 0 ? m->body_rootid[support] : -1;
  touch_ = std::make_unique<TrueTouch>(truth, object, support_root, options.touch_tolerance,
                                       options.surfaces);
  if (options.true_penetration) {
    penetration_ =
        std::make_unique<TruePenetrationWatch>(truth, object, support_root, options.surfaces);
  }
  extent_ = std::max(1.0, static_cast<double>(m->stat.extent));
}

double MotionWatch::height(const mjData* d, int body) const {
  double h = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto i = static_cast<std::size_t>(3 * body) + k;
    const auto s = static_cast<std::size_t>(3 * support_) + k;
    h += (d->xpos[i] - d->xpos[s]) * up_[k];
  }
  return h;
}

std::array<double, 3> MotionWatch::object_in_hand(const mjData* d) const {
  return {d->xpos[3 * object_] - d->xpos[3 * hand_],
          d->xpos[3 * object_ + 1] - d->xpos[3 * hand_ + 1],
          d->xpos[3 * object_ + 2] - d->xpos[3 * hand_ + 2]};
}

double MotionWatch::fastest_other(const mjData* d) const {
  double fastest = 0;
  for (std::size_t i = 0; i < others_.size(); ++i) {
    const std::array<double, 2> s = speeds(m_, d, others_[i]);
    fastest = std::max(fastest, s[0] + s[1] * others_reach_[i]);
  }
  return fastest;
}

// Every state from the start through the hold: the object's speed and energy, whether it was
// thrown out (the first time) and whether it fell off its support (the first time).
void MotionWatch::watch_speed(const mjData* d, double t) {
  GraspResult& r = measured_;
  const double speed = speeds(m_, d, object_)[0];
  r.max_speed = std::max(r.max_speed, speed);
  r.kinetic_energy_max = std::max(r.kinetic_energy_max, object_kinetic_energy(m_, d, object_));
  double com = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    com += d->xipos[3 * static_cast<std::size_t>(object_) + k] * up_[k];
  }
  peak_com_ = states_ == 1 ? com : std::max(peak_com_, com);
  fastest_other_ = std::max(fastest_other_, fastest_other(d));
  if (!r.ejected) {
    const double g = mju_norm3(m_->opt.gravity);
    const double limit =
        std::sqrt(2 * g * std::max(0.0, peak_com_ - com)) + fastest_other_ + kEjectMargin;
    const std::array<double, 3> at = position(d, object_);
    double down = 0;
    for (std::size_t k = 0; k < 3; ++k) down += (at[k] - start_[k]) * up_[k];
    down = std::min(0.0, down);
    double away = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double e = at[k] - start_[k] - down * up_[k];
      away += e * e;
    }
    if (speed > limit) {
      r.ejected = Ejection{t, speed, "speed", limit};
    } else if (std::sqrt(away) > extent_) {
      r.ejected = Ejection{t, speed, "away", extent_};
    }
  }
  const double h = height(d, object_);
  r.lowest_z = std::min(r.lowest_z, h);
  if (!r.fell && h < start_height_ - drop_) r.fell = Fall{t, speed};
}

// The start of the lift (the settling's last state): the heights, the orientation and the grip
// the lift and the hold are measured from.
void MotionWatch::at_lift_start(const mjData* d, double t) {
  GraspResult& r = measured_;
  r.object_z_gripped = height(d, object_);
  hand_at_lift_ = height(d, hand_);
  r.tilt_before_lift_deg = tip_angle(quat_start_, d->xquat + 4 * object_, up_) * kDegrees;
  for (std::size_t k = 0; k < 4; ++k)
    quat_lift_[k] = d->xquat[4 * static_cast<std::size_t>(object_) + k];
  const GripTouch grip = touch_->grip(d);
  r.touching_at_lift = grip.touching;
  r.gripped = grip.opposing;
  const Vec3 origin(d->xpos[3 * object_], d->xpos[3 * object_ + 1], d->xpos[3 * object_ + 2]);
  const Mat3 rotation = mujoco::from_row_major(d->xmat + 9 * object_);
  const Vec3 local = rotation.transpose() * (grip.point.value_or(origin) - origin);
  grip_local_ = {local.x(), local.y(), local.z()};
  grip_at_lift_ = r.object_z_gripped;
  for (std::size_t k = 0; k < 3; ++k)
    grip_at_lift_ += (rotation * local)[static_cast<int>(k)] * up_[k];
  r.release_time = grip.touching > 0 ? -1 : t;
  lifted_ = true;
}

void MotionWatch::sample_penetration(const mjData* d, RunPhase phase, double t) {
  const long index = states_ - 1;
  const long every = std::max(1, options_.sample);
  if (!penetration_ || index % every != 0) return;
  const CostTimer timer(options_.cost, CostPart::kTruePenetration);
  penetration_->measure(d, index / every + 1, t, penetration_phase(phase));
}

void MotionWatch::watch_direction(const mjData* d, bool last, int direction) {
  direction_ = direction;
  if (!last) return;
  DirectionResult result;
  result.name = six_direction_name(direction);
  result.moved = norm3(object_in_hand(d), held_in_hand_);
  result.touching = touch_->touching_now(d);
  result.passed = result.touching && result.moved < kSixDirectionsDistance;
  measured_.directions.push_back(result);
}

void MotionWatch::observe(const mjData* d, RunPhase phase, double t, bool last, int direction) {
  if (phase == RunPhase::kDirection) {
    watch_direction(d, last, direction);
    return;
  }
  GraspResult& r = measured_;
  ++states_;
  const std::array<double, 3> at = position(d, object_);
  if (states_ == 1) {
    start_ = at;
    for (std::size_t k = 0; k < 4; ++k) {
      quat_start_[k] = d->xquat[4 * static_cast<std::size_t>(object_) + k];
    }
    start_height_ = height(d, object_);
    r.object_z_initial = start_height_;
    r.lowest_z = start_height_;
    // Resting on its support in any pose, the object's origin lies at most 2 R below where it
    // started, R the farthest any of its geoms reaches from the origin.
    double reach = 0;
    const int root = m_->body_rootid[object_];
    for (int g = 0; g < m_->ngeom; ++g) {
      if (m_->body_rootid[m_->geom_bodyid[g]] != root) continue;
      double offset = 0;
      for (int k = 0; k < 3; ++k) {
        const double e = d->geom_xpos[3 * g + k] - d->xpos[3 * object_ + k];
        offset += e * e;
      }
      reach = std::max(reach, std::sqrt(offset) + m_->geom_rbound[g]);
    }
    drop_ = 2 * reach + kHeldSlip;
  }
  sample_penetration(d, phase, t);
  watch_speed(d, t);
  if (phase == RunPhase::kSqueeze && !squeeze_seen_) {
    squeeze_from_ = last_position_;
    squeeze_seen_ = true;
  }
  if (phase == RunPhase::kSqueeze || phase == RunPhase::kSettle) {
    r.squeeze_push = std::max(r.squeeze_push, norm3(at, squeeze_from_));
  }
  if (lifted_) {
    r.tilt_final_deg = rotation_angle(quat_lift_, d->xquat + 4 * object_) * kDegrees;
    r.tilt_deg = std::max(r.tilt_deg, r.tilt_final_deg);
    if (touch_->touching(d)) {
      r.release_time = -1;
    } else if (r.release_time < 0) {
      r.release_time = t;
    }
  }
  if (phase == RunPhase::kHold) {
    r.hold_min_z = std::min(r.hold_min_z, height(d, object_));
    r.hold_drift = std::max(r.hold_drift, norm3(object_in_hand(d), hold_from_));
    if (r.slip_time < 0 && r.hold_drift >= kHeldSlip) r.slip_time = t;
  }
  if (phase == RunPhase::kSettle && last) at_lift_start(d, t);
  if (phase == RunPhase::kLift && last) {
    hold_from_ = object_in_hand(d);
    r.hold_min_z = height(d, object_);
  }
  if (phase == RunPhase::kHold && last) {
    r.object_z_final = height(d, object_);
    r.hand_travel = height(d, hand_) - hand_at_lift_;
    r.object_rise = r.object_z_final - r.object_z_gripped;
    const Vec3 origin(d->xpos[3 * object_], d->xpos[3 * object_ + 1], d->xpos[3 * object_ + 2]);
    const Vec3 grip = origin + mujoco::from_row_major(d->xmat + 9 * object_) *
                                   Vec3(grip_local_[0], grip_local_[1], grip_local_[2]);
    double grip_height = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto s = static_cast<std::size_t>(3 * support_) + k;
      grip_height += (grip[static_cast<int>(k)] - d->xpos[s]) * up_[k];
    }
    r.grip_rise = grip_height - grip_at_lift_;
    held_in_hand_ = object_in_hand(d);
  }
  last_position_ = at;
  phase_ = phase;
}

void MotionWatch::fill(GraspResult& result) const {
  const GraspResult& r = measured_;
  result.object_z_initial = r.object_z_initial;
  result.object_z_gripped = r.object_z_gripped;
  result.object_z_final = r.object_z_final;
  result.hold_min_z = r.hold_min_z;
  result.hold_drift = r.hold_drift;
  result.slip_time = r.slip_time;
  result.hand_travel = r.hand_travel;
  result.object_rise = r.object_rise;
  result.grip_rise = r.grip_rise;
  result.tilt_deg = r.tilt_deg;
  result.tilt_final_deg = r.tilt_final_deg;
  result.tilt_before_lift_deg = r.tilt_before_lift_deg;
  result.max_speed = r.max_speed;
  result.kinetic_energy_max = r.kinetic_energy_max;
  result.ejected = r.ejected;
  result.fell = r.fell;
  result.lowest_z = r.lowest_z;
  result.squeeze_push = r.squeeze_push;
  result.release_time = r.release_time;
  result.touching_at_lift = r.touching_at_lift;
  result.gripped = r.gripped;
  result.directions = r.directions;
  if (penetration_) result.true_penetration = penetration_->result();
}

}  // namespace graspcd::grasp
