// The seam with MuJoCo (docs/design.md, "The seam with MuJoCo"): graspcd's function in the entries
// of mjCOLLISIONFUNC that a served pair can reach.
//
// install() puts collide_geoms() into mjCOLLISIONFUNC[t1][t2] for every t1 <= t2 among the
// served types (sphere, capsule, ellipsoid, cylinder, box, mesh: 21 entries), saving each
// original; uninstall() puts each saved one back. An entry that is NULL at install time stays
// NULL (MuJoCo never collides that type pair, and a served pair of it would never reach us; in
// MuJoCo 2.2.2 all 21 entries are non-NULL: the primitive routines for sphere-sphere,
// sphere-capsule, capsule-capsule, sphere-box, capsule-box and box-box, the convex (MPR) routine
// for the rest). Plane and height-field rows are never touched. ScopedInstall owns the install:
// counted, the first one alive installs and the last one restores (NonconvexContacts holds one).
// The table is process-global and MuJoCo's function gets no user pointer, so registries are
// attached per model in a process-wide table (model -> registry) and looked up from the
// `const mjModel*` of each call; attach() returns the Attachment that detaches the registry, held
// by whoever attached it (the registry knows nothing of the table). Attaching and detaching take a
// mutex; a call's lookup does not (a fixed table of atomic slots, scanned). A call for a pair its
// model's registry serves runs that pair's path (registry.h: the exact box-box path, or the tree
// query) and returns our contacts; every other call goes to the saved original of its own type
// pair, unchanged, with the same arguments.
//
// Non-finite state: a served call whose geoms' geom_xpos or geom_xmat hold a NaN, an infinity or
// any number beyond MuJoCo's mjMAXVAL (1e10, the bound of its own mju_isBad) is skipped: it returns
// 0 contacts without running the tree query or the box test (whose answers on a NaN pose would mean
// nothing) and counts one BridgeStats::nonfinite_skips. Delegated pairs go to MuJoCo unchanged, as
// always.
//
// Contract per served call (docs/mujoco.md): at most the pair's max_contacts (pair_config.h;
// 8 by default, never above mjMAXCONPAIR) contacts, dist <= 0,
// frame[0..2] the unit normal from geom1 toward geom2 and frame[3..8] a right-handed tangent
// basis (box-box pairs: MuJoCo's own contacts); MuJoCo fills the rest. Margins are ignored on
// served pairs (contacts are reported only for intersecting surfaces, docs/design.md, "The seam
// with MuJoCo").
//
// Not thread-safe for concurrent install/uninstall while models step; attach/detach may run while
// other models step.
//
// The seam is three parts, one file each (in MuJoCo's engine_collision_<part> manner), included
// one way only: table -> served -> pose, and each of table and served -> registry.
//   collision_table.h   install/uninstall of mjCOLLISIONFUNC entries (ScopedInstall), the
//                       model -> registry table (attach, Attachment), and collide_geoms (the entry
//                       itself: served pair, given MuJoCo's saved box-box function, or saved
//                       original)
//   collision_pose.h    MuJoCo placements as graspcd poses, bad-number checks
//   collision_served.h  the served paths: the tree query and its contacts, the exact box-box path
// This header includes all three.
#pragma once

#include "graspcd/mujoco/collision_pose.h"
#include "graspcd/mujoco/collision_served.h"
#include "graspcd/mujoco/collision_table.h"
