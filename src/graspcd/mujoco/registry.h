// The pair registry of one mjModel at run time (docs/design.md, "The MuJoCo layer"): the
// served geom pairs of a pair config (pair_config.h) resolved against the model, how each is
// served, the geoms' trees (geom_trees.h), the state each pair carries from step to step on each
// mjData, the statistics and the construction's warnings. Attaching a registry to its model is
// collision_table.h's (attach returns the handle that detaches it).
//
// A pair is served by one of two paths (PairPath; collision_served.h): two boxes by the
// detector's box test and MuJoCo's own box-box contacts, every other pair by the tree query of
// the two geoms' OBB trees (geom_trees.h) and a contact manifold of its intersecting triangle
// pairs (contact.h). Planes and height fields are not served (MuJoCo keeps them).
//
// What a served pair carries from call to call lives in one DataPairState per (mjData, pair);
// what is kept per pair (ServedPair) and per model (the trees, the config) is immutable after
// construction.
//
// Errors of the construction, each a std::runtime_error with a one-line message that starts with
// the config's name: a pattern that matches no collidable geom, a matched collidable geom of a
// type that is not served (naming the pattern, the geom and its type), a pair with no geom pair
// left, a model with a non-finite number (model_check.h). The config's own errors:
// pair_config.h.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "graspcd/core/contact.h"
#include "graspcd/core/separators.h"
#include "graspcd/mujoco/geom_trees.h"
#include "graspcd/mujoco/pair_config.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::mujoco {

// Work and output of the served pairs, summed over callback calls until reset_stats().
struct BridgeStats {
  std::uint64_t calls = 0;          // served pair calls (after MuJoCo's bounding-sphere test)
  std::uint64_t box_box_calls = 0;  // of those, calls served by the exact box-box path
  std::uint64_t detection_ns = 0;   // tree query or box test time (steady clock), summed
  std::uint64_t contact_ns = 0;     // contact generation and reduction time, summed (for box-box
                                    // pairs: MuJoCo's box-box function)
  QueryCounters counters;           // box tests, triangle tests, intersecting triangle pairs
  std::uint64_t contacts = 0;       // contacts handed to MuJoCo
  std::uint64_t capped_pairs = 0;   // tree-path calls with more candidates (one per
                                    // intersecting triangle pair) than the pair's max_contacts
  std::uint64_t candidates = 0;     // those candidates, summed (contacts before the manifold)
  std::uint64_t patches = 0;        // contact patches of the tree-path calls, summed
  // The separate containment check (docs/design.md "Semantics"): tree-path calls whose surfaces did
  // not intersect but one geom lay wholly inside the other's closed solid (core/containment.h),
  // and the time that check took (not part of detection_ns).
  std::uint64_t contained = 0;
  std::uint64_t containment_ns = 0;
  // Served calls skipped because MuJoCo's state held a non-finite number (NaN or +-inf, or beyond
  // mjMAXVAL = 1e10 as mju_isBad says) in the pair's geom_xpos or geom_xmat: the pair gets 0
  // contacts and no tree query runs on a NaN pose (collision.h). MuJoCo's own checks (mj_checkPos
  // and friends, run by mj_step) reset a state with bad qpos, qvel or qacc, so this counts what
  // gets past them: e.g. mj_forward on a bad qpos, or a caller writing into mjData.
  std::uint64_t nonfinite_skips = 0;
  // Tree queries restarted from the pair's front on its mjData (RegistryConfig::front_list).
  std::uint64_t front_restarts = 0;
  // Tree-path calls answered by the pair's reused contacts, without a query
  // (RegistryConfig::contact_reuse).
  std::uint64_t reused = 0;
};

// How a served pair is answered (see the top of this file).
enum class PairPath {
  kTrees,   // tree query on meshes and tessellated primitives, contacts from triangles
  kBoxBox,  // two boxes: the detector's box test, then MuJoCo's box-box contacts
};

// A served geom pair, immutable after the registry's construction (its state from step to step is
// a DataPairState per mjData, Registry::pair_state).
struct ServedPair {
  int geom_lo = 0;  // smaller geom id
  int geom_hi = 0;  // larger geom id
  PairPath path = PairPath::kTrees;
  ManifoldOptions manifold;  // the pair's contact budget (RegistryConfig, PairPattern)
};

// The registry of one model. Build it after mj_loadXML (e.g. Registry r(m,
// load_registry_config(path), path); Attachment a = attach(r); see collision.h), keep it alive
// while the model steps with it attached, and destroy it (after its Attachment) before the model.
// Not thread-safe: one thread steps a model at a time (the pair states and statistics mutate).
class Registry {
 public:
  // Resolves patterns and geom pairs against `m`, builds the trees. `source` names the config in
  // messages (e.g. its file name, or "<program>"), as `names` has it for a scene graspcd wrote
  // (scene_names.h: the template's config, the hand's meshes). Throws std::runtime_error for the
  // errors listed at the top of this file (a pattern that matches nothing, an unserved geom type,
  // ...), std::invalid_argument for detector options out of range (core/separators.h).
  Registry(const mjModel* m, const RegistryConfig& config, const std::string& source = "<program>",
           const SceneNames& names = {});
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  const mjModel* model() const { return model_; }
  const RegistryConfig& config() const { return config_; }

  // Index into pairs() of the unordered pair (g1, g2), or -1 when not served.
  int find_pair(int g1, int g2) const {
    const auto it = pair_index_.find(key(g1, g2));
    return it == pair_index_.end() ? -1 : it->second;
  }
  const std::vector<ServedPair>& pairs() const { return pairs_; }
  const ServedPair& pair(int index) const { return pairs_[static_cast<std::size_t>(index)]; }

