#include "graspcd/study/recording.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/model_loading.h"

namespace graspcd::study {

void Fnv1a::add_bytes(const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h_ ^= p[i];
    h_ *= 0x100000001b3ull;
  }
}

std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::vector<RecordedContact> recorded_contacts(const mjData* d) {
  std::vector<RecordedContact> out;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    RecordedContact rc;
    rc.geom1 = c.geom1;
    rc.geom2 = c.geom2;
    for (int k = 0; k < 3; ++k) {
      rc.pos[k] = c.pos[k];
      rc.normal[k] = c.frame[k];
    }
    rc.dist = c.dist;
    out.push_back(rc);
  }
  return out;
}

Recording record_grasp(const std::string& name, const std::string& scene, bool native,
                       int max_steps) {
  Recording r;
  r.name = name;
  r.scene = scene;
  r.native = native;
  grasp::GraspOptions options;
  options.native = native;
  options.max_steps = max_steps;
  // The study replays exact queries: its grasps are recorded with exact contacts every step.
  options.contact_reuse = 0.0;
  options.on_grasp_step = [&r](const mjModel* m, const mjData* d, int) {
    r.ngeom = m->ngeom;
    r.xpos.emplace_back(d->geom_xpos, d->geom_xpos + 3 * m->ngeom);
    r.xmat.emplace_back(d->geom_xmat, d->geom_xmat + 9 * m->ngeom);
    r.qpos.emplace_back(d->qpos, d->qpos + m->nq);
    r.contacts.push_back(recorded_contacts(d));
  };
  r.grasp = grasp::run_grasp(scene, options);
  Fnv1a h;
  for (std::size_t s = 0; s < r.xpos.size(); ++s) {
    h.add_bytes(r.xpos[s].data(), r.xpos[s].size() * sizeof(double));
    h.add_bytes(r.xmat[s].data(), r.xmat[s].size() * sizeof(double));
  }
  r.pose_hash = h.value();
  return r;
}

namespace {

int segment_of(const mjModel* m, int geom) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, geom);
  if (!name) return -1;
  const auto& names = grasp::finger_segment_names();
  for (std::size_t s = 0; s < names.size(); ++s) {
    if (names[s] == name) return static_cast<int>(s);
  }
  return -1;
}

// Puts the recorded geom poses of `step` into `d` (geom_xpos, geom_xmat only).
void restore(const Recording& r, int step, const mjModel* m, mjData* d) {
  if (r.ngeom != m->ngeom) {
    throw std::runtime_error(r.scene + ": the recording has " + std::to_string(r.ngeom) +
                             " geoms, the scene " + std::to_string(m->ngeom));
  }
  const auto s = static_cast<std::size_t>(step);
  std::memcpy(d->geom_xpos, r.xpos[s].data(), r.xpos[s].size() * sizeof(double));
  std::memcpy(d->geom_xmat, r.xmat[s].data(), r.xmat[s].size() * sizeof(double));
}

}  // namespace

MeshScene::MeshScene(const std::string& scene, const ObbTreeOptions& tree_options)
    : model_(mujoco::load_model(scene)), data_(mj_makeData(model_.get())) {
  const std::string config_path = mujoco::pair_config_path(scene);
  const mujoco::Registry registry(model_.get(), mujoco::load_registry_config(config_path),
                                  config_path);
  const mjModel* m = model_.get();
  std::set<int> meshes;
  for (const mujoco::ServedPair& p : registry.pairs()) {
    MeshPair pair;
    // The finger segment first when there is one: contacts and poses in the finger's frame.
    const bool lo_is_finger = segment_of(m, p.geom_lo) >= 0;
    pair.geom1 = lo_is_finger ? p.geom_lo : p.geom_hi;
    pair.geom2 = lo_is_finger ? p.geom_hi : p.geom_lo;
    pair.segment = segment_of(m, pair.geom1);
    pair.mesh1 = m->geom_dataid[pair.geom1];
    pair.mesh2 = m->geom_dataid[pair.geom2];
    meshes.insert(pair.mesh1);
    meshes.insert(pair.mesh2);
    pairs_.push_back(pair);
  }
  for (int mesh : meshes) {
    mesh_ids_.push_back(mesh);
    faces_[mesh] = mujoco::Registry::mesh_triangles(m, mesh);
    trees_[mesh] = ObbTree::build(faces_[mesh], tree_options);
  }
}

std::size_t MeshScene::face_count() const {
  std::size_t n = 0;
  for (const auto& [mesh, f] : faces_) n += f.size();
  return n;
}

Pose MeshScene::pose(const Recording& r, int step, const MeshPair& pair) const {
  restore(r, step, model_.get(), data_.get());
  return mujoco::relative_pose(data_.get(), pair.geom1, pair.geom2);
}

BoxScene::BoxScene(const std::string& scene, const std::string& kinds)
    : model_(mujoco::load_model(scene)), data_(mj_makeData(model_.get())) {
  const mjModel* m = model_.get();
  const int object = mj_name2id(m, mjOBJ_BODY, "object");
  if (object < 0) throw std::runtime_error(scene + ": no body named object");
  for (int g1 = 0; g1 < m->ngeom; ++g1) {
    const int s = segment_of(m, g1);
    if (s < 0) continue;
    const char kind = static_cast<char>('A' + s % 3);
    if (kinds.find(kind) == std::string::npos) continue;
    if (m->geom_type[g1] != mjGEOM_BOX) {
      throw std::runtime_error(scene + ": segment geom " + mj_id2name(m, mjOBJ_GEOM, g1) +
                               " is not a box");
    }
    for (int g2 = 0; g2 < m->ngeom; ++g2) {
      if (m->body_rootid[m->geom_bodyid[g2]] != object || m->geom_type[g2] != mjGEOM_BOX) continue;
      BoxPair p;
      p.geom1 = g1;
      p.geom2 = g2;
      p.segment = s;
      p.kind = kind;
      p.box1.half = Vec3(m->geom_size[3 * g1], m->geom_size[3 * g1 + 1], m->geom_size[3 * g1 + 2]);
      p.half2 = Vec3(m->geom_size[3 * g2], m->geom_size[3 * g2 + 1], m->geom_size[3 * g2 + 2]);
      pairs_.push_back(p);
    }
  }
  if (pairs_.empty()) throw std::runtime_error(scene + ": no box pairs of segments " + kinds);
}

Obb BoxScene::box2(const Recording& r, int step, const BoxPair& pair) const {
  restore(r, step, model_.get(), data_.get());
  const Pose p = mujoco::relative_pose(data_.get(), pair.geom1, pair.geom2);
  Obb b;
  b.center = p.t;
  b.axes = p.R;
  b.half = pair.half2;
  return b;
}

}  // namespace graspcd::study
