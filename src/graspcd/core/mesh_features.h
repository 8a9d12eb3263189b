// Features of a triangle mesh that its contacts depend on: its vertices welded by exact
// coordinates (the adjacency the contact manifold grows patches by) and its sharp edges (the edges
// whose edge-edge directions triangle_pair_contact considers). Pure geometry.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd {

// The three vertices of a face as ids: two vertices have the same id exactly when their
// coordinates are equal (-0.0 and 0.0 alike), the relation the manifold grows patches by.
using FaceVertexIds = std::array<std::uint32_t, 3>;

// Welds `faces` by exact coordinates: one FaceVertexIds per face, ids 0, 1, ... numbered in the
// order of the coordinates' bit patterns. Throws std::length_error beyond 2^31 distinct vertices.
std::vector<FaceVertexIds> weld_vertex_ids(const std::vector<Triangle>& faces);

// Per face, 3 bits: bit k set when edge v[k] -> v[k+1] is sharp: its two faces (found by
// welding vertices with identical coordinates) meet at more than tol::kSharpEdgeAngle
// (tolerances.h), or the edge has one face or more than two, or a face is degenerate.
std::vector<std::uint8_t> sharp_edge_masks(const std::vector<Triangle>& faces);

// sharp_edge_masks(faces) with the faces' welded ids already at hand (`ids` from
// weld_vertex_ids(faces)), so that a mesh is welded once. Throws std::invalid_argument when `ids`
// and `faces` differ in length.
std::vector<std::uint8_t> sharp_edge_masks(const std::vector<Triangle>& faces,
                                           const std::vector<FaceVertexIds>& ids);

}  // namespace graspcd
