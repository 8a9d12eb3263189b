// The served paths of the MuJoCo layer: what graspcd answers for a pair its registry serves
// (registry.h).
#pragma once

#include <mujoco/mujoco.h>

#include "graspcd/mujoco/registry.h"

namespace graspcd::mujoco {

// Writes one contact `c` of geom1's frame (geom1 placed at rotation R1, position p1) into `out` in
// the world frame: dist = -depth, frame[0..2] the unit normal, frame[3..5] and [6..8] a
// right-handed tangent basis (the axis least aligned with the normal, crossed with it). The tree
// path's write of each kept contact; MuJoCo fills the rest of `out`.
void write_contact(const TriContact& c, const Mat3& R1, const Vec3& p1, mjContact& out);

// Runs a served pair by its path (registry.h); a pair whose placement in `d` holds a bad number
// is skipped and counted (collision.h, "Non-finite state"). Trees: the tree query with the pair's
// detector in all-contacts mode, the contact manifold of the intersecting triangle pairs
// (graspcd/core/contact.h). Box-box: the detector's box test, then `box_box`, MuJoCo's own box-box
// function (the table passes its saved original), with margin 0 unless the boxes were proven
// disjoint; none when it is null. At most the pair's max_contacts (<= mjMAXCONPAIR) written to
// `con`. Returns the count. Updates the pair's state on `d` (Registry::pair_state) and the
// registry's statistics.
int collide_served_pair(Registry& registry, int pair_index, const mjData* d, mjContact* con, int g1,
                        int g2, mjfCollision box_box);

}  // namespace graspcd::mujoco
