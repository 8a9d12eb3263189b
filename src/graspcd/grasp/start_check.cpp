#include "graspcd/grasp/start_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "graspcd/core/containment.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/core/penetration.h"
#include "graspcd/grasp/decomposed_pieces.h"
#include "graspcd/io/limit_text.h"
#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/collision_pose.h"
#include "graspcd/mujoco/primitives.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

namespace {

// "geom 'NAME'", or for an unnamed geom "geom N (TYPE of body 'BODY')"; with `names`, a mesh of
// the hand is called the hand's ("geom 12 (the robotiq hand's mesh 'pad' of body 'left')").
std::string geom_name(const mjModel* m, int g, const mujoco::SceneNames* names = nullptr) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, g);
  if (name != nullptr && *name != '\0') return "geom '" + std::string(name) + "'";
  const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]);
  std::string type = mujoco::geom_type_name(m->geom_type[g]);
  if (m->geom_type[g] == mjGEOM_MESH) {
    const char* mesh = mj_id2name(m, mjOBJ_MESH, m->geom_dataid[g]);
    if (mesh != nullptr) {
      type = (names != nullptr ? names->mesh_owner(mesh) : "") + type + " '" + mesh + "'";
    }
  }
  return "geom " + std::to_string(g) + " (" + type + " of body '" +
         (body != nullptr ? body : "world") + "')";
}

std::string millimetres(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f mm", metres * 1e3);
  return text;
}

// A depth beyond kStartPenetration, in mm with enough decimals to differ from it (0.5004 mm is
// not "0.5 mm" beside "at most 0.5 mm allowed").
std::string depth_mm(double metres) {
  return io::fixed_beyond(metres * 1e3, kStartPenetration * 1e3, 1) + " mm";
}

// How a refusal names what MuJoCo collides of a mesh geom: a piece of a decomposed scene
// (is_piece) by its number, its mesh and, when `names` has it, its file ("piece 3 of mesh 'bowl'
// (bowl16/bowl_piece_3.obj)"); any other mesh as its convex hull, "mesh 'bowl''s convex hull".
// `geom` words a geom that is not a piece ("geom 'finger'").
std::string piece_name(const mjModel* m, int g, const mujoco::SceneNames* names) {
  const char* mesh = mj_id2name(m, mjOBJ_MESH, m->geom_dataid[g]);
  const std::string name = mesh != nullptr ? mesh : "";
  const std::size_t at = name.rfind("__piece_");
  const std::string k = name.substr(at + 8);
  std::string out = "piece " + k + " of mesh '" + name.substr(0, at) + "'";
  const bool number =
      !k.empty() && k.size() < 10 && k.find_first_not_of("0123456789") == std::string::npos;
  const std::size_t index = number ? static_cast<std::size_t>(std::stoul(k)) : 0;
  if (number && names != nullptr && index < names->pieces.size()) {
    out += " (" + names->pieces[index] + ")";
  }
  return out;
}

// A geom's surface in the world: its triangles, their tree, whether it bounds a solid, and the
// points that probe the other geom's solid: its vertices and points along its edges at most
// kStartPenetration apart (an edge can cross a solid with both its ends outside).
struct WorldSurface {
  ObbTree tree;
  Closedness closedness;
  std::vector<Vec3> probes;
};

// The faces of a mesh's convex hull as MuJoCo 2.2 keeps it for its native collision (mesh_graph,
// built when the model is compiled by qhull, the Quickhull algorithm of Barber, Dobkin and
// Huhdanpaa, ACM TOMS 22(4), 1996; user_mesh.cc, MakeGraph): at mesh_graphadr, the
// ints numvert, numface, then vert_edgeadr[numvert], vert_globalid[numvert],
// edge_localid[numvert + 3 numface] and face_globalid[3 numface], the faces' vertices as indices
// into the mesh's vertices. Empty for a mesh without a graph.
std::vector<Triangle> hull_triangles(const mjModel* m, int mesh_id) {
  const int adr = m->mesh_graphadr[mesh_id];
  if (adr < 0) return {};
  const int* graph = m->mesh_graph + adr;
  const int numvert = graph[0];
  const int numface = graph[1];
  const int* face_globalid = graph + 2 + 3 * numvert + 3 * numface;
  const int vadr = m->mesh_vertadr[mesh_id];
  std::vector<Triangle> out(static_cast<std::size_t>(numface));
  for (int f = 0; f < numface; ++f) {
    Triangle& t = out[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) {
      const float* v = m->mesh_vert + 3 * (vadr + face_globalid[3 * f + k]);
      t.v[static_cast<std::size_t>(k)] = Vec3(v[0], v[1], v[2]);
    }
  }
  return out;
}

