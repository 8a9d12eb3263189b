#include "graspcd/grasp/start_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "graspcd/core/containment.h"
#include "graspcd/grasp/decomposed_pieces.h"
#include "graspcd/grasp/true_surfaces.h"
#include "graspcd/io/limit_text.h"
#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/collision_pose.h"
#include "graspcd/mujoco/primitives.h"

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

// The place of geom b in geom a's frame.
Pose pose_in(const mjData* d, int a, int b) { return mujoco::relative_pose(d, a, b); }

}  // namespace

std::string check_start_state(const mjModel* m, const mjData* d, int object_body,
                              const mujoco::SceneNames& names, const OpenMeshes& open,
                              SurfaceCache* surfaces) {
  std::unique_ptr<SurfaceCache> own;
  if (surfaces == nullptr) surfaces = (own = std::make_unique<SurfaceCache>(m)).get();
  const int root = m->body_rootid[object_body];
  const auto in_object = [&](int g) { return m->body_rootid[m->geom_bodyid[g]] == root; };
  std::vector<char> warned(static_cast<std::size_t>(m->ngeom), 0);
  std::vector<Vec3> placed;
  for (int o = 0; o < m->ngeom; ++o) {
    if (!in_object(o) || (m->geom_contype[o] == 0 && m->geom_conaffinity[o] == 0)) continue;
    const GeomSurface* object = nullptr;  // found at the first geom near it
    for (int g = 0; g < m->ngeom; ++g) {
      if (in_object(g) || !may_collide(m, o, g)) continue;
      const int type = m->geom_type[g];
      if (type == mjGEOM_HFIELD) continue;
      if (type != mjGEOM_PLANE && far_apart(m, d, o, g)) continue;
      if (object == nullptr) {
        object = surfaces->surface(o);
        if (object == nullptr)
          return "";  // a plane or height field as the object: nothing to check
      }
      const std::string what = geom_name(m, o) + " of the object";
      if (type == mjGEOM_PLANE) {
        // The plane's solid is the half-space below it (its z axis points out); a triangle lies
        // deepest below it at a vertex.
        const Mat3 R = mujoco::from_row_major(d->geom_xmat + 9 * g);
        const Vec3 normal = R.col(2);
        const Vec3 at = mujoco::geom_position(d, g);
        const Pose pose{mujoco::from_row_major(d->geom_xmat + 9 * o), mujoco::geom_position(d, o)};
        double depth = 0;
        for (const Vec3& v : object->vertices()) {
          depth = std::max(depth, -normal.dot(apply_pose(pose, v) - at));
        }
        if (depth > kStartPenetration) {
          return what + " lies " + depth_mm(depth) + " below the plane " + geom_name(m, g) +
                 " (at most " + millimetres(kStartPenetration) +
                 " allowed): put its lowest point on the support";
        }
        continue;
      }
      const GeomSurface* other = surfaces->surface(g);
      if (other == nullptr) continue;
      const bool object_closed = object->closed();
      const bool other_closed = other->closed();
      // In the object's frame: the other geom placed there.
      const Pose other_in_object = pose_in(d, o, g);
      if (object_closed && other_closed) {
        const MeshContainment c =
            mesh_containment(object->tree(), object->closedness(), other_in_object, other->tree(),
                             other->closedness());
        if (c.a_inside_b) return what + " lies wholly inside " + geom_name(m, g);
        if (c.b_inside_a) return geom_name(m, g) + " lies wholly inside the object (" + what + ")";
      }
      if (other_closed) {
        const ProbeDepth p = deepest_probe_inside(*other, *object, pose_in(d, g, o),
                                                  kStartPenetration, kStartPenetration, placed);
        if (p.depth > kStartPenetration) {
          return what + " penetrates " + geom_name(m, g) + " by " + depth_mm(p.depth) +
                 " (at most " + millimetres(kStartPenetration) + " allowed)";
        }
      } else {
        warn_open(m, g, warned, names, open);
      }
      if (object_closed) {
        const ProbeDepth p = deepest_probe_inside(*object, *other, other_in_object,
                                                  kStartPenetration, kStartPenetration, placed);
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
                             const mujoco::SceneNames& names, SurfaceCache* surfaces) {
  std::unique_ptr<SurfaceCache> own;
  if (surfaces == nullptr) surfaces = (own = std::make_unique<SurfaceCache>(m)).get();
  const int root = m->body_rootid[object_body];
  const auto in_object = [&](int g) { return m->body_rootid[m->geom_bodyid[g]] == root; };
  std::vector<Vec3> placed;
  for (int o = 0; o < m->ngeom; ++o) {
    if (!in_object(o) || (m->geom_contype[o] == 0 && m->geom_conaffinity[o] == 0)) continue;
    const GeomSurface* object = nullptr;  // found at the first geom near it
    for (int g = 0; g < m->ngeom; ++g) {
      if (in_object(g) || !may_collide(m, o, g)) continue;
      const bool object_mesh = m->geom_type[o] == mjGEOM_MESH;
      const bool other_mesh = m->geom_type[g] == mjGEOM_MESH;
      // Planes, height fields and pairs of primitives collide as check_start_state sees them.
      if (!object_mesh && !other_mesh) continue;
      if (!mujoco::is_primitive(m->geom_type[g]) && !other_mesh) continue;
      if (far_apart(m, d, o, g)) continue;
      if (object == nullptr) {
        object = surfaces->hull(o);
        if (object == nullptr) return "";
      }
      const GeomSurface* other = surfaces->hull(g);
      if (other == nullptr) continue;
      // A hull is convex and closed. The object's hull around the other geom first (a finger in
      // a bowl's cavity or a handle's hole), then the other's hull around the object. A mesh's
      // probes are its hull's: MuJoCo collides two meshes hull against hull.
      const auto probed = [&](int geom, std::string name) {
        if (is_piece(m, geom)) return piece_name(m, geom, &names);
        return m->geom_type[geom] == mjGEOM_MESH ? "the hull of " + name : name;
      };
      if (object_mesh && object->closed()) {
        const ProbeDepth p = deepest_probe_inside(*object, *other, pose_in(d, o, g),
                                                  kStartPenetration, kStartPenetration, placed);
        if (p.depth > kStartPenetration) {
          return inside_hull(m, o, probed(g, geom_name(m, g)), p.depth, names);
        }
      }
      if (other_mesh && other->closed()) {
        const ProbeDepth p = deepest_probe_inside(*other, *object, pose_in(d, g, o),
                                                  kStartPenetration, kStartPenetration, placed);
        if (p.depth > kStartPenetration) {
          return inside_hull(m, g, probed(o, geom_name(m, o) + " of the object"), p.depth, names);
        }
      }
    }
  }
  return "";
}

}  // namespace graspcd::grasp