  // The tree of a mesh id (in the mesh frame, which is the geom frame), or nullptr when the mesh
  // is in no pair served by trees.
  const MeshTree* tree(int mesh_id) const { return trees_.mesh_tree(mesh_id); }
  // The tree of a geom (its mesh's, or its primitive shape's, in the geom frame), or nullptr when
  // the geom is in no pair served by trees. O(1): what each collision call uses.
  const MeshTree* geom_tree(int geom) const { return trees_.geom_tree(geom); }
  // Every tree built: one per mesh plus one per primitive (type, size).
  std::size_t tree_count() const { return trees_.tree_count(); }
  std::size_t primitive_tree_count() const { return trees_.primitive_tree_count(); }

  // Non-fatal findings of the construction, one line each, starting with the config's name: a
  // served geom with a non-zero margin (served pairs report intersecting surfaces only); a mesh
  // of a pair served by trees that is not closed (no containment check inside it: "mesh N 'name'
  // is not closed: ..."); a mesh with zero-area faces, which its tree leaves out ("mesh N 'name':
  // dropped K zero-area faces ..."). Each is also added to the process's sink (io/warnings.h).
  const std::vector<std::string>& warnings() const { return warnings_; }

  BridgeStats& stats() { return stats_; }
  const BridgeStats& stats() const { return stats_; }
  void reset_stats() { stats_ = BridgeStats{}; }
  // The statistics since the last reset, then a reset: once per physics step or grasp step.
  BridgeStats take_stats() {
    const BridgeStats s = stats_;
    stats_ = BridgeStats{};
    return s;
  }

  // What a served pair carries from call to call on one mjData, the only state that changes while
  // the model steps: kept per (mjData, pair) so that two mjData stepping the same model (the
  // study's threads, a planner's rollouts) never follow each other's detectors, fronts or kept
  // contacts.
  struct DataPairState {
    explicit DataPairState(Detector fresh) : detector(std::move(fresh)) {}
    // The box separator with its state (warm planes, cached axes, switches), core/separators.h.
    Detector detector;
    // The tree query's front (RegistryConfig::front_list, core/tree_query.h).
    QueryFront front;
    // The contacts kept for reuse (RegistryConfig::contact_reuse, contact.h).
    ReusedContacts reused;
    // After the pair's last call: the surfaces did not intersect and one geom lay wholly inside
    // the other's closed solid (the containment check; the pair then gets no contacts).
    bool contained = false;
  };
  // The state of a pair on `d`, created fresh on first use (one lookup per served call). At most
  // kMaxFrontData mjData are remembered: past that, every state is forgotten (a speed matter
  // only: any state, even one left by a freed mjData whose address was reused, gives the same
  // contacts).
  DataPairState& pair_state(const mjData* d, int pair_index);
  // The state of a pair on `d`, or nullptr when `d` has none yet.
  const DataPairState* find_pair_state(const mjData* d, int pair_index) const;
  // The query front of a tree-path pair on one mjData (pair_state(d, pair_index).front).
  QueryFront& front(const mjData* d, int pair_index) { return pair_state(d, pair_index).front; }
  // Forgets every pair's state on `d` (e.g. before mj_deleteData; not needed for correctness:
  // every answer depends on the pose alone).
  void forget_fronts(const mjData* d);
  // Forgets every pair's state on every mjData: detectors, fronts, reused contacts.
  void reset_detectors();
  // A copy of every pair's state on `d` (empty when `d` has none yet), and its restore onto `d`,
  // replacing what `d` has (an empty copy: `d` starts afresh): runs that branch from one state
  // (the grasp's six-direction test) each start with the same detectors, fronts and reused
  // contacts, so that each branch's contacts are those of the others'.
  using PairStates = std::vector<DataPairState>;
  PairStates snapshot(const mjData* d) const;
  void restore(const mjData* d, const PairStates& states);
  static constexpr std::size_t kMaxFrontData = 64;

  // The mesh's faces in the mesh frame (geom_trees.h, mesh_triangles): for tests and the exact
  // check.
  static std::vector<Triangle> mesh_triangles(const mjModel* m, int mesh_id) {
    return graspcd::mujoco::mesh_triangles(m, mesh_id);
  }

 private:
  static std::uint64_t key(int g1, int g2) {
    const auto lo = static_cast<std::uint32_t>(g1 < g2 ? g1 : g2);
    const auto hi = static_cast<std::uint32_t>(g1 < g2 ? g2 : g1);
    return (static_cast<std::uint64_t>(lo) << 32) | hi;
  }
  // The construction's steps, in order.
  void check_model(const std::string& source) const;
  void add_pattern_pairs(const std::string& source);
  void add_geom_pairs(const std::string& source);
  void warn_served_margins(const std::string& source);
  void choose_paths_and_build_trees(const std::string& source, const SceneNames& names);
  void warn_open_meshes(const std::string& source, const SceneNames& names);
  void add_pair(int g1, int g2, const ManifoldOptions& manifold);
  Detector make_detector() const { return Detector(config_.method, config_.detector); }
  // Adds a warning to warnings_ and to the process's sink under `code`.
  void warn(const std::string& code, const std::string& message);

  const mjModel* model_;
  RegistryConfig config_;
  std::vector<ServedPair> pairs_;
  std::unordered_map<std::uint64_t, int> pair_index_;
  GeomTrees trees_;
  BridgeStats stats_;
  std::vector<std::string> warnings_;
  // Every pair's state on every mjData: by mjData, then by pair index.
  std::unordered_map<const mjData*, std::vector<DataPairState>> states_;
};

}  // namespace graspcd::mujoco
