#include "graspcd/grasp/decomposed_pieces.h"

#include <stdexcept>
#include <string>

namespace graspcd::grasp {

bool is_piece(const mjModel* m, int g) {
  if (m->geom_type[g] != mjGEOM_MESH || m->geom_dataid[g] < 0) return false;
  const char* mesh = mj_id2name(m, mjOBJ_MESH, m->geom_dataid[g]);
  return mesh != nullptr && std::string(mesh).find("__piece_") != std::string::npos;
}

mujoco::ModelPtr true_object_model(const mjModel* m) {
  mujoco::ModelPtr copy(mj_copyModel(nullptr, m));
  if (!copy) throw std::runtime_error("true_object_model: mj_copyModel failed");
  // The pieces of a geom follow it in its body (write_decomposed_scene inserts them right after
  // it, and MuJoCo keeps a body's geoms in document order): the replaced geom is the nearest
  // geom before a piece that is not a piece. Each piece carries the geom's own collision bits.
  int replaced = -1;
  for (int g = 0; g < m->ngeom; ++g) {
    if (!is_piece(m, g)) {
      replaced = g;
      continue;
    }
    if (replaced >= 0 && m->geom_bodyid[replaced] == m->geom_bodyid[g]) {
      copy->geom_contype[replaced] = m->geom_contype[g];
      copy->geom_conaffinity[replaced] = m->geom_conaffinity[g];
    }
    copy->geom_contype[g] = 0;
    copy->geom_conaffinity[g] = 0;
  }
  return copy;
}

}  // namespace graspcd::grasp
