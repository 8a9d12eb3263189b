#include "graspcd/mujoco/registry.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "graspcd/core/contact.h"
#include "graspcd/core/mesh_hygiene.h"
#include "graspcd/core/warnings.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/json_config.h"
#include "graspcd/mujoco/model_check.h"
#include "graspcd/mujoco/primitives.h"

namespace graspcd::mujoco {
namespace {

[[noreturn]] void fail(const std::string& source, const std::string& message) {
  throw std::runtime_error(source + ": " + message);
}

std::string name_of(const mjModel* m, int type, int id) {
  const char* n = mj_id2name(m, type, id);
  return n ? std::string(n) : std::string();
}

bool collidable(const mjModel* m, int g) {
  return m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0;
}

bool served_type(int type) { return type == mjGEOM_MESH || is_primitive(type); }

// "geom 3 'floor' of type plane, which graspcd does not serve (...)": the tail of the error for
// a geom whose type is not served.
std::string unserved_geom(const mjModel* m, int g) {
  const std::string gname = name_of(m, mjOBJ_GEOM, g);
  return "geom " + std::to_string(g) + (gname.empty() ? "" : " '" + gname + "'") + " of type " +
         geom_type_name(m->geom_type[g]) +
         ", which graspcd does not serve (meshes, boxes, spheres, capsules, cylinders and "
         "ellipsoids only; planes and height fields stay with MuJoCo)";
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

// The collidable geoms a pattern selects, checked to be served (see registry.h for the pattern
// grammar).
std::vector<int> resolve(const mjModel* m, const std::string& pattern, const std::string& source) {
  std::vector<int> out = match_geoms(m, pattern);
  for (int g : out) {
    if (!served_type(m->geom_type[g])) {
      fail(source, "pattern '" + pattern + "' matches " + unserved_geom(m, g));
    }
  }
  if (out.empty()) fail(source, "pattern '" + pattern + "' matches no collidable geom");
  return out;
}

// A contact budget of the config: an integer in 1 .. mjMAXCONPAIR (what MuJoCo takes per pair).
int contact_budget(const nlohmann::json& v, const std::string& field, const std::string& source) {
  if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > mjMAXCONPAIR) {
    fail(source, "'" + field + "' must be an integer from 1 to " + std::to_string(mjMAXCONPAIR));
  }
  return v.get<int>();
}

}  // namespace

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
    const bool hit = (by_geom && glob_match(glob, name_of(m, mjOBJ_GEOM, g))) ||
                     (by_body && glob_match(glob, name_of(m, mjOBJ_BODY, m->geom_bodyid[g])));
    if (hit && collidable(m, g)) out.push_back(g);
  }
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

RegistryConfig parse_registry_config(const std::string& json_text, const std::string& source) {
  const nlohmann::json j = parse_json_config(json_text, source);
  if (!j.is_object()) fail(source, "the config must be a JSON object");
  RegistryConfig c;
  const auto positive_int = [&](const char* field) {
    const auto& v = j.at(field);
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > (1ll << 30)) {
      fail(source, std::string("'") + field + "' must be an integer >= 1");
    }
    return v.get<int>();
  };
  for (const auto& [field, value] : j.items()) {
    if (field == "method") {
      if (!value.is_string()) fail(source, "'method' must be a string");
      const auto m = parse_method(value.get<std::string>());
      if (!m) fail(source, "unknown method '" + value.get<std::string>() + "'");
      c.method = *m;
    } else if (field == "cap") {
      c.detector.cap = positive_int("cap");
    } else if (field == "switch") {
      c.detector.switch_passes = positive_int("switch");
    } else if (field == "cache_slots") {
      c.detector.cache_slots = static_cast<std::size_t>(positive_int("cache_slots"));
    } else if (field == "max_depth") {
      if (!value.is_number() || !(value.get<double>() > 0)) {
        fail(source, "'max_depth' must be a number > 0");
      }
      c.max_depth = value.get<double>();
    } else if (field == "max_contacts") {
      c.manifold.max_per_pair = contact_budget(value, "max_contacts", source);
    } else if (field == "max_patch_contacts") {
      c.manifold.max_per_patch = contact_budget(value, "max_patch_contacts", source);
    } else if (field == "front_list") {
      if (!value.is_boolean()) fail(source, "'front_list' must be true or false");
      c.front_list = value.get<bool>();
    } else if (field == "contact_reuse") {
      if (!value.is_number() || !(value.get<double>() >= 0) ||
          !(value.get<double>() <= RegistryConfig::kMaxContactReuse)) {
        fail(source, "'contact_reuse' must be a number of metres in [0, 0.001]");
      }
      c.contact_reuse = value.get<double>();
    } else if (field == "grasp") {
      // How the grasp experiment drives a hand: read by graspcd_grasp (graspcd/grasp/
      // drive_config.h), not by the seam.
    } else if (field == "pairs") {
      if (!value.is_array()) fail(source, "'pairs' must be an array");
      for (const auto& p : value) {
        if (!p.is_object() || !p.contains("a") || !p.contains("b") || !p.at("a").is_string() ||
            !p.at("b").is_string()) {
          fail(source, "each entry of 'pairs' must be {\"a\": \"pattern\", \"b\": \"pattern\"}");
        }
        PairPattern pattern{p.at("a").get<std::string>(), p.at("b").get<std::string>(), {}, {}};
        for (const auto& [key, v] : p.items()) {
          if (key == "max_contacts") {
            pattern.max_contacts = contact_budget(v, "max_contacts", source);
          } else if (key == "max_patch_contacts") {
            pattern.max_patch_contacts = contact_budget(v, "max_patch_contacts", source);
          } else if (key != "a" && key != "b") {
            fail(source, "unknown field '" + key + "' in an entry of 'pairs'");
          }
        }
        c.patterns.push_back(std::move(pattern));
      }
    } else {
      fail(source, "unknown field '" + field + "'");
    }
  }
  if (!j.contains("pairs")) fail(source, "missing field 'pairs'");
  return c;
}

