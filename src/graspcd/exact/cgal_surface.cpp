// A graspcd triangle soup as a CGAL Surface_mesh and back (cgal_surface.h).
#include "graspcd/exact/cgal_surface.h"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>

#include <array>
#include <cstddef>
#include <cstdint>

namespace graspcd::exact {

namespace detail {

Mesh surface_of(const std::vector<const TriangleMesh*>& meshes) {
  namespace PMP = CGAL::Polygon_mesh_processing;
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

TriangleMesh triangle_mesh_of(const Mesh& mesh) {
  TriangleMesh out;
  // num_vertices() counts the removed vertices too: every index CGAL may hand out.
  std::vector<std::int32_t> index(mesh.num_vertices(), -1);
  for (const Mesh::Vertex_index v : mesh.vertices()) {
    index[static_cast<std::size_t>(v)] = static_cast<std::int32_t>(out.vertices.size());
    const Point& p = mesh.point(v);
    out.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const Mesh::Face_index f : mesh.faces()) {
    std::array<std::int32_t, 3> face{};
    std::size_t k = 0;
    for (const Mesh::Vertex_index v : mesh.vertices_around_face(mesh.halfedge(f))) {
      if (k < 3) face[k] = index[static_cast<std::size_t>(v)];
      ++k;
    }
    if (k == 3) out.faces.push_back(face);
  }
  return out;
}

}  // namespace detail

}  // namespace graspcd::exact
