// graspcd's function in MuJoCo's collision table, as a whole (docs/design.md, "The MuJoCo
// layer"). This header includes its three parts, one file each (in MuJoCo's
// engine_collision_<part> manner), included one way only: table -> served -> pose, and each of
// table and served -> registry.
//   collision_table.h   the table's entries (install, ScopedInstall), the model -> registry table
//                       (attach, Attachment) and collide_geoms, the entry itself
//   collision_served.h  the served paths: the tree query and its contacts, the exact box-box path
//   collision_pose.h    MuJoCo placements as graspcd poses, bad-number checks
//
// A call for a pair its model's registry serves runs that pair's path (registry.h) and returns
// graspcd's contacts; every other call goes to MuJoCo's saved original of its own type pair,
// unchanged, with the same arguments. Per served call (docs/mujoco.md): at most the pair's
// max_contacts (pair_config.h; 8 by default, never above mjMAXCONPAIR) contacts, dist <= 0,
// frame[0..2] the unit normal from geom1 toward geom2 and frame[3..8] a right-handed tangent basis
// (box-box pairs: MuJoCo's own contacts); MuJoCo fills the rest. Margins are ignored on served
// pairs: contacts are reported only for intersecting surfaces.
//
// Non-finite state: a served call whose geoms' geom_xpos or geom_xmat hold a NaN, an infinity or
// any number beyond mjMAXVAL (1e10, the bound of MuJoCo's mju_isBad) returns 0 contacts without a
// query or box test and counts one BridgeStats::nonfinite_skips.
#pragma once

#include "graspcd/mujoco/collision_pose.h"
#include "graspcd/mujoco/collision_served.h"
#include "graspcd/mujoco/collision_table.h"
