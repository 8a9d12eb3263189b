#include "graspcd/grasp/verdicts.h"

#include <cstdio>

namespace graspcd::grasp {

namespace {

std::string format(const char* pattern, double a, double b = 0, double c = 0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// Where a dropped object went.
std::string drop_text(const GraspResult& r) {
  if (r.fell) {
    return format("it fell off its support, %.3f m below its start at the end",
                  r.object_z_initial - r.object_z_final);
  }
  return format("it left the hand and ended %.3f m below the hand's path, on its support",
                r.hand_travel - r.object_rise);
}

std::string ejection_text(const Ejection& e) {
  if (e.cause == "away") {
    return format(
        "ejected at t = %.3f s (%.1f m/s): farther than the scene's %.2f m from its start", e.time,
        e.speed, e.limit);
  }
  return format(
      "ejected at t = %.3f s (%.1f m/s, faster than the %.1f m/s gravity and the hand "
      "could give)",
      e.time, e.speed, e.limit);
}

}  // namespace

std::string tilt_note(const GraspResult& result) {
  if (!result.held || result.tilt_final_deg < kTiltShownDeg) return "";
  return format("tilted %.0f\xc2\xb0", result.tilt_final_deg);
}

std::string push_note(const GraspResult& result) {
  if (!result.held || !result.pushed_during_squeeze) return "";
  return format("pushed %.1f cm during the squeeze", 100 * result.squeeze_push);
}

void judge_grasp(GraspResult& r) {
  r.pushed_during_squeeze = r.squeeze_push > kSqueezePush;
  r.pushed_over = r.tilt_before_lift_deg > kPushedOverDeg;
  const bool rose = r.hand_travel > 0 && r.grip_rise >= kHeldRiseShare * r.hand_travel;
  const bool slipped = r.hold_drift >= kHeldSlip;
  // Left behind the hand's path: the object sank more than kHeldSlip relative to the hand from
  // the start of the lift.
  const bool behind = r.hand_travel - r.object_rise > kHeldSlip;
  r.dropped_at.reset();
  r.drop.clear();
  if (!r.ejected) {
    if (r.fell) {
      r.dropped_at = r.fell->time;
    } else if (r.touching_at_lift > 0 && r.release_time >= 0 && behind) {
      r.dropped_at = r.release_time;
    }
    if (r.dropped_at) r.drop = drop_text(r);
  }
  r.held = rose && !slipped && !r.ejected && !r.dropped_at;

  r.evidence = format("its grip point rose %.4f m of the hand's %.4f m, drift %.4f m in the hold",
                      r.grip_rise, r.hand_travel, r.hold_drift) +
               "; " + std::to_string(r.touching_at_lift) + " hand geom" +
               (r.touching_at_lift == 1 ? "" : "s") + " touched it at the start of the lift" +
               (r.touching_at_lift >= 2
                    ? (r.gripped ? ", from opposing sides" : ", none from opposing sides")
                    : "");
  if (r.held) {
    r.reason.clear();
  } else if (r.ejected) {
    r.reason = ejection_text(*r.ejected);
  } else if (r.pushed_over) {
    r.reason = format("pushed over: tipped %.0f\xc2\xb0 before the lift", r.tilt_before_lift_deg);
  } else if (r.dropped_at) {
    r.reason = format("dropped at t = %.3f s: ", *r.dropped_at) + r.drop;
  } else if (r.touching_at_lift == 0) {
    r.reason = "the hand did not touch it at the start of the lift";
  } else if (slipped) {
    r.reason = format("slipped at t = %.3f s (moved %.1f cm in the hand)", r.slip_time,
                      100 * r.hold_drift);
  } else {
    r.reason = format("its grip rose %.1f cm of the hand's %.1f cm travel (less than %.0f%%)",
                      100 * r.grip_rise, 100 * r.hand_travel, 100 * kHeldRiseShare);
  }

  r.notes.clear();
  if (!tilt_note(r).empty()) r.notes.push_back(tilt_note(r));
  if (!push_note(r).empty()) r.notes.push_back(push_note(r));
  if (r.pushed_over && r.held) {
    r.notes.push_back(format("pushed over %.0f\xc2\xb0 before the lift", r.tilt_before_lift_deg));
  }
  if (r.closing == "max_steps") {
    r.notes.push_back("the closing was cut short at grasp step " + std::to_string(r.max_steps) +
                      " (--max-steps)");
  }

  if (r.ejected) {
    r.outcome = "ejected";
  } else if (r.held) {
    r.outcome = r.tilt_final_deg >= kTiltShownDeg ? "held tilted" : "held";
  } else {
    r.outcome = "dropped";
  }
}

std::string support_warning(const GraspResult& result, const std::string& cause) {
  const TruePenetration& p = result.true_penetration;
  if (p.support_max <= kSupportPenetrationLimit) return "";
  std::string where;
  if (p.side == "support" && p.step > 0) {
    where = " (" + p.geom + format(", t = %.3f s, in ", p.time) + p.phase + ")";
  }
  return format("the true meshes: the object went %.1f mm into its support", 1e3 * p.support_max) +
         where +
         format(", past the %.0f mm a resting object sinks: ", 1e3 * kSupportPenetrationLimit) +
         cause;
}

}  // namespace graspcd::grasp