std::string pair_config_path(const std::string& scene_path) {
  std::filesystem::path p(scene_path);
  p.replace_extension(".pairs.json");
  return p.string();
}

RegistryConfig load_registry_config(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the config file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_registry_config(text.str(), path);
}

std::vector<Triangle> Registry::mesh_triangles(const mjModel* m, int mesh_id) {
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

// Resolve every pattern pair and direct geom pair, choose each pair's path, then build one tree per
// mesh and per primitive (type, size) that a pair served by trees uses (docs/design.md: trees once
// per mesh, in the geom frame, shared by the geoms of a mesh; primitives through a tessellated
// mesh, primitives.h).
Registry::Registry(const mjModel* m, const RegistryConfig& config, const std::string& source)
    : model_(m), config_(config) {
  if (!m) fail(source, "no model");
  // A model with a non-finite number (MuJoCo compiles a NaN attribute with a warning) is refused
  // here, at construction, never met inside mj_step (model_check.h).
  const std::string non_finite = find_non_finite(m);
  if (!non_finite.empty()) fail(source, non_finite);
  for (const PairPattern& p : config.patterns) {
    const std::vector<int> as = resolve(m, p.a, source);
    const std::vector<int> bs = resolve(m, p.b, source);
    ManifoldOptions manifold = config.manifold;
    if (p.max_contacts) manifold.max_per_pair = *p.max_contacts;
    if (p.max_patch_contacts) manifold.max_per_patch = *p.max_patch_contacts;
    bool any = false;
    for (int a : as) {
      for (int b : bs) {
        if (a == b) continue;
        any = true;
        add_pair(a, b, manifold);
      }
    }
    if (!any) {
      fail(source, "pair ('" + p.a + "', '" + p.b + "') selects no pair of distinct geoms");
    }
  }
  for (const auto& [a, b] : config.geom_pairs) {
    if (a < 0 || b < 0 || a >= m->ngeom || b >= m->ngeom || a == b) {
      fail(source, "bad geom pair (" + std::to_string(a) + ", " + std::to_string(b) + ")");
    }
    for (int g : {a, b}) {
      if (!served_type(m->geom_type[g])) fail(source, "geom pair member " + unserved_geom(m, g));
    }
    add_pair(a, b, config.manifold);
  }
  // Served geoms with a margin: MuJoCo would expect contacts within it; we report none.
  std::set<int> served;
  for (const ServedPair& p : pairs_) served.insert({p.geom_lo, p.geom_hi});
  for (int g : served) {
    if (m->geom_margin[g] != 0) {
      const std::string gname = name_of(m, mjOBJ_GEOM, g);
      warn("served_geom_margin", source + ": served geom " + std::to_string(g) +
                                     (gname.empty() ? "" : " '" + gname + "'") + " has margin " +
                                     std::to_string(m->geom_margin[g]) +
                                     "; served pairs report intersecting surfaces only (margin 0)");
    }
  }
  // The path of each pair; trees for the geoms of pairs served by trees only: one per mesh, one
  // per primitive (type, size).
  geom_trees_.assign(static_cast<std::size_t>(m->ngeom), nullptr);
  for (ServedPair& p : pairs_) {
    if (m->geom_type[p.geom_lo] == mjGEOM_BOX && m->geom_type[p.geom_hi] == mjGEOM_BOX) {
      p.path = PairPath::kBoxBox;
      continue;
    }
    p.path = PairPath::kTrees;
    for (int g : {p.geom_lo, p.geom_hi}) {
      if (geom_trees_[static_cast<std::size_t>(g)]) continue;
      const MeshTree* built = nullptr;
      if (m->geom_type[g] == mjGEOM_MESH) {
        const int mesh = m->geom_dataid[g];
        auto it = trees_.find(mesh);
        if (it == trees_.end()) {
          // Mesh hygiene: the tree leaves zero-area faces out (core/mesh_hygiene.h).
          HygieneReport hygiene;
          const std::vector<Triangle> tris =
              drop_zero_area_faces(mesh_triangles(m, mesh), &hygiene);
          const std::string mname = name_of(m, mjOBJ_MESH, mesh);
          const std::string what =
              "mesh " + std::to_string(mesh) + (mname.empty() ? "" : " '" + mname + "'");
          if (tris.empty()) fail(source, what + " has no face of non-zero area");
          if (!hygiene.dropped_faces.empty()) {
            std::string ids;
            for (std::size_t i = 0; i < hygiene.dropped_faces.size() && i < 5; ++i) {
              ids += (i ? ", " : "") + std::to_string(hygiene.dropped_faces[i]);
            }
            if (hygiene.dropped_faces.size() > 5) ids += ", ...";
            warn("mesh_zero_area_faces", source + ": " + what + ": dropped " +
                                             std::to_string(hygiene.dropped_faces.size()) +
                                             " zero-area faces (MuJoCo face ids, from 0: " + ids +
                                             "; each spans a segment or a point)");
          }
          MeshTree built_tree = make_tree(tris);
          built_tree.source_face = std::move(hygiene.source_face);
          it = trees_.emplace(mesh, std::move(built_tree)).first;
        }
        built = &it->second;
      } else {
        const std::array<double, 4> k = primitive_key(m, g);
        auto it = primitive_trees_.find(k);
        if (it == primitive_trees_.end()) {
          TriangleMesh shape;
          try {
            shape = tessellate_primitive(m->geom_type[g], m->geom_size + 3 * g);
          } catch (const std::invalid_argument& e) {
            fail(source, "geom " + std::to_string(g) + ": " + e.what());
          }
          std::vector<Triangle> tris;
          for (std::size_t f = 0; f < shape.faces.size(); ++f) tris.push_back(shape.triangle(f));
          it = primitive_trees_.emplace(k, make_tree(tris)).first;
        }
        built = &it->second;
      }
      geom_trees_[static_cast<std::size_t>(g)] = built;
    }
  }
  // Open meshes (core/containment.h): the separate containment check needs a closed solid, so it
  // is skipped inside them; their pairs still get every surface contact. Once per mesh.
  std::set<int> warned;
  for (const ServedPair& p : pairs_) {
    if (p.path != PairPath::kTrees) continue;
    for (int g : {p.geom_lo, p.geom_hi}) {
      const MeshTree* t = geom_trees_[static_cast<std::size_t>(g)];
      if (t->closedness.closed() || m->geom_type[g] != mjGEOM_MESH) continue;
      const int mesh = m->geom_dataid[g];
      if (!warned.insert(mesh).second) continue;
      const std::string mname = name_of(m, mjOBJ_MESH, mesh);
      warn("mesh_open", source + ": mesh " + std::to_string(mesh) +
                            (mname.empty() ? "" : " '" + mname + "'") + " is " +
                            t->closedness.describe() +
                            "; containment inside it is not checked (surface contacts only)");
    }
  }
}

Registry::~Registry() { detach(*this); }

void Registry::add_pair(int g1, int g2, const ManifoldOptions& manifold) {
  const std::uint64_t k = key(g1, g2);
  if (pair_index_.count(k)) return;
  ServedPair p;
  p.geom_lo = g1 < g2 ? g1 : g2;
  p.geom_hi = g1 < g2 ? g2 : g1;
  p.detector = std::make_unique<Detector>(config_.method, config_.detector);
  p.manifold = manifold;
  pair_index_.emplace(k, static_cast<int>(pairs_.size()));
  pairs_.push_back(std::move(p));
}

void Registry::reset_detectors() {
  for (ServedPair& p : pairs_) p.detector->reset();
  states_.clear();
}

Registry::DataPairState& Registry::pair_state(const mjData* d, int pair_index) {
  auto it = states_.find(d);
  if (it == states_.end()) {
    // Bounded: past kMaxFrontData mjData, forget them all (a speed matter only: any front, even
    // one left by a freed mjData whose address was reused, gives the same answers, and kept
    // contacts hold for the pose they were kept at).
    if (states_.size() >= kMaxFrontData) states_.clear();
    it = states_.emplace(d, std::vector<DataPairState>(pairs_.size())).first;
  }
  return it->second[static_cast<std::size_t>(pair_index)];
}

void Registry::forget_fronts(const mjData* d) { states_.erase(d); }

void Registry::warn(const std::string& code, const std::string& message) {
  warnings_.push_back(message);
  graspcd::warnings().add(code, message);
}

}  // namespace graspcd::mujoco
