// The start-state check of a grasp: before the first physics step, the object must not lie
// inside the hand, a finger or its support, nor any of them inside the object (a grasp that
// starts interpenetrated ends in a verdict that means nothing); run_grasp (grasp.h) refuses it as
// bad input.
//
// What is checked, at the initial state (after mj_forward): every geom of the object's body tree
// against every other geom the contype/conaffinity filter lets collide with it (explicit <pair>
// elements are not read), skipping pairs whose bounding spheres (geom_rbound) are farther apart
// than kStartPenetration. The geoms' surfaces are MuJoCo's own float vertices in the geoms' frames
// (meshes: mesh_face, not the hull; primitives: the MuJoCo layer's tessellations, primitives.h;
// surface_cache.h), one geom placed in the other's frame by the state.
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

#include <functional>
#include <string>

#include "graspcd/grasp/surface_cache.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::grasp {

// The largest penetration allowed at the start, m. A scene placed by hand or by graspcd grasp
// --object (the object's lowest point 0.5 mm above its support, fingers open) passes with room;
// MuJoCo's soft contacts at rest sink a fraction of a millimetre, which this also allows.
inline constexpr double kStartPenetration = 0.5e-3;

// Which open meshes the start check leaves unreported (each is reported elsewhere, once): the
// geoms of the hand (the subtree of `hand_body`, the "grasp" section's "hand"; docs/real-hands.md
// lists the real hands' open meshes) and the geoms `served` says the registry serves (it warns
// "mesh_open" for those).
struct OpenMeshes {
  int hand_body = -1;
  std::function<bool(int geom)> served;
};

// The first violation as one message (no file name in front), or "" when the start state is
// valid. `object_body` is the object's body id; `d` holds the initial state after mj_forward.
// `names` words the warnings of a scene graspcd wrote (a mesh of the hand called the hand's).
// An open mesh near the object is the warning "start_check_open" (what lies inside it is not
// checked), but for those `open` leaves out. `surfaces`: the geoms' surfaces (surface_cache.h),
// kept by the caller across grasps of one model (null: built for this check).
std::string check_start_state(const mjModel* m, const mjData* d, int object_body,
                              const mujoco::SceneNames& names = {}, const OpenMeshes& open = {},
                              SurfaceCache* surfaces = nullptr);

// The start as MuJoCo's native collision sees it (--native, and the pieces of --decomposed, which
// are mesh geoms collided natively): every mesh geom is its convex hull (MuJoCo 2.2's mesh_graph,
// the hull qhull built when the model was compiled). For each object geom and each geom near it
// that may collide with it, when one of them is a mesh, the same probes as above (vertices and
// edge points; of a mesh, its hull's) and their depth inside a mesh's hull: first the other
// geom's inside the object's hull, then the object's inside the other's hull. The first depth
// beyond kStartPenetration as one message, "MuJoCo collides mesh 'bowl' as its convex hull, which
// geom 'left_pad' lies 18.3 mm inside at the start" (a mesh's probes are named "the hull of geom
// ..."), or "" when none. A piece of a decomposed scene is convex and is named as the piece it is,
// with its file from `names` (SceneNames::pieces): "geom 'table' lies 3.6 mm inside piece 0 of
// mesh 'object_mesh' (can/textured_piece_0.obj) at the start". A start that passes
// check_start_state and fails this one is a limit of the hull (or of the pieces), not of the
// scene. Primitives against primitives, planes and height fields are left to check_start_state,
// which sees them as MuJoCo collides them. Every depth is printed with enough decimals to differ
// from kStartPenetration. `surfaces` as for check_start_state.
std::string check_hull_start(const mjModel* m, const mjData* d, int object_body,
                             const mujoco::SceneNames& names = {},
                             SurfaceCache* surfaces = nullptr);

}  // namespace graspcd::grasp
