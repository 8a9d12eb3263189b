// How far an approximation of a surface lies from it, judged by CGAL: the one-sided Hausdorff
// distance with a stated error bound, and the volume of a closed mesh. This header does not
// include CGAL; CGAL is reached from hausdorff.cpp, in the exact module (docs/design.md, "Layers").
#pragma once

#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd::exact {

// A one-sided Hausdorff distance h(A, B) = max over points a of A of min over points b of B of
// |a - b| (metres, A and B surfaces), and the bound within which CGAL guarantees it:
// |distance - h(A, B)| <= error_bound.
struct BoundedHausdorff {
  double distance = 0;
  double error_bound = 0;
};

// h(from, to) for the union of the surfaces `from` (e.g. the convex pieces of a decomposition)
// and the surface `to` (the original mesh), by CGAL 5.5's
// Polygon_mesh_processing::bounded_error_Hausdorff_distance (Sequential_tag: the triangles of
// `from` subdivided until each one's bounds on its distance to `to`, taken from an AABB tree of
// `to`, are within the error bound; the CGAL 5.3 manual, "Bounded Hausdorff distance"). Both are
// triangle soups: equal vertices are welded and each soup oriented and made manifold by CGAL's
// polygon-soup routines (which change no point). `error_bound` > 0, metres. Throws
// std::invalid_argument on an empty soup.
BoundedHausdorff one_sided_hausdorff(const std::vector<TriangleMesh>& from, const TriangleMesh& to,
                                     double error_bound);

// The volume enclosed by a closed triangle mesh (m^3), CGAL's Polygon_mesh_processing::volume on
// the welded, oriented soup (outward faces). Throws std::invalid_argument when the welded soup is
// not a closed triangle mesh for CGAL.
double closed_mesh_volume(const TriangleMesh& mesh);

}  // namespace graspcd::exact
