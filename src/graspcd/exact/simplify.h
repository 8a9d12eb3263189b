// Mesh decimation by CGAL's edge collapse, for `graspcd decompose --simplify`: HACD partitions a
// decimated copy of a large mesh (docs/design.md, "Convex decomposition and the race"). This
// header does not include CGAL; CGAL is reached from simplify.cpp, in the exact module.
#pragma once

#include <cstddef>

#include "graspcd/core/geometry.h"

namespace graspcd::exact {

// `mesh` decimated to at most `max_faces` faces by CGAL 5.5's
// Surface_mesh_simplification::edge_collapse with its default cost and placement, Lindstrom and
// Turk's ("Fast and memory efficient polygonal simplification", IEEE Visualization 1998). The
// soup is first welded and oriented as for the Hausdorff distance (hausdorff.h). A mesh of at
// most `max_faces` faces is returned as CGAL's welded copy, not decimated. The count can stay
// above `max_faces` when no edge may be collapsed any more (CGAL collapses only edges whose
// collapse keeps the surface's topology, its link condition): the caller reports the count. Throws
// std::invalid_argument on an empty mesh or `max_faces` == 0.
TriangleMesh simplify_edge_collapse(const TriangleMesh& mesh, std::size_t max_faces);

}  // namespace graspcd::exact
