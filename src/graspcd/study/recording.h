// The study's grasp recordings and the pairs it replays them on ("record each grasp once,
// then replay its poses for each method").
//
// A Recording is one run of the grasp of paper section 9 (grasp/grasp.h) with the poses of every
// geom after each closing grasp step (docs/design.md "Semantics": detection is measured per grasp
// step). A MeshScene resolves a triangle scene's served pairs (its SCENE.pairs.json, through the
// MuJoCo layer's registry) and builds the trees the replay uses; a BoxScene lists the box pairs of
// the parallelepiped hand (Figures 13-15): segments B and C against every object box.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "graspcd/core/obb_tree.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::study {

// A contact of mjData after a grasp step (the viewer's and the figures' data, trajectory.h).
struct RecordedContact {
  int geom1 = 0;
  int geom2 = 0;
  std::array<double, 3> pos{};
  std::array<double, 3> normal{};  // from geom1 toward geom2 (frame[0..2])
  double dist = 0;                 // negative when penetrating
};

struct Recording {
  std::string name;   // e.g. "example1"
  std::string scene;  // the MJCF path
  bool native = false;
  int ngeom = 0;
  // Per closing grasp step: d->geom_xpos (3 ngeom) and d->geom_xmat (9 ngeom) after its last
  // physics step.
  std::vector<std::vector<double>> xpos;
  std::vector<std::vector<double>> xmat;
  // Per closing grasp step: d->qpos and d->contact after its last physics step (not hashed).
  std::vector<std::vector<double>> qpos;
  std::vector<std::vector<RecordedContact>> contacts;
  grasp::GraspResult grasp;
  std::uint64_t pose_hash = 0;  // FNV-1a over the bits of every recorded pose

  int steps() const { return static_cast<int>(xpos.size()); }
};

// The contacts of `d` (d->contact[0 .. ncon)).
std::vector<RecordedContact> recorded_contacts(const mjData* d);

// Runs the grasp on `scene` (served by graspcd with the scene's pair config, or MuJoCo's native
// collision) and records the poses of every closing grasp step.
Recording record_grasp(const std::string& name, const std::string& scene, bool native,
                       int max_steps);

// FNV-1a, 64 bit (Fowler, Noll, Vo): the study's answer and pose hashes.
class Fnv1a {
 public:
  void add_bytes(const void* data, std::size_t n);
  template <class T>
  void add(const T& value) {
    add_bytes(&value, sizeof(T));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

std::string hex64(std::uint64_t v);

// One served mesh pair of a triangle scene: geom1 is the geom whose frame the query works in.
struct MeshPair {
  int geom1 = 0;
  int geom2 = 0;
  int mesh1 = 0;
  int mesh2 = 0;
  int segment = -1;  // index into grasp::finger_segment_names() of the finger geom, -1 none
};

class MeshScene {
 public:
  // Loads the scene and resolves its pairs from SCENE.pairs.json. Trees are built with
  // `tree_options` for every mesh of a pair.
  MeshScene(const std::string& scene, const ObbTreeOptions& tree_options = {});

  const std::vector<MeshPair>& pairs() const { return pairs_; }
  const ObbTree& tree(int mesh) const { return trees_.at(mesh); }
  // The mesh's faces in face order, as the trees hold them (the exact judge's input).
  const std::vector<Triangle>& faces(int mesh) const { return faces_.at(mesh); }
  const std::vector<int>& meshes() const { return mesh_ids_; }
  const mjModel* model() const { return model_.get(); }
  std::size_t face_count() const;

  // geom2 in geom1's frame at a recorded step (mujoco::relative_pose on the recorded state).
  Pose pose(const Recording& r, int step, const MeshPair& pair) const;

  // Replaces every tree by `make(tree)` (e.g. ObbTree::rounded_to_float).
  template <class Make>
  void transform_trees(Make make) {
    for (auto& [mesh, t] : trees_) t = make(t);
  }

 private:
  mujoco::ModelPtr model_;
  mujoco::DataPtr data_;
  std::vector<MeshPair> pairs_;
  std::vector<int> mesh_ids_;
  std::map<int, ObbTree> trees_;
  std::map<int, std::vector<Triangle>> faces_;
};

// One box pair of the parallelepiped hand: a finger segment box against an object box.
struct BoxPair {
  int geom1 = 0;  // the segment's box
  int geom2 = 0;  // the object's box
  int segment = 0;
  char kind = 'B';  // the segment: 'A', 'B' or 'C'
  Obb box1;         // in geom1's frame: centre 0, axes I, half-extents geom_size
  Vec3 half2 = Vec3::Zero();
};

class BoxScene {
 public:
  // Every box geom of the object against the box geoms of the segments whose letter is in
  // `kinds` (e.g. "BC").
  BoxScene(const std::string& scene, const std::string& kinds);
  const std::vector<BoxPair>& pairs() const { return pairs_; }
  // geom2's box in geom1's frame at a recorded step.
  Obb box2(const Recording& r, int step, const BoxPair& pair) const;

 private:
  mujoco::ModelPtr model_;
  mujoco::DataPtr data_;
  std::vector<BoxPair> pairs_;
};

}  // namespace graspcd::study
