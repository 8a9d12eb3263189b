// Geom selection and the geoms' trees (geom_trees.h).
#include "graspcd/mujoco/geom_trees.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "graspcd/core/mesh_hygiene.h"
#include "graspcd/mujoco/input_error.h"
#include "graspcd/mujoco/primitives.h"

namespace graspcd::mujoco {
namespace {

bool collidable(const mjModel* m, int g) {
  return m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0;
}

// The key of a primitive's tessellation: type and the sizes the type uses (others 0).
std::array<double, 4> primitive_key(const mjModel* m, int g) {
  const int type = m->geom_type[g];
  const mjtNum* s = m->geom_size + 3 * g;
  const int used = type == mjGEOM_SPHERE                               ? 1
                   : type == mjGEOM_CAPSULE || type == mjGEOM_CYLINDER ? 2
                                                                       : 3;
  std::array<double, 4> key{static_cast<double>(type), 0, 0, 0};
  for (int k = 0; k < used; ++k) key[static_cast<std::size_t>(k + 1)] = s[k];
  return key;
}

MeshTree make_tree(const std::vector<Triangle>& tris) {
  MeshTree mt;
  mt.tree = ObbTree::build(tris);
  mt.slot_of_face.assign(tris.size(), -1);
  const auto& ids = mt.tree.face_ids();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    mt.slot_of_face[static_cast<std::size_t>(ids[i])] = static_cast<std::int32_t>(i);
  }
  mt.vertex_ids = weld_vertex_ids(tris);  // tris[f] is face(f): the tree copies the triangles
  mt.sharp_masks = sharp_edge_masks(tris, mt.vertex_ids);
  mt.closedness = closedness(mt.tree);
  for (const Triangle& t : tris) {
    for (const Vec3& v : t.v) mt.radius = std::max(mt.radius, v.norm());
  }
  return mt;
}

// "mesh N 'name': dropped K zero-area faces (MuJoCo face ids, from 0: ...)".
std::string dropped_faces_message(const std::string& source, const std::string& what,
                                  const std::vector<std::int32_t>& dropped) {
  std::string ids;
  for (std::size_t i = 0; i < dropped.size() && i < 5; ++i) {
    ids += (i ? ", " : "") + std::to_string(dropped[i]);
  }
  if (dropped.size() > 5) ids += ", ...";
  return source + ": " + what + ": dropped " + std::to_string(dropped.size()) +
         " zero-area faces (MuJoCo face ids, from 0: " + ids + "; each spans a segment or a point)";
}

}  // namespace

std::string object_name(const mjModel* m, int type, int id) {
  const char* n = mj_id2name(m, type, id);
  return n ? std::string(n) : std::string();
}

bool served_geom_type(int type) { return type == mjGEOM_MESH || is_primitive(type); }

std::string unserved_geom(const mjModel* m, int g) {
  const std::string gname = object_name(m, mjOBJ_GEOM, g);
  return "geom " + std::to_string(g) + (gname.empty() ? "" : " '" + gname + "'") + " of type " +
         geom_type_name(m->geom_type[g]) +
         ", which graspcd does not serve (meshes, boxes, spheres, capsules, cylinders and "
         "ellipsoids only; planes and height fields stay with MuJoCo)";
}

std::vector<int> match_geoms(const mjModel* m, const std::string& pattern) {
  bool by_geom = true, by_body = true;
  std::string glob = pattern;
  if (glob.rfind("geom:", 0) == 0) {
    by_body = false;
    glob = glob.substr(5);
  } else if (glob.rfind("body:", 0) == 0) {
    by_geom = false;
    glob = glob.substr(5);
  }
  std::vector<int> out;
  for (int g = 0; g < m->ngeom; ++g) {
    const bool hit = (by_geom && glob_match(glob, object_name(m, mjOBJ_GEOM, g))) ||
                     (by_body && glob_match(glob, object_name(m, mjOBJ_BODY, m->geom_bodyid[g])));
    if (hit && collidable(m, g)) out.push_back(g);
  }
  return out;
}

std::vector<int> resolve_pattern(const mjModel* m, const std::string& pattern,
                                 const std::string& source) {
  std::vector<int> out = match_geoms(m, pattern);
  for (int g : out) {
    if (!served_geom_type(m->geom_type[g])) {
      throw io::InputError(source, 0, "pattern '" + pattern + "' matches " + unserved_geom(m, g));
    }
  }
  if (out.empty())
    throw io::InputError(source, 0, "pattern '" + pattern + "' matches no collidable geom");
  return out;
}

