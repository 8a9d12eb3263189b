#include "graspcd/grasp/grasp_result.h"

#include <cstdio>
#include <string>
#include <vector>

namespace graspcd::grasp {

namespace {

constexpr int kFingers = 4;
constexpr int kSegmentsPerFinger = 3;

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

std::string tilt_note(const GraspResult& result) {
  if (!result.held || result.tilt_final_deg < kTiltShownDeg) return "";
  char text[48];
  std::snprintf(text, sizeof text, "tilted %.0f\xc2\xb0", result.tilt_final_deg);
  return text;
}

double kinetic_energy(const mjModel* m, const mjData* d) {
  thread_local std::vector<mjtNum> mv;
  mv.resize(static_cast<std::size_t>(m->nv));
  mj_mulM(m, d, mv.data(), d->qvel);
  return 0.5 * mju_dot(d->qvel, mv.data(), m->nv);
}

}  // namespace graspcd::grasp
