#include "graspcd/grasp/grasp_result.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace graspcd::grasp {

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

std::optional<ManifoldChoice> parse_manifold_choice(const std::string& text) {
  ManifoldChoice out;
  std::string count;
  if (text.rfind("support", 0) == 0) {
    count = text.substr(7);
  } else if (text.rfind("moment", 0) == 0) {
    out.reduction = ManifoldReduction::kMoment;
    count = text.substr(6);
  } else if (text.rfind("force", 0) == 0) {
    out.reduction = ManifoldReduction::kForce;
    count = text.substr(5);
  } else {
    return std::nullopt;
  }
  if (count.empty()) return out;
  if (count.size() > 2 || count[0] == '0' ||
      !std::all_of(count.begin(), count.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  const int n = std::stoi(count);
  if (n > mjMAXCONPAIR) return std::nullopt;
  out.max_contacts = n;
  return out;
}

double kinetic_energy(const mjModel* m, const mjData* d) {
  thread_local std::vector<mjtNum> mv;
  mv.resize(static_cast<std::size_t>(m->nv));
  mj_mulM(m, d, mv.data(), d->qvel);
  return 0.5 * mju_dot(d->qvel, mv.data(), m->nv);
}

double object_kinetic_energy(const mjModel* m, const mjData* d, int body) {
  const int root = m->body_rootid[body];
  double energy = 0;
  for (int b = root; b < m->nbody; ++b) {
    if (m->body_rootid[b] != root) continue;
    mjtNum v[6];
    mj_objectVelocity(m, d, mjOBJ_BODY, b, v, 0);
    mjtNum w[3];  // the angular velocity in the body's inertia frame
    mju_rotVecMatT(w, v, d->ximat + 9 * b);
    energy += 0.5 * m->body_mass[b] * mju_dot3(v + 3, v + 3);
    for (int k = 0; k < 3; ++k) energy += 0.5 * m->body_inertia[3 * b + k] * w[k] * w[k];
  }
  return energy;
}

}  // namespace graspcd::grasp
