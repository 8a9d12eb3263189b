// Contacts MuJoCo's solver can use, made from the intersecting triangle pairs of the tree query:
// the whole contact geometry in one include. Pure geometry (no MuJoCo; the MuJoCo layer writes the
// contacts into mjContact): everything is in geom1's frame, geom2's triangles already posed. One
// header per job:
//   triangle_contact.h  the contact of one intersecting triangle pair (TriContact,
//                       triangle_pair_contact)
//   mesh_features.h     a mesh's welded vertices and sharp edges (weld_vertex_ids,
//                       sharp_edge_masks)
//   contact_manifold.h  a geom pair's contacts reduced to a few per patch (build_contact_manifold,
//                       select_contacts)
//   reused_contacts.h   a pair's contacts kept and refreshed across steps (ReusedContacts,
//                       pose_drift, contact_drift)
#pragma once

#include "graspcd/core/contact_manifold.h"
#include "graspcd/core/mesh_features.h"
#include "graspcd/core/reused_contacts.h"
#include "graspcd/core/triangle_contact.h"
