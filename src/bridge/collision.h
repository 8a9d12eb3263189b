// The seam with MuJoCo (DESIGN.md): graspcd's function in
// mjCOLLISIONFUNC[mjGEOM_MESH][mjGEOM_MESH].
//
// install() saves the original entry and puts ours in its place; uninstall() puts the saved one
// back. The table is process-global and MuJoCo's function gets no user pointer, so registries are
// attached per model in a process-wide table (model -> registry) and looked up from the
// `const mjModel*` of each call. Attaching and detaching take a mutex; a call's lookup does not
// (a fixed table of atomic slots, scanned). A call for a pair its model's registry serves runs
// the tree query and returns our contacts; every other call goes to the saved original,
// unchanged, with the same arguments.
//
// Contract per served call (mujoco-2.2-notes.md): at most mjMAXCONPAIR contacts, dist <= 0,
// frame[0..2] the unit normal from geom1 toward geom2 and frame[3..8] a right-handed tangent
// basis; MuJoCo fills the rest. Margins are ignored on served pairs (contacts are reported only
// for intersecting surfaces, DESIGN.md "Registered pairs use margin 0").
//
// Not thread-safe for concurrent install/uninstall while models step; attach/detach may run while
// other models step.
#pragma once

#include <mujoco/mujoco.h>

#include "bridge/registry.h"

namespace graspcd::bridge {

// The most registries attached at once (one per live model using the bridge).
inline constexpr int kMaxAttachedModels = 64;

// Installs graspcd's mesh-mesh function (idempotent). Returns false when already installed.
bool install();
// Restores the saved original entry (idempotent). Returns false when not installed.
bool uninstall();
bool installed();
// The original entry saved by install() (nullptr when not installed).
mjfCollision original_mesh_mesh();
// graspcd's collision function itself (what install() puts into the table).
int collide_mesh_mesh(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                      mjtNum margin);

// Attaches `registry` to its model (replacing any registry attached to the same model). Throws
// std::runtime_error when kMaxAttachedModels registries are attached already.
void attach(Registry& registry);
// Detaches `registry` if it is the one attached to its model (the Registry destructor calls it).
void detach(const Registry& registry);
// The registry attached to `m`, or nullptr.
Registry* find_registry(const mjModel* m);

// Runs a served pair: the tree query with the pair's detector in all-contacts mode, contacts
// from the intersecting triangle pairs (contact.h), at most mjMAXCONPAIR written to `con`.
// Returns the count. Updates the registry's statistics.
int collide_served_pair(Registry& registry, int pair_index, const mjData* d, mjContact* con, int g1,
                        int g2);

// geom2 placed in geom1's frame from d->geom_xpos / d->geom_xmat (row-major):
// R = R1^T R2, t = R1^T (p2 - p1), so that x_1 = R x_2 + t.
Pose relative_pose(const mjData* d, int g1, int g2);

// RAII: install() on construction, uninstall() on destruction if this object installed it.
class ScopedInstall {
 public:
  ScopedInstall() : owner_(install()) {}
  ~ScopedInstall() {
    if (owner_) uninstall();
  }
  ScopedInstall(const ScopedInstall&) = delete;
  ScopedInstall& operator=(const ScopedInstall&) = delete;

 private:
  bool owner_;
};

}  // namespace graspcd::bridge
