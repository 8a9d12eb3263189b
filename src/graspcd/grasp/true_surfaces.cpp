#include "graspcd/grasp/true_surfaces.h"

#include "graspcd/mujoco/primitives.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

std::string geom_label(const mjModel* m, int g) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, g);
  if (name != nullptr && *name != '\0') return "geom '" + std::string(name) + "'";
  std::string type = mujoco::geom_type_name(m->geom_type[g]);
  if (m->geom_type[g] == mjGEOM_MESH) {
    const char* mesh = mj_id2name(m, mjOBJ_MESH, m->geom_dataid[g]);
    if (mesh != nullptr) type += " '" + std::string(mesh) + "'";
  }
  const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]);
  return "geom " + std::to_string(g) + " (" + type + " of body '" +
         (body != nullptr ? body : "world") + "')";
}

bool may_collide(const mjModel* m, int a, int b) {
  return (m->geom_contype[a] & m->geom_conaffinity[b]) != 0 ||
         (m->geom_contype[b] & m->geom_conaffinity[a]) != 0;
}

std::vector<Triangle> geom_triangles(const mjModel* m, int g) {
  std::vector<Triangle> out;
  const int type = m->geom_type[g];
  if (type == mjGEOM_MESH && m->geom_dataid[g] >= 0) {
    out = mujoco::Registry::mesh_triangles(m, m->geom_dataid[g]);
  } else if (mujoco::is_primitive(type)) {
    const TriangleMesh mesh = mujoco::tessellate_primitive(type, m->geom_size + 3 * g);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) out.push_back(mesh.triangle(f));
  }
  return out;
}

}  // namespace graspcd::grasp
