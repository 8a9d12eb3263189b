// The seam with MuJoCo (DESIGN.md): graspcd's function in the entries of mjCOLLISIONFUNC that a
// served pair can reach.
//
// install() puts collide_geoms() into mjCOLLISIONFUNC[t1][t2] for every t1 <= t2 among the
// served types (sphere, capsule, ellipsoid, cylinder, box, mesh: 21 entries), saving each
// original; uninstall() puts each saved one back. An entry that is NULL at install time stays
// NULL (MuJoCo never collides that type pair, and a served pair of it would never reach us; in
// MuJoCo 2.2.2 all 21 entries are non-NULL: the primitive routines for sphere-sphere,
// sphere-capsule, capsule-capsule, sphere-box, capsule-box and box-box, the convex (MPR) routine
// for the rest). Plane and height-field rows are never touched. The table is process-global and
// MuJoCo's function gets no user pointer, so registries are attached per model in a process-wide
// table (model -> registry) and looked up from the `const mjModel*` of each call. Attaching and
// detaching take a mutex; a call's lookup does not (a fixed table of atomic slots, scanned). A
// call for a pair its model's registry serves runs that pair's path (registry.h: the exact
// box-box path, or the tree query) and returns our contacts; every other call goes to the saved
// original of its own type pair, unchanged, with the same arguments.
//
// Non-finite state: a served call whose geoms' geom_xpos or geom_xmat hold a NaN, an infinity or
// any number beyond MuJoCo's mjMAXVAL (1e10, the bound of its own mju_isBad) is skipped: it returns
// 0 contacts without running the tree query or the box test (whose answers on a NaN pose would mean
// nothing) and counts one BridgeStats::nonfinite_skips. Delegated pairs go to MuJoCo unchanged, as
// always.
//
// Contract per served call (mujoco-2.2-notes.md): at most mjMAXCONPAIR contacts, dist <= 0,
// frame[0..2] the unit normal from geom1 toward geom2 and frame[3..8] a right-handed tangent
// basis (box-box pairs: MuJoCo's own contacts); MuJoCo fills the rest. Margins are ignored on
// served pairs (contacts are reported only for intersecting surfaces, DESIGN.md "Registered pairs
// use margin 0").
//
// Not thread-safe for concurrent install/uninstall while models step; attach/detach may run while
// other models step.
#pragma once

#include <mujoco/mujoco.h>

#include "bridge/registry.h"

namespace graspcd::bridge {

// The most registries attached at once (one per live model using the bridge).
inline constexpr int kMaxAttachedModels = 64;

// True for the types whose entries install() replaces: sphere, capsule, ellipsoid, cylinder, box,
// mesh.
bool installable_type(int geom_type);
// Installs graspcd's function in every non-NULL entry of the installable type pairs (idempotent).
// Returns false when already installed.
bool install();
// Restores every saved original entry (idempotent). Returns false when not installed.
bool uninstall();
bool installed();
// The original entry of the type pair (either order) saved by install(); nullptr when not
// installed, when the pair is not installable, or when the entry was NULL.
mjfCollision original_collision(int type1, int type2);
// graspcd's collision function itself (what install() puts into the table).
int collide_geoms(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2, mjtNum margin);

// Attaches `registry` to its model (replacing any registry attached to the same model). Throws
// std::runtime_error when kMaxAttachedModels registries are attached already.
void attach(Registry& registry);
// Detaches `registry` if it is the one attached to its model (the Registry destructor calls it).
void detach(const Registry& registry);
// The registry attached to `m`, or nullptr.
Registry* find_registry(const mjModel* m);

// Runs a served pair by its path (registry.h); a pair whose placement in `d` holds a bad number
// is skipped and counted (see "Non-finite state" above). Trees: the tree query with the pair's
// detector in all-contacts mode, contacts from the intersecting triangle pairs (contact.h).
// Box-box: the detector's box test, then MuJoCo's box-box function with margin 0 (the saved
// original; the current table entry when not installed) unless the boxes were proven disjoint. At
// most mjMAXCONPAIR contacts written to `con`. Returns the count. Updates the registry's
// statistics.
int collide_served_pair(Registry& registry, int pair_index, const mjData* d, mjContact* con, int g1,
                        int g2);

// True when geom_xpos or geom_xmat of geom `g` in `d` holds a number MuJoCo calls bad
// (mju_isBad: NaN, or |x| > mjMAXVAL = 1e10, which covers the infinities).
bool bad_geom_placement(const mjData* d, int g);

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
