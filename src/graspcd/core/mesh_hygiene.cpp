// Mesh hygiene (mesh_hygiene.h): exact welding by coordinate equality and exact zero-area tests.
#include "graspcd/core/mesh_hygiene.h"

#include <array>
#include <map>

#include "graspcd/core/predicates.h"

namespace graspcd {

bool is_zero_area(const Triangle& t) {
  // (b-a) x (c-a) is zero exactly when its projections onto the three coordinate planes are.
  for (int drop = 0; drop < 3; ++drop) {
    if (predicates::orient2d(t.v[0], t.v[1], t.v[2], drop) != 0) return false;
  }
  return true;
}

TriangleMesh clean_mesh(const TriangleMesh& mesh, HygieneReport* report) {
  HygieneReport local;
  HygieneReport& r = report != nullptr ? *report : local;
  r = HygieneReport{};
  r.input_vertices = mesh.vertices.size();

  // Weld: each distinct position gets the index of its first occurrence. std::map compares with
  // <, under which -0.0 and 0.0 are equivalent, as == says.
  TriangleMesh out;
  std::map<std::array<double, 3>, std::int32_t> index_of;
  std::vector<std::int32_t> new_index(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& p = mesh.vertices[i];
    const auto [it, inserted] =
        index_of.try_emplace({p[0], p[1], p[2]}, static_cast<std::int32_t>(out.vertices.size()));
    if (inserted) out.vertices.push_back(p);
    new_index[i] = it->second;
  }
  r.welded_vertices = mesh.vertices.size() - out.vertices.size();

  // Drop the zero-area faces, keeping the others' order and winding.
  out.faces.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    std::array<std::int32_t, 3> face{};
    for (std::size_t k = 0; k < 3; ++k) {
      face[k] = new_index[static_cast<std::size_t>(mesh.faces[f][k])];
    }
    const Triangle t{{out.vertices[static_cast<std::size_t>(face[0])],
                      out.vertices[static_cast<std::size_t>(face[1])],
                      out.vertices[static_cast<std::size_t>(face[2])]}};
    if (is_zero_area(t)) {
      r.dropped_faces.push_back(static_cast<std::int32_t>(f));
    } else {
      r.source_face.push_back(static_cast<std::int32_t>(f));
      out.faces.push_back(face);
    }
  }
  return out;
}

std::vector<Triangle> drop_zero_area_faces(const std::vector<Triangle>& triangles,
                                           HygieneReport* report) {
  HygieneReport local;
  HygieneReport& r = report != nullptr ? *report : local;
  r = HygieneReport{};
  r.input_vertices = 3 * triangles.size();
  std::vector<Triangle> out;
  out.reserve(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    if (is_zero_area(triangles[f])) {
      r.dropped_faces.push_back(static_cast<std::int32_t>(f));
    } else {
      r.source_face.push_back(static_cast<std::int32_t>(f));
      out.push_back(triangles[f]);
    }
  }
  return out;
}

}  // namespace graspcd
