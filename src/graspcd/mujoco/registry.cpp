// The pair registry of one model at run time (registry.h).
#include "graspcd/mujoco/registry.h"

#include <set>
#include <stdexcept>

#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/input_error.h"
#include "graspcd/mujoco/model_check.h"

namespace graspcd::mujoco {

// Resolve every pattern pair and direct geom pair, choose each pair's path, then build one tree per
// mesh and per primitive (type, size) that a pair served by trees uses (docs/design.md: trees once
// per mesh, in the geom frame, shared by the geoms of a mesh; primitives through a tessellated
// mesh, primitives.h).
Registry::Registry(const mjModel* m, const RegistryConfig& config, const std::string& source,
                   const SceneNames& names)
    : model_(m), config_(config), trees_(m) {
  const std::string named = names.file(source);
  check_model(named);
  add_pattern_pairs(named);
  add_geom_pairs(named);
  warn_served_margins(named);
  choose_paths_and_build_trees(named, names);
  warn_open_meshes(named, names);
}

// A model with a non-finite number (MuJoCo compiles a NaN attribute with a warning) is refused
// here, at construction, never met inside mj_step (model_check.h).
void Registry::check_model(const std::string& source) const {
  if (!model_) throw io::InputError(source, 0, "no model");
  const std::string non_finite = find_non_finite(model_);
  if (!non_finite.empty()) throw io::InputError(source, 0, non_finite);
}

void Registry::add_pattern_pairs(const std::string& source) {
  for (const PairPattern& p : config_.patterns) {
    const std::vector<int> as = resolve_pattern(model_, p.a, source);
    const std::vector<int> bs = resolve_pattern(model_, p.b, source);
    ManifoldOptions manifold = config_.manifold;
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
      throw io::InputError(source, 0,
                           "pair ('" + p.a + "', '" + p.b + "') selects no pair of distinct geoms");
    }
  }
}

void Registry::add_geom_pairs(const std::string& source) {
  const mjModel* m = model_;
  for (const auto& [a, b] : config_.geom_pairs) {
    if (a < 0 || b < 0 || a >= m->ngeom || b >= m->ngeom || a == b) {
      throw io::InputError(source, 0,
                           "bad geom pair (" + std::to_string(a) + ", " + std::to_string(b) + ")");
    }
    for (int g : {a, b}) {
      if (!served_geom_type(m->geom_type[g])) {
        throw io::InputError(source, 0, "geom pair member " + unserved_geom(m, g));
      }
    }
    add_pair(a, b, config_.manifold);
  }
}

// Served geoms with a margin: MuJoCo would expect contacts within it; we report none.
void Registry::warn_served_margins(const std::string& source) {
  const mjModel* m = model_;
  std::set<int> served;
  for (const ServedPair& p : pairs_) served.insert({p.geom_lo, p.geom_hi});
  for (int g : served) {
    if (m->geom_margin[g] == 0) continue;
    const std::string gname = object_name(m, mjOBJ_GEOM, g);
    warn("served_geom_margin", source + ": served geom " + std::to_string(g) +
                                   (gname.empty() ? "" : " '" + gname + "'") + " has margin " +
                                   std::to_string(m->geom_margin[g]) +
                                   "; served pairs report intersecting surfaces only (margin 0)");
  }
}

// The path of each pair; trees for the geoms of pairs served by trees only: one per mesh, one per
// primitive (type, size).
void Registry::choose_paths_and_build_trees(const std::string& source, const SceneNames& names) {
  const mjModel* m = model_;
  const WarningSink sink = [this](const std::string& code, const std::string& message) {
    warn(code, message);
  };
  for (ServedPair& p : pairs_) {
    if (m->geom_type[p.geom_lo] == mjGEOM_BOX && m->geom_type[p.geom_hi] == mjGEOM_BOX) {
      p.path = PairPath::kBoxBox;
      continue;
    }
    p.path = PairPath::kTrees;
    for (int g : {p.geom_lo, p.geom_hi}) trees_.add_geom(m, g, source, sink, names);
  }
}

// Open meshes (core/containment.h): the separate containment check needs a closed solid, so it is
// skipped inside them; their pairs still get every surface contact. Once per mesh.
void Registry::warn_open_meshes(const std::string& source, const SceneNames& names) {
  const mjModel* m = model_;
  std::set<int> warned;
  for (const ServedPair& p : pairs_) {
    if (p.path != PairPath::kTrees) continue;
    for (int g : {p.geom_lo, p.geom_hi}) {
      const MeshTree* t = trees_.geom_tree(g);
      if (t->closedness.closed() || m->geom_type[g] != mjGEOM_MESH) continue;
      const int mesh = m->geom_dataid[g];
      if (!warned.insert(mesh).second) continue;
      const std::string mname = object_name(m, mjOBJ_MESH, mesh);
      warn("mesh_open", source + ": " + names.mesh_owner(mname) + "mesh " + std::to_string(mesh) +
                            (mname.empty() ? "" : " '" + mname + "'") + " is " +
                            t->closedness.describe() +
                            "; containment inside it is not checked (surface contacts only)");
    }
  }
}

void Registry::add_pair(int g1, int g2, const ManifoldOptions& manifold) {
  const std::uint64_t k = key(g1, g2);
  if (pair_index_.count(k)) return;
  // Detector options out of range throw std::invalid_argument when the first pair is registered,
  // as they always have, not at a pair's first call inside mj_step.
  if (pairs_.empty()) (void)make_detector();
  ServedPair p;
  p.geom_lo = g1 < g2 ? g1 : g2;
  p.geom_hi = g1 < g2 ? g2 : g1;
  p.manifold = manifold;
  pair_index_.emplace(k, static_cast<int>(pairs_.size()));
  pairs_.push_back(p);
}

void Registry::reset_detectors() { states_.clear(); }

Registry::DataPairState& Registry::pair_state(const mjData* d, int pair_index) {
  auto it = states_.find(d);
  if (it == states_.end()) {
    if (states_.size() >= kMaxFrontData) states_.clear();
    std::vector<DataPairState> fresh;
    fresh.reserve(pairs_.size());
    for (std::size_t i = 0; i < pairs_.size(); ++i) fresh.emplace_back(make_detector());
    it = states_.emplace(d, std::move(fresh)).first;
  }
  return it->second[static_cast<std::size_t>(pair_index)];
}

const Registry::DataPairState* Registry::find_pair_state(const mjData* d, int pair_index) const {
  const auto it = states_.find(d);
  return it == states_.end() ? nullptr : &it->second[static_cast<std::size_t>(pair_index)];
}

void Registry::forget_fronts(const mjData* d) { states_.erase(d); }

Registry::PairStates Registry::snapshot(const mjData* d) const {
  const auto it = states_.find(d);
  return it == states_.end() ? PairStates{} : it->second;
}

void Registry::restore(const mjData* d, const PairStates& states) {
  if (states.empty()) {
    states_.erase(d);
    return;
  }
  if (states_.find(d) == states_.end() && states_.size() >= kMaxFrontData) states_.clear();
  states_.insert_or_assign(d, states);
}

void Registry::warn(const std::string& code, const std::string& message) {
  warnings_.push_back(message);
  graspcd::warnings().add(code, message);
}

}  // namespace graspcd::mujoco
