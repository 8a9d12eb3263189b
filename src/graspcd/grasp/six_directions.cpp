#include "graspcd/grasp/six_directions.h"

namespace graspcd::grasp {

std::string six_direction_name(int k) {
  static const char* const kNames[kSixDirections] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  return k >= 0 && k < kSixDirections ? kNames[k] : "?";
}

std::array<double, 3> six_direction(const mjData* d, int hand, int k) {
  const int column = k / 2;
  const double sign = k % 2 == 0 ? 1.0 : -1.0;
  // xmat is row-major: column c of the rotation is entries c, c + 3, c + 6.
  const mjtNum* r = d->xmat + 9 * hand;
  return {sign * r[column], sign * r[column + 3], sign * r[column + 6]};
}

SixDirectionsModel::SixDirectionsModel(mjModel* m, int object, int support) : m_(m) {
  for (int k = 0; k < 3; ++k) gravity_[static_cast<std::size_t>(k)] = m->opt.gravity[k];
  weight_ = m->body_subtreemass[object] * mju_norm3(m->opt.gravity);
  mju_zero3(m->opt.gravity);
  const int root = support > 0 ? m->body_rootid[support] : 0;
  for (int g = 0; g < m->ngeom; ++g) {
    const int body = m->geom_bodyid[g];
    const bool of_support = support > 0 ? m->body_rootid[body] == root : body == 0;
    if (!of_support) continue;
    geoms_.push_back({g, m->geom_contype[g], m->geom_conaffinity[g]});
    m->geom_contype[g] = 0;
    m->geom_conaffinity[g] = 0;
  }
}

SixDirectionsModel::~SixDirectionsModel() {
  for (int k = 0; k < 3; ++k) m_->opt.gravity[k] = gravity_[static_cast<std::size_t>(k)];
  for (const auto& [g, contype, conaffinity] : geoms_) {
    m_->geom_contype[g] = contype;
    m_->geom_conaffinity[g] = conaffinity;
  }
}

}  // namespace graspcd::grasp
