// The start-state check of a grasp: before the first physics step, the object must not lie
// inside the hand, a finger or its support, nor any of them inside the object. A grasp that
// starts interpenetrated ends in a verdict that means nothing (MuJoCo pushes the bodies apart
// with whatever force the overlap gives), so run_grasp (grasp.h) refuses it as bad input.
//
// What is checked, at the initial state (after mj_forward): every geom of the object's body tree
// against every other geom the contype/conaffinity filter lets collide with it (explicit <pair>
// elements are not read), skipping pairs whose bounding spheres (geom_rbound) are farther apart
// than kStartPenetration. The geoms' surfaces are MuJoCo's own float vertices placed in the world
// (meshes: mesh_face, not the hull; primitives: the bridge's tessellations, primitives.h).
//  - A plane (the floor): the depth of the object's lowest vertex below it.
//  - Anything else: the depth inside the other's closed solid of each vertex of one geom and of
//    points along its edges at most kStartPenetration apart, both ways (exact inside test,
//    distance to the surface: core/penetration.h), and whether one lies wholly inside the other
//    (core/containment.h, mesh_containment, exact). The edge points catch an edge that crosses
//    the other solid with both ends outside (a finger's edge across an object's corner); a
//    crossing deeper than the tolerance is seen at least kStartPenetration / 2 less deep.
// It fails when a depth exceeds kStartPenetration or one geom lies wholly inside the other. A geom
// whose mesh is not closed has no inside: what lies in it is not checked, with a warning
// ("start_check_open") in the process's sink.
#pragma once

#include <mujoco/mujoco.h>

#include <string>

namespace graspcd::grasp {

// The largest penetration allowed at the start, m. A scene placed by hand or by graspcd grasp
// --object (the object's lowest point 0.5 mm above its support, fingers open) passes with room;
// MuJoCo's soft contacts at rest sink a fraction of a millimetre, which this also allows.
inline constexpr double kStartPenetration = 0.5e-3;

// The first violation as one message (no file name in front), or "" when the start state is
// valid. `object_body` is the object's body id; `d` holds the initial state after mj_forward.
std::string check_start_state(const mjModel* m, const mjData* d, int object_body);

}  // namespace graspcd::grasp
