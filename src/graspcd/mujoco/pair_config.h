// The pair config of a scene: which geom pairs graspcd serves and the detector options
// (docs/design.md, "The MuJoCo layer"). Parsed here; resolved against a model by the registry
// (registry.h), whose geom selection and trees are geom_trees.h.
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
//     "reduction": "support", // how a patch's points are chosen: "support" (the support polygon,
//                             // the default), "moment" (its net normal force and moment about
//                             // the centre of pressure kept: an anchor point and support
//                             // extremes, contact.h, build_contact_manifold) or "force" (the
//                             // support points of 8 per pair reduced to "max_contacts" with the
//                             // same summed depth and centre of pressure per patch)
//     "front_list": true,      // restart each tree query from the last step's front (speed only)
//     "contact_reuse": 2e-5,   // metres in [0, 0.001]: reuse a pair's contacts while it moves
//                              // less (contact.h, ReusedContacts); 0: exact contacts every step
//     "pairs": [ {"a": "finger*", "b": "body:object"} , ... ],
//     "grasp": { ... }         // how the grasp experiment drives a hand (graspcd/grasp/
//                              // drive_config.h); accepted unread here
//   }
// A pair entry may carry its own "max_contacts" and "max_patch_contacts", which override the
// top-level ones for the geom pairs it registers (the first entry to register a pair decides).
// A pattern is a glob where '*' matches any run of characters (possibly empty) and every other
// character matches itself. "geom:GLOB" matches geom names, "body:GLOB" the name of the geom's
// body, and a bare "GLOB" either (geom_trees.h, match_geoms). Each pair entry registers every
// (geom of a, geom of b) pair of distinct geoms; duplicates and both orders collapse into one
// unordered pair. Geoms with contype == conaffinity == 0 (visual only) are skipped silently.
//
// Errors of the parser, each a std::runtime_error with a one-line message that starts with the
// config's name: bad JSON, a key given twice in one object, an unknown field or method, a value out
// of range, an empty "pairs" (a config that serves nothing).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/contact.h"
#include "graspcd/core/separators.h"
#include "graspcd/mujoco/scene_names.h"

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
  // Contacts reused across steps (contact.h, ReusedContacts): while no point of geom2 that can
  // touch geom1 moved more than this (metres) relative to geom1, and the larger geom's rim turned
  // no more, since the pair's last exact query on the same mjData, its contacts are refreshed
  // instead of queried (their depths along their normals; a region that begins or ends to touch
  // within this drift is seen at the next exact query). Why 20 um by default: docs/design.md, "The
  // MuJoCo layer"; 0: every step's contacts from an exact query. At most kMaxContactReuse.
  static constexpr double kDefaultContactReuse = 2e-5;
  double contact_reuse = kDefaultContactReuse;
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
// Reads and parses a config file. Throws std::runtime_error naming the file (as `names` has it,
// for a copy graspcd wrote) when it cannot be read or does not parse.
RegistryConfig load_registry_config(const std::string& path, const SceneNames& names = {});

}  // namespace graspcd::mujoco
