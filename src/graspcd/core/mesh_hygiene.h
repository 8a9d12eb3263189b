// Mesh hygiene on load (docs/design.md, "Semantics"): welding equal vertices and dropping zero-area
// faces, with the bookkeeping that keeps the kept faces mappable to the input's face ids.
//
// - Welding: two vertices are the same when their coordinates compare equal (==, so -0.0 and 0.0
//   weld), as in containment.h. Mesh files and MuJoCo often give each face fresh vertices
//   (MuJoCo 2.2 always does for OBJ: nmeshvert == 3 * nmeshface); welding restores the adjacency.
// - Zero-area faces: faces whose three vertices are collinear or coincident, decided exactly
//   (predicates.h: the three coordinate projections of (b-a) x (c-a) are exactly zero). They span
//   a segment or a point and are dropped; the triangle tests still answer such triangles when
//   they are given directly (the `tritri` command).
// Everything here is exact on the input doubles; nothing is moved.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd {

// True when the triangle spans no area (exact).
bool is_zero_area(const Triangle& t);

// What clean_mesh and drop_zero_area_faces did.
struct HygieneReport {
  std::size_t input_vertices = 0;
  std::size_t welded_vertices = 0;  // vertices merged into an equal earlier vertex
  // Input face ids (0-based) of the dropped zero-area faces, ascending.
  std::vector<std::int32_t> dropped_faces;
  // For each kept face, in output order, its input face id (ascending: the order is kept).
  std::vector<std::int32_t> source_face;
};

// Welds equal vertices (the first occurrence keeps its place; vertex order is otherwise kept) and
// drops zero-area faces (decided after welding). Faces keep their order and winding.
TriangleMesh clean_mesh(const TriangleMesh& mesh, HygieneReport* report = nullptr);

// The same for a triangle soup (e.g. MuJoCo's mesh faces): drops zero-area triangles, keeping the
// order; `report` (optional) gets the dropped and kept input indices (no vertices are welded: a
// soup has no shared vertices to weld).
std::vector<Triangle> drop_zero_area_faces(const std::vector<Triangle>& triangles,
                                           HygieneReport* report = nullptr);

}  // namespace graspcd
