// graspcd's public entry point for an existing MuJoCo 2.2 program: non-convex contacts for the geom
// pairs a config names, every other pair left to MuJoCo unchanged (docs/design.md, "The MuJoCo
// layer"). A thin RAII owner of the pieces in registry.h and collision.h:
//
//   mjModel* m = mj_loadXML("scene.xml", nullptr, error, sizeof error);
//   mjData* d = mj_makeData(m);
//   graspcd::mujoco::NonconvexContacts contacts(m, "scene.pairs.json");
//   for (...) mj_step(m, d);                  // as usual: served pairs get graspcd's contacts
//   graspcd::mujoco::BridgeStats s = contacts.take_stats();
//
// Construction builds the pair registry (the OBB trees of the meshes and primitives in served
// pairs), attaches it to the model and installs graspcd's function in mjCOLLISIONFUNC; destruction
// undoes both (it owns the Attachment and the ScopedInstall). Lifetime: construct after loading the
// model, keep it alive while the model steps, destroy it before mj_deleteModel (the registry refers
// to the model).
//
// Several NonconvexContacts (one per model) may live at once: each holds a ScopedInstall
// (collision_table.h), so the function table is installed when the first is constructed and
// restored when the last is destroyed (a program's own ScopedInstall keeps it installed for as
// long as it lives; a table installed by install() is left to the program).
// Construction and destruction are thread-safe; stepping one model from two threads at once is
// not (the registry's pair states and statistics mutate, registry.h).
#pragma once

#include <mujoco/mujoco.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "graspcd/core/separators.h"
#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::mujoco {

class NonconvexContacts {
 public:
  // Reads the JSON pair config at `config_path` (format: pair_config.h) and serves its pairs in
  // `m`. `method`, when given, replaces the config's "method" (the box separator of the OBB-tree
  // query; core/separators.h, e.g. parse_method("sat")). Every detector answers exactly; the method
  // changes the cost, never the contacts. Since 0.4.0 a touching pair's contacts are reused
  // within 20 um unless the config sets "contact_reuse" (0: exact contacts every step;
  // RegistryConfig::kDefaultContactReuse).
  // Errors: std::runtime_error with a one-line message starting with `config_path` for a missing
  // file, bad JSON, an unknown field or method, a pattern that matches no collidable geom, a
  // matched geom of a type graspcd does not serve (plane, height field); std::runtime_error when
  // kMaxAttachedModels models use the MuJoCo layer already. Nothing is installed when it throws.
  NonconvexContacts(const mjModel* m, const std::string& config_path,
                    std::optional<Method> method = std::nullopt);
  // The same from a config built in code (patterns and/or geom id pairs, pair_config.h); `source`
  // starts the error messages.
  NonconvexContacts(const mjModel* m, const RegistryConfig& config,
                    const std::string& source = "<program>");
  // Detaches the registry and, if this was the last NonconvexContacts, restores MuJoCo's table.
  ~NonconvexContacts();
  NonconvexContacts(const NonconvexContacts&) = delete;
  NonconvexContacts& operator=(const NonconvexContacts&) = delete;

  // The box separator in use.
  Method method() const { return registry_.config().method; }
  // The number of served geom pairs (unordered, distinct geoms).
  std::size_t served_pairs() const { return registry_.pairs().size(); }
  // Non-fatal findings of the construction, one line each (e.g. a served geom with a non-zero
  // margin: served pairs report contacts of intersecting surfaces only).
  const std::vector<std::string>& warnings() const { return registry_.warnings(); }

  // Work and output of the served pairs summed since construction or the last take_stats() /
  // reset_stats(): served calls, detection and contact time in ns (steady clock), box and
  // triangle tests, contacts handed to MuJoCo (registry.h, BridgeStats).
  const BridgeStats& stats() const { return registry_.stats(); }
  // The statistics since the last take, then a reset: call it once per mj_step for per-step
  // numbers.
  BridgeStats take_stats() { return registry_.take_stats(); }
  void reset_stats() { registry_.reset_stats(); }
  // Forgets the detectors' state carried from step to step (warm planes, cached axes), e.g. after
  // mj_resetData.
  void reset_detectors() { registry_.reset_detectors(); }

  // The underlying registry (trees, served pairs and their paths), for inspection.
  const Registry& registry() const { return registry_; }

 private:
  Registry registry_;
  Attachment attachment_;  // detaches registry_ before it goes
  ScopedInstall install_;  // counted: the table stays installed while any ScopedInstall lives
};

}  // namespace graspcd::mujoco
