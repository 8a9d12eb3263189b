// Deprecated include path of graspcd 0.1, kept for one release (removed in 0.3): the contact
// geometry moved to the core, <graspcd/core/contact.h>, namespace graspcd.
#pragma once

#include "graspcd/core/contact.h"
#include "graspcd/mujoco/bridge_namespace.h"

namespace graspcd::mujoco {
using graspcd::select_contacts;
using graspcd::sharp_edge_masks;
using graspcd::triangle_pair_contact;
using graspcd::TriContact;
}  // namespace graspcd::mujoco
