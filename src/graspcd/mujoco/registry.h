// The pair registry of one mjModel: which geom pairs graspcd serves, the detector options, how
// each pair is served, and one OBB tree per mesh and per primitive shape that appears in a pair
// served by trees (docs/design.md, "The seam with MuJoCo").
//
// Config (JSON, nlohmann-json), every field optional except "pairs":
//   {
//     "method": "sat",         // any name of parse_method (core/separators.h); default "sat"
//     "cap": 1500,             // perceptron pass cap (>= 1)
//     "switch": 300,           // Neuro-SAT switch (>= 1)
//     "cache_slots": 4096,     // per-pair temporal-coherence cache slots (>= 1)
//     "max_depth": 0.01,       // contact penetration cap in metres (> 0), see contact.h
//     "max_contacts": 8,       // contacts handed to MuJoCo per geom pair (1 .. mjMAXCONPAIR = 50)
//     "max_patch_contacts": 4, // contacts per contact patch (1 .. 50), see contact.h, "manifold"
//     "front_list": true,      // restart each tree query from the last step's front (speed only)
//     "contact_reuse": 0,      // metres in [0, 0.001]: reuse a pair's contacts while it moves
//                              // less (contact.h, ReusedContacts); 0: exact contacts every step
//     "pairs": [ {"a": "finger*", "b": "body:object"} , ... ]
//   }
// A pair entry may carry its own "max_contacts" and "max_patch_contacts", which override the
// top-level ones for the geom pairs it registers (the first entry to register a pair decides).
// A pattern is a glob where '*' matches any run of characters (possibly empty) and every other
// character matches itself. "geom:GLOB" matches geom names, "body:GLOB" the name of the geom's
// body, and a bare "GLOB" either. Each pair entry registers every (geom of a, geom of b) pair of
// distinct geoms; duplicates and both orders collapse into one unordered pair. Geoms with
// contype == conaffinity == 0 (visual only) are skipped silently.
//
// Served geom types: mesh, box, sphere, capsule, cylinder, ellipsoid. A pair is served by one of
// two paths (PairPath):
// - kBoxBox, both geoms boxes: exact and without triangles. The pair's Detector tests the two
//   boxes (geom frame: centre 0, axes identity, half-extents geom_size, geom2 placed in geom1's
//   frame by relative_pose); proven disjoint gives 0 contacts, otherwise MuJoCo's own box-box
//   function (the original entry saved by install(), called with margin 0) makes the contacts.
// - kTrees, every other pair: the tree query of the two geoms' OBB trees and contacts from the
//   intersecting triangle pairs, reduced to a small manifold (contact.h: patches by normal and
//   adjacency, at most max_patch_contacts points each and max_contacts per pair; the full
//   triangle-pair list is what validate and the study check). A mesh's tree is built from MuJoCo's
//   mesh (one per mesh); a primitive's from its tessellation (primitives.h: a box exactly, curved
//   primitives circumscribed, with the documented tolerance), one per (type, size), in the geom
//   frame.
// Planes and height fields are not served (MuJoCo keeps them).
//
// Errors, each a std::runtime_error with a one-line message that starts with the config's name:
// bad JSON, an unknown field or method, a pattern that matches no collidable geom, a matched
// collidable geom of a type that is not served (naming the pattern, the geom and its type), a
// pair with no geom pair left.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "graspcd/core/contact.h"
#include "graspcd/core/containment.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/core/separators.h"
#include "graspcd/mujoco/bridge_namespace.h"