// `hull`: a mesh geom's surface is its convex hull (hull_triangles; its faces when it has none).
std::optional<WorldSurface> world_surface(const mjModel* m, const mjData* d, int g,
                                          bool hull = false) {
  std::vector<Triangle> local;
  const int type = m->geom_type[g];
  if (type == mjGEOM_MESH) {
    if (hull) local = hull_triangles(m, m->geom_dataid[g]);
    if (local.empty()) local = mujoco::Registry::mesh_triangles(m, m->geom_dataid[g]);
  } else if (mujoco::is_primitive(type)) {
    const TriangleMesh mesh = mujoco::tessellate_primitive(type, m->geom_size + 3 * g);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) local.push_back(mesh.triangle(f));
  }
  if (local.empty()) return std::nullopt;
  const Pose pose{mujoco::from_row_major(d->geom_xmat + 9 * g), mujoco::geom_position(d, g)};
  std::vector<Triangle> world;
  world.reserve(local.size());
  WorldSurface out;
  out.probes.reserve(3 * local.size());
  for (const Triangle& t : local) {
    world.push_back(apply_pose(pose, t));
    const Triangle& w = world.back();
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = w.v[static_cast<std::size_t>(k)];
      const Vec3& b = w.v[static_cast<std::size_t>((k + 1) % 3)];
      out.probes.push_back(a);
      const int n = static_cast<int>(std::ceil((b - a).norm() / kStartPenetration));
      for (int i = 1; i < n; ++i) out.probes.push_back(a + (b - a) * (static_cast<double>(i) / n));
    }
  }
  // MuJoCo gives each face fresh vertices, and each edge is walked from both faces: one copy of
  // each point is enough to test.
  std::sort(out.probes.begin(), out.probes.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  out.probes.erase(std::unique(out.probes.begin(), out.probes.end()), out.probes.end());
  out.tree = ObbTree::build(std::move(world));
  out.closedness = closedness(out.tree);
  return out;
}

// Whether geom `g`'s body is `body` or lies below it.
bool in_subtree(const mjModel* m, int g, int body) {
  if (body < 0) return false;
  for (int b = m->geom_bodyid[g]; b > 0; b = m->body_parentid[b]) {
    if (b == body) return true;
  }
  return false;
}

// Once per geom and check (`warned` by geom id), and only for a geom no other part reports: not
// the hand's (`open.hand_body`'s subtree: a hand's own open meshes are listed in its docs), not
// one the registry serves (it reports its open meshes, "mesh_open").
void warn_open(const mjModel* m, int g, std::vector<char>& warned, const mujoco::SceneNames& names,
               const OpenMeshes& open) {
  if (warned[static_cast<std::size_t>(g)]) return;
  warned[static_cast<std::size_t>(g)] = 1;
  if (in_subtree(m, g, open.hand_body) || (open.served && open.served(g))) return;
  warnings().add("start_check_open",
                 "start check: " + geom_name(m, g, &names) +
                     " is not a closed mesh: what lies inside it is not checked");
}

bool may_collide(const mjModel* m, int a, int b) {
  return (m->geom_contype[a] & m->geom_conaffinity[b]) != 0 ||
         (m->geom_contype[b] & m->geom_conaffinity[a]) != 0;
}

// Whether the bounding spheres of two geoms lie farther apart than kStartPenetration.
bool far_apart(const mjModel* m, const mjData* d, int a, int b) {
  const double gap = (mujoco::geom_position(d, a) - mujoco::geom_position(d, b)).norm() -
                     m->geom_rbound[a] - m->geom_rbound[b];
  return gap > kStartPenetration;
}

// "MuJoCo collides mesh 'M' as its convex hull, which WHAT lies X inside at the start"; inside a
// piece of a decomposed scene, "WHAT lies X inside piece K of mesh 'M' (FILE) at the start".
std::string inside_hull(const mjModel* m, int hull_geom, const std::string& what, double depth,
                        const mujoco::SceneNames& names) {
  if (is_piece(m, hull_geom)) {
    return what + " lies " + depth_mm(depth) + " inside " + piece_name(m, hull_geom, &names) +
           " at the start";
  }
  const char* mesh = mj_id2name(m, mjOBJ_MESH, m->geom_dataid[hull_geom]);
  const std::string named = mesh != nullptr && *mesh != '\0' ? "mesh '" + std::string(mesh) + "'"
                                                             : geom_name(m, hull_geom);
  return "MuJoCo collides " + named + " as its convex hull, which " + what + " lies " +
         depth_mm(depth) + " inside at the start";
}

}  // namespace

