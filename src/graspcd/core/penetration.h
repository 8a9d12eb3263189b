// Penetration depth at the vertices: how deep the points of one surface lie inside the solid of a
// closed mesh, measured as their Euclidean distance to its surface. The start-state check of a
// grasp (graspcd/grasp/start_check.h) asks it whether an object starts inside a finger or a
// finger inside the object.
//
// What it measures: the largest distance from a point inside the solid (point_side != kOutside,
// exact, containment.h) to the solid's surface. For two polyhedra A and B this is the largest
// depth of a vertex of B in A; the true penetration depth (the smallest translation that
// separates them) can be larger, for example where two edges cross with no vertex inside the
// other solid: a vertex measure underestimates, it never invents a penetration. The side of each
// point is exact; the distances are floating point (a few ulps of the coordinates).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb_tree.h"

namespace graspcd {

// The distance from p to the closed triangle t (its interior, edges and vertices). A zero-area
// triangle is the segment or point it spans.
// Algorithm: C. Ericson, Real-Time Collision Detection (2005), 5.1.5 "Closest point on triangle to
// point": the Voronoi regions of the vertices, then of the edges, then the face, by barycentric
// coordinates; a degenerate triangle falls back to its three edges as segments (5.1.2).
double point_triangle_distance(const Vec3& p, const Triangle& t);

// The distance from p to the nearest triangle of `tree` (its closed triangles), or some value at
// most `enough` as soon as the search finds a triangle at most `enough` away (the caller then
// needs no more: the search stops there). Branch and bound on the node boxes (a bounding volume
// hierarchy's closest-point query, Ericson (2005), 6.6), the nearer child first; a result above
// `enough` is the linear scan's minimum exactly. `stack` is scratch.
double nearest_surface_distance(const ObbTree& tree, const Vec3& p, double enough,
                                std::vector<std::int32_t>& stack);

struct VertexPenetration {
  double depth = 0;  // the deepest inside point's distance to the surface, m (0: none inside)
  std::size_t point = std::numeric_limits<std::size_t>::max();  // its index, or max() when none
  std::size_t inside = 0;  // points found inside the solid (up to the early stop)
};

// The deepest of `points` inside the solid bounded by `solid` (a closed mesh, its triangles in the
// frame of the points: no pose). Points outside the tree's root box are skipped without a query.
// The scan stops as soon as a point deeper than `stop_above` is found (its depth is then a lower
// bound of the maximum): the check needs only to know that the limit is passed. For each inside
// point the distance is the minimum over the solid's triangles, searched through the tree's boxes
// (branch and bound: a box farther than the nearest triangle so far is skipped) and abandoned once
// it is below the deepest depth found so far (it cannot raise the maximum: the early break of
// Hausdorff-distance computations, Taha and Hanbury, IEEE TPAMI 37(11), 2015).
// The mesh must be closed (containment.h, closedness(tree).closed()): the caller checks.
VertexPenetration deepest_point_inside(const ObbTree& solid, const std::vector<Vec3>& points,
                                       double stop_above = std::numeric_limits<double>::infinity());

}  // namespace graspcd