namespace graspcd::mujoco {

struct PairPattern {
  PairPattern() = default;
  // Keeps PairPattern{"a", "b"} (0.1's aggregate form) compiling without warnings.
  PairPattern(std::string a_pattern, std::string b_pattern,
              std::optional<int> max_contacts_override = std::nullopt,
              std::optional<int> max_patch_contacts_override = std::nullopt)
      : a(std::move(a_pattern)),
        b(std::move(b_pattern)),
        max_contacts(max_contacts_override),
        max_patch_contacts(max_patch_contacts_override) {}
  std::string a;
  std::string b;
  // The entry's own contact budget, overriding RegistryConfig::manifold for its pairs.
  std::optional<int> max_contacts;
  std::optional<int> max_patch_contacts;
};

struct RegistryConfig {
  Method method = Method::kSat;
  DetectorOptions detector{tol::kPerceptronDefaultCap, tol::kNeuroSatDefaultSwitch, 1u << 12};
  // Penetration depths reported to MuJoCo are clipped to this (metres): a triangle pair far
  // inside the other geom says little about the local penetration, and MuJoCo's soft contacts keep
  // true penetrations at millimetres.
  double max_depth = tol::kContactMaxDepth;
  // The contact manifold of every served pair (contact.h): points per patch and per pair, at most
  // mjMAXCONPAIR each.
  ManifoldOptions manifold;
  // Temporal coherence of the tree path: each query restarts from where the same pair's query on
  // the same mjData stopped last time, when the pair moved little (core/tree_query.h,
  // collide_coherent). The contacts are the same either way; false: every query from the roots.
  bool front_list = true;
  // Contacts reused across steps (contact.h, ReusedContacts), opt-in: while no point of geom2
  // that can touch geom1 moved more than this (metres) relative to geom1, and the larger geom's
  // rim turned no more, since the pair's last exact query on the same mjData, its contacts are
  // refreshed instead of queried (their depths along their normals; a region that begins or ends
  // to touch within this drift is seen at the next exact query). 0 (the default): every step's
  // contacts come from an exact query. At most kMaxContactReuse.
  double contact_reuse = 0;
  static constexpr double kMaxContactReuse = 0.001;
  std::vector<PairPattern> patterns;
  // Geom id pairs registered directly (programmatic use), in addition to the patterns.
  std::vector<std::pair<int, int>> geom_pairs;
};

// Parses the JSON text of a config; `source` (a file name) starts every error message. Throws
// std::runtime_error for bad JSON, an unknown field or method, or a value out of range.
RegistryConfig parse_registry_config(const std::string& json_text, const std::string& source);
// The pair config of a scene when none is named: SCENE.pairs.json beside SCENE.xml (the scene's
// extension, if any, replaced).
std::string pair_config_path(const std::string& scene_path);
// Reads and parses a config file. Throws std::runtime_error naming the file when it cannot be read
// or does not parse.
RegistryConfig load_registry_config(const std::string& path);

// True when `name` matches the glob `pattern` ('*' only).
bool glob_match(const std::string& pattern, const std::string& name);
// The collidable geoms (contype or conaffinity non-zero) that a pattern of the config selects
// ("geom:GLOB", "body:GLOB" or "GLOB"), in id order; empty when none.
std::vector<int> match_geoms(const mjModel* m, const std::string& pattern);

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

// The tree of one mesh (or of one primitive's tessellation) and, for each face id, the face's slot
// in the tree's leaf-ordered triangles. Also the sharp-edge masks of the faces (contact.h), by
// face id.
// Face ids are the tree's: a mesh's zero-area faces are dropped before the build (core/
// mesh_hygiene.h), and source_face maps each tree face id to MuJoCo's face id in the mesh.
struct MeshTree {
  ObbTree tree;
  Closedness closedness;  // of the tree's triangles: containment is decided for closed ones only
  std::vector<std::int32_t> source_face;  // tree face id -> MuJoCo face id (mesh trees)
  std::vector<std::int32_t> slot_of_face;
  std::vector<std::uint8_t> sharp_masks;
  std::vector<FaceVertexIds> vertex_ids;  // per face: its welded vertices (the manifold's patches)
  double radius = 0;  // the largest distance of a vertex from the geom frame's origin
  std::uint8_t sharp(std::int32_t f) const { return sharp_masks[static_cast<std::size_t>(f)]; }
  const FaceVertexIds& vertices(std::int32_t f) const {
    return vertex_ids[static_cast<std::size_t>(f)];
  }
  const Triangle& face(std::int32_t f) const {
    return tree.triangles()[static_cast<std::size_t>(slot_of_face[static_cast<std::size_t>(f)])];
  }
};

// How a served pair is answered (see the config doc above).
enum class PairPath {
  kTrees,   // tree query on meshes and tessellated primitives, contacts from triangles
  kBoxBox,  // two boxes: the detector's box test, then MuJoCo's box-box contacts
};

// A served geom pair: its detector carries the method's state from step to step.
struct ServedPair {
  int geom_lo = 0;  // smaller geom id
  int geom_hi = 0;  // larger geom id
  PairPath path = PairPath::kTrees;
  std::unique_ptr<Detector> detector;
  ManifoldOptions manifold;  // the pair's contact budget (RegistryConfig, PairPattern)
  // After the pair's last call: the surfaces did not intersect and one geom lay wholly inside the
  // other's closed solid (the containment check; the pair then gets no contacts).
  bool contained = false;
};

// The registry of one model. Build it after mj_loadXML (e.g. Registry r(m,
// load_registry_config(path), path); attach(r); see collision.h), keep it alive while the model
// steps with the bridge attached, and destroy it before the model (it detaches itself).
// Not thread-safe: one thread steps a model at a time (the detectors and statistics mutate).
class Registry {
 public:
  // Resolves patterns and geom pairs against `m`, builds the trees. `source` names the config in
  // error messages (e.g. its file name, or "<program>"). Throws std::runtime_error for the errors
  // listed at the top of this file (a pattern that matches nothing, an unserved geom type, ...).
  Registry(const mjModel* m, const RegistryConfig& config, const std::string& source = "<program>");
  ~Registry();
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
  ServedPair& pair(int index) { return pairs_[static_cast<std::size_t>(index)]; }

