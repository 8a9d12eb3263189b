// The race's judge (contact_judge.h).
#include "graspcd/study/contact_judge.h"

#include <algorithm>
#include <stdexcept>

#include "graspcd/core/geometry.h"
#include "graspcd/exact/exact.h"
#include "graspcd/exact/surface_distance.h"
#include "graspcd/grasp/decomposed_scene.h"
#include "graspcd/mujoco/collision_pose.h"
#include "graspcd/mujoco/primitives.h"

namespace graspcd::study {

namespace {

// A geom's triangles in its geom frame: a mesh's from MuJoCo's float vertices (as the registry's
// trees), a primitive's tessellation (graspcd/mujoco/primitives.h: a box exactly, curved ones
// circumscribed within tessellation_tolerance).
TriangleMesh geom_mesh(const mjModel* m, int g) {
  if (m->geom_type[g] != mjGEOM_MESH)
    return mujoco::tessellate_primitive(m->geom_type[g], m->geom_size + 3 * g);
  const int mesh = m->geom_dataid[g];
  TriangleMesh out;
  const int vadr = m->mesh_vertadr[mesh];
  for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
    const float* p = m->mesh_vert + 3 * (vadr + v);
    out.vertices.emplace_back(p[0], p[1], p[2]);
  }
  const int fadr = m->mesh_faceadr[mesh];
  for (int f = 0; f < m->mesh_facenum[mesh]; ++f) {
    const int* i = m->mesh_face + 3 * (fadr + f);
    out.faces.push_back({i[0], i[1], i[2]});
  }
  return out;
}

std::string geom_name(const mjModel* m, int g) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, g);
  return name != nullptr ? name : "geom" + std::to_string(g);
}

// The point p (world frame) in geom g's frame.
Vec3 in_geom_frame(const mjData* d, int g, const mjtNum* p) {
  const mjtNum* R = d->geom_xmat + 9 * g;
  const mjtNum* t = d->geom_xpos + 3 * g;
  const Vec3 r(p[0] - t[0], p[1] - t[1], p[2] - t[2]);
  // x_local = R^T (x - t), R row-major.
  return Vec3(R[0] * r.x() + R[3] * r.y() + R[6] * r.z(),
              R[1] * r.x() + R[4] * r.y() + R[7] * r.z(),
              R[2] * r.x() + R[5] * r.y() + R[8] * r.z());
}

struct JudgedGeom {
  int id = -1;
  std::string name;
  std::string body;
  TriangleMesh mesh;
  std::vector<Triangle> triangles;
  std::unique_ptr<exact::SurfaceDistance> surface;
};

JudgedGeom judged(const mjModel* m, int g) {
  JudgedGeom j;
  j.id = g;
  j.name = geom_name(m, g);
  const char* body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]);
  j.body = body != nullptr ? body : "body" + std::to_string(m->geom_bodyid[g]);
  j.mesh = geom_mesh(m, g);
  for (std::size_t f = 0; f < j.mesh.faces.size(); ++f) j.triangles.push_back(j.mesh.triangle(f));
  j.surface = std::make_unique<exact::SurfaceDistance>(j.mesh);
  return j;
}

}  // namespace

struct ContactJudge::Impl {
  int object = -1;
  std::vector<char> in_object;  // by geom
  std::vector<int> hand_index;  // by geom: index into hand, or -1
  std::vector<JudgedGeom> hand, truth;
  ContactJudgeSummary summary;
  double inflation = 0;
};

ContactJudge::ContactJudge(const mjModel* m, const std::string& object_body,
                           const std::string& support_body, double inflation)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.inflation = inflation;
  s.object = mj_name2id(m, mjOBJ_BODY, object_body.c_str());
  if (s.object < 0) throw std::invalid_argument("ContactJudge: no body " + object_body);
  // The support's own geoms are neither hand nor object (contact_judge.h).
  int support = -1;
  if (!support_body.empty()) {
    support = mj_name2id(m, mjOBJ_BODY, support_body.c_str());
    if (support < 0) throw std::invalid_argument("ContactJudge: no body " + support_body);
    for (int b = support; b > 0; b = m->body_parentid[b]) {
      if (b == s.object) {
        throw std::invalid_argument("ContactJudge: the support " + support_body +
                                    " is the object or inside it");
      }
    }
  }
  s.in_object.assign(static_cast<std::size_t>(m->ngeom), 0);
  s.hand_index.assign(static_cast<std::size_t>(m->ngeom), -1);
  for (int g = 0; g < m->ngeom; ++g) {
    const int body = m->geom_bodyid[g];
    bool inside = false;
    for (int b = body; b > 0; b = m->body_parentid[b]) inside = inside || b == s.object;
    s.in_object[static_cast<std::size_t>(g)] = inside;
    if (inside) {
      if (m->geom_type[g] == mjGEOM_MESH && !grasp::is_piece(m, g)) {
        s.truth.push_back(judged(m, g));
      }
    } else if (m->geom_type[g] != mjGEOM_MESH && !mujoco::is_primitive(m->geom_type[g])) {
      continue;  // a plane or a height field
    } else if (body != 0 && body != support &&
               (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0)) {
      s.hand_index[static_cast<std::size_t>(g)] = static_cast<int>(s.hand.size());
      s.hand.push_back(judged(m, g));
    }
  }
  if (s.truth.empty()) throw std::invalid_argument("ContactJudge: the object has no mesh geom");
}

