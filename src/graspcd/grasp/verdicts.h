// The verdicts of a grasp, computed by one function from what the motion watch measured
// (motion_watch.h): the same for `graspcd grasp`'s own run, for `graspcd judge`'s reading of a
// run record of any simulator, and for the object-set study (docs/design.md, "Semantics").
//
//  - held: the object was carried with the hand, whatever touched it: its grip point (the mean
//    of the true meshes' touching places at the start of the lift, carried with the object; its
//    origin without a touch) rose at least kHeldRiseShare of the hand's travel from the start of
//    the lift to the end of the hold, it moved less than kHeldSlip relative to the hand in the
//    hold, and it was neither ejected nor dropped. A held run has no reason.
//  - gripped: two hand geoms touched it from opposing sides at the start of the lift (true
//    meshes, true_touch.h); evidence, not a condition of held.
//  - ejected: a speed or a path that gravity and the hand cannot give: after any state, faster
//    than sqrt(2 g d) + v + kEjectMargin (d the fall of its centre of mass from the highest it
//    has been, v the fastest any point of another body has moved so far), or farther from its
//    start than the scene's extent (at least 1 m) other than downwards. Never held.
//  - dropped: not ejected, and it fell off its support (more than 2 R + kHeldSlip below its
//    start, R how far its geoms reach from its origin: dropped when it passed there), or it
//    touched the hand at the start of the lift, left it for good (release_time) and ended more
//    than kHeldSlip behind the hand's path. `drop` says where it went.
//  - pushed over: tipped by more than kPushedOverDeg from the start to the start of the lift (its
//    up axis turned away from up; a turn about gravity is no tip).
//  - tilted (held), pushed during the squeeze (held), pushed over, and a closing cut short by
//    --max-steps are notes beside the verdict, held or not.
//  - reason (not held), the first that applies: ejected, pushed over, dropped, the hand did not
//    touch it at the start of the lift, slipped, the grip rose too little.
//  - outcome (the race's): ejected; held, "held tilted" from kTiltShownDeg; else dropped.
#pragma once

#include <string>

#include "graspcd/grasp/grasp_result.h"

namespace graspcd::grasp {

// Sets gripped, held, pushed_during_squeeze, pushed_over, dropped_at, drop, reason, evidence,
// notes and outcome of `result` from its measures (motion_watch.h's fill, and closing and
// max_steps).
void judge_grasp(GraspResult& result);

// "tilted 12°" for a held object's final tilt of kTiltShownDeg or more, else "".
std::string tilt_note(const GraspResult& result);

// "pushed 12.0 cm during the squeeze" for a held object the squeeze moved more than
// kSqueezePush, else "".
std::string push_note(const GraspResult& result);

// The warning of a run whose true meshes went deeper than kSupportPenetrationLimit into the
// support: "the true meshes: the object went 9.6 mm into its support (geom 'table', t = 1.200 s,
// in the hold), past the 2 mm a resting object sinks: CAUSE", or "" within the limit. `cause`
// says how the run collided the object with its support.
std::string support_warning(const GraspResult& result, const std::string& cause);

}  // namespace graspcd::grasp