  // The tree of a mesh id (in the mesh frame, which is the geom frame), or nullptr when the mesh
  // is in no pair served by trees.
  const MeshTree* tree(int mesh_id) const {
    const auto it = trees_.find(mesh_id);
    return it == trees_.end() ? nullptr : &it->second;
  }
  // The tree of a geom (its mesh's, or its primitive shape's, in the geom frame), or nullptr when
  // the geom is in no pair served by trees. O(1): what each collision call uses.
  const MeshTree* geom_tree(int geom) const {
    return geom >= 0 && static_cast<std::size_t>(geom) < geom_trees_.size()
               ? geom_trees_[static_cast<std::size_t>(geom)]
               : nullptr;
  }
  // Every tree built: one per mesh plus one per primitive (type, size).
  std::size_t tree_count() const { return trees_.size() + primitive_trees_.size(); }
  std::size_t primitive_tree_count() const { return primitive_trees_.size(); }

  // Non-fatal findings of the construction, one line each, starting with the config's name: a
  // served geom with a non-zero margin (served pairs report intersecting surfaces only,
  // docs/design.md "The seam with MuJoCo"); a mesh of a pair served by trees that is not closed
  // (core/containment.h: "mesh N 'name' is not closed: ...; containment inside it is not checked
  // (surface contacts only)"), since the containment check needs a closed solid: its pairs get
  // their surface contacts, and containment is decided only inside the pair's other geom, if
  // closed (closedness welds MuJoCo's per-face vertices by position); a mesh with zero-area
  // faces, which its tree leaves out ("mesh N 'name': dropped K zero-area faces (MuJoCo faces
  // ...)"; MeshTree::source_face maps the rest).
  // Each is also added to the process's sink (graspcd/core/warnings.h), which the command line
  // prints and the JSON envelope carries.
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
  // Forgets every detector's cached state (warm planes, cached axes, switches), every front and
  // every pair's reused contacts.
  void reset_detectors();
  // The query front of a tree-path pair on one mjData (RegistryConfig::front_list): the state of
  // the tree query's temporal coherence is kept per (mjData, pair), so that two mjData stepping
  // the same model (the study's threads, a planner's rollouts) never follow each other's fronts.
  // Created empty on first use; at most kMaxFrontData mjData are remembered.
  QueryFront& front(const mjData* d, int pair_index) { return pair_state(d, pair_index).front; }
  // What a tree-path pair carries from step to step on one mjData: its front, and the contacts it
  // keeps (RegistryConfig::contact_reuse), forgotten with the front. One lookup for both.
  struct DataPairState {
    QueryFront front;
    ReusedContacts reused;
  };
  DataPairState& pair_state(const mjData* d, int pair_index);
  // Forgets the fronts and reused contacts of `d` (e.g. before mj_deleteData; not needed for
  // correctness: both depend on the pose alone).
  void forget_fronts(const mjData* d);
  static constexpr std::size_t kMaxFrontData = 64;

  // The mesh's faces in the mesh frame, as doubles converted from MuJoCo's floats (what the tree
  // holds, in face order): for tests and the exact check.
  static std::vector<Triangle> mesh_triangles(const mjModel* m, int mesh_id);

 private:
  static std::uint64_t key(int g1, int g2) {
    const auto lo = static_cast<std::uint32_t>(g1 < g2 ? g1 : g2);
    const auto hi = static_cast<std::uint32_t>(g1 < g2 ? g2 : g1);
    return (static_cast<std::uint64_t>(lo) << 32) | hi;
  }
  void add_pair(int g1, int g2, const ManifoldOptions& manifold);

  const mjModel* model_;
  RegistryConfig config_;
  std::vector<ServedPair> pairs_;
  std::unordered_map<std::uint64_t, int> pair_index_;
  std::unordered_map<int, MeshTree> trees_;  // by mesh id
  // By (geom type, size[0..2]) with the sizes the type does not use set to 0. std::map: stable
  // element addresses, which geom_trees_ holds.
  std::map<std::array<double, 4>, MeshTree> primitive_trees_;
  std::vector<const MeshTree*> geom_trees_;  // by geom id
  BridgeStats stats_;
  std::unordered_map<const mjData*, std::vector<DataPairState>> states_;
  std::vector<std::string> warnings_;
  // Adds a warning to warnings_ and to the process's sink under `code`.
  void warn(const std::string& code, const std::string& message);
};

}  // namespace graspcd::mujoco