ContactJudge::~ContactJudge() = default;

void ContactJudge::judge_step(const mjModel* m, const mjData* d, int step) {
  judge_step(m, d, step, d->contact, d->ncon);
}

void ContactJudge::judge_step(const mjModel* /*m*/, const mjData* d, int step,
                              const mjContact* contacts, int n) {
  Impl& s = *impl_;
  ++s.summary.steps;
  std::vector<char> touched(s.hand.size(), 0);
  // Every hand-object contact: its point against both true surfaces.
  for (int c = 0; c < n; ++c) {
    const mjContact& con = contacts[c];
    int hand_geom = -1;
    if (s.in_object[static_cast<std::size_t>(con.geom1)]) hand_geom = con.geom2;
    if (s.in_object[static_cast<std::size_t>(con.geom2)]) hand_geom = con.geom1;
    if (hand_geom < 0 || s.in_object[static_cast<std::size_t>(hand_geom)]) continue;
    const int h = s.hand_index[static_cast<std::size_t>(hand_geom)];
    if (h < 0) continue;
    touched[static_cast<std::size_t>(h)] = 1;
    ++s.summary.contacts;
    const double to_hand =
        s.hand[static_cast<std::size_t>(h)].surface->distance(in_geom_frame(d, hand_geom, con.pos));
    double to_object = INFINITY;
    for (const JudgedGeom& t : s.truth) {
      to_object = std::min(to_object, t.surface->distance(in_geom_frame(d, t.id, con.pos)));
    }
    if (to_hand > kPhantomDistance || to_object > kPhantomDistance + s.inflation) {
      ++s.summary.phantom;
      ++s.summary.phantom_by_geom[s.hand[static_cast<std::size_t>(h)].name];
    }
  }
  // Every hand geom against the true object: CGAL's verdict, and the contacts the
  // configuration missed.
  for (std::size_t h = 0; h < s.hand.size(); ++h) {
    bool meets = false;
    for (const JudgedGeom& t : s.truth) {
      const Pose pose = mujoco::relative_pose(d, s.hand[h].id, t.id);
      meets =
          meets ||
          !exact::mesh_mesh_pairs(s.hand[h].triangles, posed_triangles(t.mesh, pose), true).empty();
    }
    if (!meets) continue;
    ++s.summary.truth_hits;
    s.summary.cgal_first_contact.emplace(s.hand[h].name, step);
    s.summary.cgal_first_contact_body.emplace(s.hand[h].body, step);
    if (!touched[h]) {
      ++s.summary.missed;
      ++s.summary.missed_by_geom[s.hand[h].name];
    }
  }
}

const ContactJudgeSummary& ContactJudge::summary() const { return impl_->summary; }

nlohmann::json contact_judge_json(const ContactJudgeSummary& j, double inflation) {
  const double steps = j.steps > 0 ? j.steps : 1;
  return {{"steps", j.steps},
          {"contacts", j.contacts},
          {"phantom", j.phantom},
          {"missed", j.missed},
          {"phantom_by_geom", j.phantom_by_geom},
          {"missed_by_geom", j.missed_by_geom},
          {"truth_hits", j.truth_hits},
          {"contact_error_per_step", static_cast<double>(j.phantom + j.missed) / steps},
          {"cgal_first_contact", j.cgal_first_contact},
          {"cgal_first_contact_body", j.cgal_first_contact_body},
          {"phantom_distance", kPhantomDistance + inflation}};
}

}  // namespace graspcd::study
