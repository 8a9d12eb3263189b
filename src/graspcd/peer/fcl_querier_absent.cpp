// fcl_querier.h in a build without FCL (GRASPCD_WITH_FCL=OFF): Table 1 has no peer rows.
// make_fcl_querier is not defined here; nothing in such a build calls it.
#include <vector>

#include "graspcd/peer/fcl_querier.h"

namespace graspcd::peer {

std::vector<study::PeerMethod> fcl_table_methods() { return {}; }

}  // namespace graspcd::peer