// Iterative glob matching with one backtrack point for the last '*' (the classic linear-time
// wildcard matcher, as in Krauss, "Matching Wildcards", Dr. Dobb's 2008).
bool glob_match(const std::string& pattern, const std::string& name) {
  std::size_t p = 0, n = 0, star = std::string::npos, mark = 0;
  while (n < name.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = n;
    } else if (p < pattern.size() && pattern[p] == name[n]) {
      ++p;
      ++n;
    } else if (star != std::string::npos) {
      p = star + 1;
      n = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

std::vector<Triangle> mesh_triangles(const mjModel* m, int mesh_id) {
  const int vadr = m->mesh_vertadr[mesh_id];
  const int fadr = m->mesh_faceadr[mesh_id];
  const int nface = m->mesh_facenum[mesh_id];
  std::vector<Triangle> out(static_cast<std::size_t>(nface));
  for (int f = 0; f < nface; ++f) {
    Triangle& t = out[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) {
      const float* v = m->mesh_vert + 3 * (vadr + m->mesh_face[3 * (fadr + f) + k]);
      t.v[static_cast<std::size_t>(k)] = Vec3(v[0], v[1], v[2]);
    }
  }
  return out;
}

GeomTrees::GeomTrees(const mjModel* m) {
  if (m) by_geom_.assign(static_cast<std::size_t>(m->ngeom), nullptr);
}

void GeomTrees::add_geom(const mjModel* m, int g, const std::string& source,
                         const WarningSink& warn, const SceneNames& names) {
  const MeshTree*& slot = by_geom_[static_cast<std::size_t>(g)];
  if (slot) return;
  slot = m->geom_type[g] == mjGEOM_MESH ? &mesh_tree_of(m, m->geom_dataid[g], source, warn, names)
                                        : &primitive_tree_of(m, g, source);
}

// Mesh hygiene: the tree leaves zero-area faces out (core/mesh_hygiene.h).
const MeshTree& GeomTrees::mesh_tree_of(const mjModel* m, int mesh, const std::string& source,
                                        const WarningSink& warn, const SceneNames& names) {
  auto it = meshes_.find(mesh);
  if (it != meshes_.end()) return it->second;
  HygieneReport hygiene;
  const std::vector<Triangle> tris = drop_zero_area_faces(mesh_triangles(m, mesh), &hygiene);
  const std::string mname = object_name(m, mjOBJ_MESH, mesh);
  const std::string what =
      "mesh " + std::to_string(mesh) + (mname.empty() ? "" : " '" + mname + "'");
  if (tris.empty()) throw io::InputError(source, 0, what + " has no face of non-zero area");
  // The object mesh of a scene graspcd wrote from a user's file (SceneNames::object_mesh): the
  // reader that copied the file reported its zero-area faces, under the user's file and in its
  // face order; the same fault is not reported again here.
  const bool reported = !names.object_mesh.empty() && mname == names.object_mesh;
  if (!hygiene.dropped_faces.empty() && !reported) {
    warn("mesh_zero_area_faces",
         dropped_faces_message(source, names.mesh_owner(mname) + what, hygiene.dropped_faces));
  }
  MeshTree built = make_tree(tris);
  built.source_face = std::move(hygiene.source_face);
  return meshes_.emplace(mesh, std::move(built)).first->second;
}

const MeshTree& GeomTrees::primitive_tree_of(const mjModel* m, int g, const std::string& source) {
  const std::array<double, 4> k = primitive_key(m, g);
  auto it = primitives_.find(k);
  if (it != primitives_.end()) return it->second;
  TriangleMesh shape;
  try {
    shape = tessellate_primitive(m->geom_type[g], m->geom_size + 3 * g);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(source, 0, "geom " + std::to_string(g) + ": " + e.what());
  }
  std::vector<Triangle> tris;
  for (std::size_t f = 0; f < shape.faces.size(); ++f) tris.push_back(shape.triangle(f));
  return primitives_.emplace(k, make_tree(tris)).first->second;
}

}  // namespace graspcd::mujoco
