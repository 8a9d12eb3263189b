// CGAL's bounded-error Hausdorff distance and mesh volume (hausdorff.h).
#include "graspcd/exact/hausdorff.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Surface_mesh.h>

#include <stdexcept>
#include <vector>

#include "graspcd/exact/cgal_surface.h"

namespace graspcd::exact {

namespace {
using detail::Mesh;
using detail::surface_of;
namespace PMP = CGAL::Polygon_mesh_processing;
}  // namespace

BoundedHausdorff one_sided_hausdorff(const std::vector<TriangleMesh>& from, const TriangleMesh& to,
                                     double error_bound) {
  std::vector<const TriangleMesh*> from_meshes;
  for (const TriangleMesh& m : from) from_meshes.push_back(&m);
  const Mesh a = surface_of(from_meshes);
  const Mesh b = surface_of({&to});
  if (a.is_empty() || b.is_empty()) {
    throw std::invalid_argument("exact::one_sided_hausdorff: an empty surface");
  }
  BoundedHausdorff out;
  out.error_bound = error_bound;
  out.distance = PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(a, b, error_bound);
  return out;
}

double closed_mesh_volume(const TriangleMesh& mesh) {
  Mesh m = surface_of({&mesh});
  if (m.is_empty() || !CGAL::is_closed(m) || !CGAL::is_triangle_mesh(m)) {
    throw std::invalid_argument("exact::closed_mesh_volume: not a closed triangle mesh");
  }
  // orient_polygon_soup makes the faces consistent, not outward: turn them out.
  if (!PMP::is_outward_oriented(m)) PMP::reverse_face_orientations(m);
  return PMP::volume(m);
}

}  // namespace graspcd::exact
