#include "graspcd/core/reused_contacts.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace graspcd {
namespace {

// The turn ||R - R0||_2 of pose_drift (reused_contacts.h): ||R - R0||_2 = ||R0^T R - I||_2 =
// 2 sin(theta / 2), and ||R0^T R - I||_F = 2 sqrt(2) sin(theta / 2) (two singular values of
// 2 sin(theta / 2), one 0).
double turn_norm(const Pose& from, const Pose& to) {
  return (to.R - from.R).norm() / std::sqrt(2.0);
}

// contact_drift with the turn ||R - R0||_2 already at hand.
double contact_drift_turned(const Pose& from, const Pose& to, double turn, double radius_a,
                            double radius_b) {
  const double seen_from_b = (to.R.transpose() * to.t - from.R.transpose() * from.t).norm();
  return std::min((to.t - from.t).norm() + turn * radius_b, seen_from_b + turn * radius_a);
}

}  // namespace

double pose_drift(const Pose& from, const Pose& to, double radius) {
  return (to.t - from.t).norm() + turn_norm(from, to) * radius;
}

// contact_drift: the bound of reused_contacts.h. The inverse pose is (R^T, -R^T t), and
// ||R^T - R0^T|| = ||R - R0||.
double contact_drift(const Pose& from, const Pose& to, double radius_a, double radius_b) {
  return contact_drift_turned(from, to, turn_norm(from, to), radius_a, radius_b);
}

// After Bullet's btPersistentManifold (refreshContactPoints): points kept on both bodies, the
// depth refreshed as their penetration along the contact normal.
void ReusedContacts::store(const Pose& pose, const std::vector<TriContact>& contacts,
                           const std::vector<double>& gains) {
  valid_ = !contacts.empty();
  if (!valid_) return;
  pose_ = pose;
  contacts_ = contacts;
  if (gains.size() == contacts.size()) {
    gains_ = gains;
  } else {
    gains_.assign(contacts.size(), 1.0);
  }
  on_b_.clear();
  reach_ = 0;
  const Mat3 Rt = pose.R.transpose();
  for (const TriContact& c : contacts) {
    // The contact lies midway: geom2's surface point half the depth back along the normal (the
    // normal points from geom1 toward geom2, and geom2 reaches depth into geom1).
    const Vec3 on_b = c.pos - 0.5 * c.depth * c.normal;
    reach_ = std::max(reach_, on_b.norm());
    on_b_.push_back(Rt * (on_b - pose.t));
  }
}

bool ReusedContacts::refresh(const Pose& pose, double radius_a, double radius_b, double max_drift,
                             std::vector<TriContact>& out) const {
  if (!valid_) return false;
  if (pose.R == pose_.R && pose.t == pose_.t) {
    out = contacts_;
    return true;
  }
  // The points of geom2 near geom1 moved at most the drift, and (the normal is not refreshed: it
  // is off by the pair's turn) the larger geom's rim turned at most the drift. NaN: not reused.
  const double turn = turn_norm(pose_, pose);
  if (!(contact_drift_turned(pose_, pose, turn, std::max(radius_a, reach_), radius_b) <=
            max_drift &&
        turn * std::max(radius_a, radius_b) <= max_drift)) {
    return false;
  }
  out.resize(contacts_.size());
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const TriContact& c = contacts_[i];
    const Vec3 on_a = c.pos + 0.5 * c.depth * c.normal;
    const Vec3 on_b = pose.R * on_b_[i] + pose.t;
    const double raw = (on_a - on_b).dot(c.normal);
    const double depth = gains_[i] == 1.0 ? raw : c.depth + gains_[i] * (raw - c.depth);
    if (depth < 0) return false;
    out[i].normal = c.normal;
    out[i].depth = depth;
    out[i].pos = 0.5 * (on_a + on_b);
  }
  return true;
}

}  // namespace graspcd
