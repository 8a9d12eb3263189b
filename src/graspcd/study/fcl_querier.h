// FCL (src/graspcd/peer/fcl_peer.h) as a replay method: the peer column of Table 1
// (issue 5, item 1).
#pragma once

#include <memory>

#include "graspcd/peer/fcl_peer.h"
#include "graspcd/study/replay.h"

namespace graspcd::study {

// FCL's collide() on the scene's meshes (built once per mesh, in the mesh frame, from the same
// doubles our trees hold), all contacts: every intersecting triangle pair, as face indices.
std::unique_ptr<Querier> make_fcl_querier(const MeshScene& scene, peer::FclBv bv);

}  // namespace graspcd::study
