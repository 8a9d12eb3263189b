// FCL (fcl_peer.h) as a replay method of the study: the peer rows of Table 1. The study library
// links no peer; the graspcd executable hands these to it (study.h, StudyOptions::peers).
//
// FCL: J. Pan, S. Chitta, D. Manocha, "FCL: A General Purpose Library for Collision and Proximity
// Queries", IEEE ICRA 2012; its OBB trees follow Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH
// 1996, as ours do.
#pragma once

#include <memory>
#include <vector>

#include "graspcd/peer/fcl_peer.h"
#include "graspcd/study/replay.h"
#include "graspcd/study/study.h"

namespace graspcd::peer {

// FCL's collide() on the scene's meshes (built once per mesh, in the mesh frame, from the same
// doubles our trees hold), all contacts: every intersecting triangle pair, as face indices.
std::unique_ptr<study::Querier> make_fcl_querier(const study::MeshScene& scene, FclBv bv);

// Table 1's peer rows: FCL's OBB tree and its RSS tree, all contacts ("fcl-obb", "fcl-rss"); none
// in a build without FCL (GRASPCD_WITH_FCL=OFF: fcl_querier_absent.cpp).
std::vector<study::PeerMethod> fcl_table_methods();

}  // namespace graspcd::peer