std::string check_start_state(const mjModel* m, const mjData* d, int object_body,
                              const mujoco::SceneNames& names, const OpenMeshes& open) {
  const int root = m->body_rootid[object_body];
  const auto in_object = [&](int g) { return m->body_rootid[m->geom_bodyid[g]] == root; };
  std::vector<char> warned(static_cast<std::size_t>(m->ngeom), 0);
  for (int o = 0; o < m->ngeom; ++o) {
    if (!in_object(o) || (m->geom_contype[o] == 0 && m->geom_conaffinity[o] == 0)) continue;
    std::optional<WorldSurface> object;  // built at the first geom near it
    for (int g = 0; g < m->ngeom; ++g) {
      if (in_object(g) || !may_collide(m, o, g)) continue;
      const int type = m->geom_type[g];
      if (type == mjGEOM_HFIELD) continue;
      if (type != mjGEOM_PLANE && far_apart(m, d, o, g)) continue;
      if (!object) {
        object = world_surface(m, d, o);
        if (!object) return "";  // a plane or height field as the object: nothing to check
      }
      const std::string what = geom_name(m, o) + " of the object";
      if (type == mjGEOM_PLANE) {
        // The plane's solid is the half-space below it (its z axis points out).
        const Mat3 R = mujoco::from_row_major(d->geom_xmat + 9 * g);
        const Vec3 normal = R.col(2);
        const Vec3 at = mujoco::geom_position(d, g);
        double depth = 0;
        for (const Vec3& v : object->probes) depth = std::max(depth, -normal.dot(v - at));
        if (depth > kStartPenetration) {
          return what + " lies " + depth_mm(depth) + " below the plane " + geom_name(m, g) +
                 " (at most " + millimetres(kStartPenetration) +
                 " allowed): put its lowest point on the support";
        }
        continue;
      }
      const std::optional<WorldSurface> other = world_surface(m, d, g);
      if (!other) continue;
      const bool object_closed = object->closedness.closed();
      const bool other_closed = other->closedness.closed();
      if (object_closed && other_closed) {
        const MeshContainment c = mesh_containment(object->tree, object->closedness, Pose{},
                                                   other->tree, other->closedness);
        if (c.a_inside_b) return what + " lies wholly inside " + geom_name(m, g);
        if (c.b_inside_a) return geom_name(m, g) + " lies wholly inside the object (" + what + ")";
      }
      if (other_closed) {
        const VertexPenetration p = deepest_point_inside(other->tree, object->probes);
        if (p.depth > kStartPenetration) {
          return what + " penetrates " + geom_name(m, g) + " by " + depth_mm(p.depth) +
                 " (at most " + millimetres(kStartPenetration) + " allowed)";
        }
      } else {
        warn_open(m, g, warned, names, open);
      }
      if (object_closed) {
        const VertexPenetration p = deepest_point_inside(object->tree, other->probes);
        if (p.depth > kStartPenetration) {
          return geom_name(m, g) + " penetrates the object (" + what + ") by " + depth_mm(p.depth) +
                 " (at most " + millimetres(kStartPenetration) + " allowed)";
        }
      } else {
        warn_open(m, o, warned, names, open);
      }
    }
  }
  return "";
}

std::string check_hull_start(const mjModel* m, const mjData* d, int object_body,
                             const mujoco::SceneNames& names) {
  const int root = m->body_rootid[object_body];
  const auto in_object = [&](int g) { return m->body_rootid[m->geom_bodyid[g]] == root; };
  for (int o = 0; o < m->ngeom; ++o) {
    if (!in_object(o) || (m->geom_contype[o] == 0 && m->geom_conaffinity[o] == 0)) continue;
    std::optional<WorldSurface> object;  // built at the first geom near it
    for (int g = 0; g < m->ngeom; ++g) {
      if (in_object(g) || !may_collide(m, o, g)) continue;
      const bool object_mesh = m->geom_type[o] == mjGEOM_MESH;
      const bool other_mesh = m->geom_type[g] == mjGEOM_MESH;
      // Planes, height fields and pairs of primitives collide as check_start_state sees them.
      if (!object_mesh && !other_mesh) continue;
      if (!mujoco::is_primitive(m->geom_type[g]) && !other_mesh) continue;
      if (far_apart(m, d, o, g)) continue;
      if (!object) {
        object = world_surface(m, d, o, true);
        if (!object) return "";
      }
      const std::optional<WorldSurface> other = world_surface(m, d, g, true);
      if (!other) continue;
      // A hull is convex and closed. The object's hull around the other geom first (a finger in
      // a bowl's cavity or a handle's hole), then the other's hull around the object. A mesh's
      // probes are its hull's: MuJoCo collides two meshes hull against hull.
      const auto probed = [&](int geom, std::string name) {
        if (is_piece(m, geom)) return piece_name(m, geom, &names);
        return m->geom_type[geom] == mjGEOM_MESH ? "the hull of " + name : name;
      };
      if (object_mesh && object->closedness.closed()) {
        const VertexPenetration p = deepest_point_inside(object->tree, other->probes);
        if (p.depth > kStartPenetration) {
          return inside_hull(m, o, probed(g, geom_name(m, g)), p.depth, names);
        }
      }
      if (other_mesh && other->closedness.closed()) {
        const VertexPenetration p = deepest_point_inside(other->tree, object->probes);
        if (p.depth > kStartPenetration) {
          return inside_hull(m, g, probed(o, geom_name(m, o) + " of the object"), p.depth, names);
        }
      }
    }
  }
  return "";
}

}  // namespace graspcd::grasp
