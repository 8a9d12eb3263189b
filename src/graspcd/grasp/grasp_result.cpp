#include "graspcd/grasp/grasp_result.h"

#include <algorithm>
#include <cstdio>
#include <optional>
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

std::string tilt_note(const GraspResult& result) {
  if (!result.held || result.tilt_final_deg < kTiltShownDeg) return "";
  char text[48];
  std::snprintf(text, sizeof text, "tilted %.0f\xc2\xb0", result.tilt_final_deg);
  return text;
}

std::string push_note(const GraspResult& result) {
  if (!result.held || !result.pushed_during_squeeze) return "";
  char text[64];
  std::snprintf(text, sizeof text, "pushed %.1f cm during the squeeze", 100 * result.squeeze_push);
  return text;
}

void judge_grasp(bool ever_touched, int touching, bool opposing, GraspResult& result) {
  result.gripped = opposing;
  result.pushed_during_squeeze = result.squeeze_push > kSqueezePush;
  const bool rose =
      result.hand_travel > 0 && result.grip_rise >= kHeldRiseShare * result.hand_travel;
  const bool slipped = result.hold_drift >= kHeldSlip;
  // Left the hand for good and fell behind it: the object sank more than kHeldSlip relative to
  // the hand's path from the start of the lift.
  const bool fell = result.hand_travel - result.object_rise > kHeldSlip;
  result.dropped_at.reset();
  if (ever_touched && result.gripped && !result.ejected && result.release_time >= 0 && fell) {
    result.dropped_at = result.release_time;
  }
  result.held = result.gripped && rose && !slipped && !result.ejected && !result.dropped_at;
  char text[160];
  if (result.ejected) {
    std::snprintf(text, sizeof text, "ejected at t = %.3f s (%.1f m/s)", result.ejected->time,
                  result.ejected->speed);
    result.reason = text;
  } else if (!ever_touched) {
    result.reason = "no segment reached the object";
  } else if (touching == 0) {
    result.reason = "no segment touched the object after the squeeze";
  } else if (!opposing) {
    result.reason = "no two touching segments push from opposing sides (" +
                    std::to_string(touching) + " touching)";
  } else if (result.dropped_at) {
    std::snprintf(text, sizeof text, "dropped at t = %.3f s", *result.dropped_at);
    result.reason = text;
  } else if (slipped) {
    std::snprintf(text, sizeof text, "slipped at t = %.3f s (moved %.1f cm in the hand)",
                  result.slip_time, 100 * result.hold_drift);
    result.reason = text;
  } else if (!rose) {
    std::snprintf(text, sizeof text,
                  "its grip rose %.1f cm of the hand's %.1f cm travel (less than %.0f%%)",
                  100 * result.grip_rise, 100 * result.hand_travel, 100 * kHeldRiseShare);
    result.reason = text;
  } else {
    result.reason.clear();
  }
}

double kinetic_energy(const mjModel* m, const mjData* d) {
  thread_local std::vector<mjtNum> mv;
  mv.resize(static_cast<std::size_t>(m->nv));
  mj_mulM(m, d, mv.data(), d->qvel);
  return 0.5 * mju_dot(d->qvel, mv.data(), m->nv);
}

double object_kinetic_energy(const mjModel* m, const mjData* d, int body,
                             std::vector<mjtNum>& scratch) {
  const auto nv = static_cast<std::size_t>(m->nv);
  scratch.assign(2 * nv, 0);
  mjtNum* v = scratch.data();
  mjtNum* mv = v + nv;
  const int root = m->body_rootid[body];
  for (int i = 0; i < m->nv; ++i) {
    if (m->body_rootid[m->dof_bodyid[i]] == root) v[i] = d->qvel[i];
  }
  mj_mulM(m, d, mv, v);
  return 0.5 * mju_dot(v, mv, m->nv);
}

}  // namespace graspcd::grasp
