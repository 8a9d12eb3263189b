// Edge-collapse decimation (simplify.h).
//
// Lindstrom and Turk, "Fast and memory efficient polygonal simplification", IEEE Visualization
// 1998: each edge's collapse is placed where it keeps the volume and the boundary and minimises a
// quadratic of the change of volume and area, and edges are collapsed by that cost, the least
// first. CGAL's edge_collapse does all of it (its defaults are LindstromTurk_cost and
// LindstromTurk_placement, Debian's CGAL 5.5.1 Surface_mesh_simplification/edge_collapse.h);
// graspcd only chooses when to stop.
#include "graspcd/exact/simplify.h"

#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <stdexcept>

#include "graspcd/exact/cgal_surface.h"

namespace graspcd::exact {

TriangleMesh simplify_edge_collapse(const TriangleMesh& mesh, std::size_t max_faces) {
  if (max_faces == 0) throw std::invalid_argument("exact::simplify_edge_collapse: 0 faces");
  detail::Mesh surface = detail::surface_of({&mesh});
  if (surface.is_empty() || !CGAL::is_triangle_mesh(surface)) {
    throw std::invalid_argument("exact::simplify_edge_collapse: not a triangle mesh");
  }
  if (surface.number_of_faces() > max_faces) {
    // CGAL 5.5 stops on a count of edges. Every face has 3 edges and every edge at most 2 faces,
    // so 3 F <= 2 E: at most floor(3 max_faces / 2) edges leave at most max_faces faces, and the
    // predicate stops as soon as fewer than its threshold remain.
    namespace SMS = CGAL::Surface_mesh_simplification;
    const SMS::Count_stop_predicate<detail::Mesh> stop(3 * max_faces / 2 + 1);
    SMS::edge_collapse(surface, stop);
  }
  return detail::triangle_mesh_of(surface);
}

}  // namespace graspcd::exact
