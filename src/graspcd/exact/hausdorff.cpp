// CGAL's bounded-error Hausdorff distance and mesh volume (hausdorff.h).
#include "graspcd/exact/hausdorff.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cstddef>
#include <stdexcept>

namespace graspcd::exact {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

// The meshes as one CGAL surface: the soup repaired (equal points merged, faces with a repeated
// vertex dropped), oriented (vertices duplicated where the surface is not a manifold) and
// converted.
Mesh surface_of(const std::vector<const TriangleMesh*>& meshes) {
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> faces;
  for (const TriangleMesh* m : meshes) {
    const std::size_t first = points.size();
    for (const Vec3& v : m->vertices) points.emplace_back(v.x(), v.y(), v.z());
    for (const auto& f : m->faces) {
      faces.push_back({first + static_cast<std::size_t>(f[0]),
                       first + static_cast<std::size_t>(f[1]),
                       first + static_cast<std::size_t>(f[2])});
    }
  }
  PMP::repair_polygon_soup(points, faces);
  PMP::orient_polygon_soup(points, faces);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  return mesh;
}

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
