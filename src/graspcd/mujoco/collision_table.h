// graspcd's entries in MuJoCo's collision table and the model -> registry table (collision.h says
// what a call does).
//
// install() puts collide_geoms() into mjCOLLISIONFUNC[t1][t2] for every t1 <= t2 among the served
// types (21 entries), saving each original; uninstall() puts each saved one back. An entry that is
// NULL at install time stays NULL (MuJoCo never collides that type pair; in MuJoCo 2.2.2 all 21 are
// set); plane and height-field rows are never touched. ScopedInstall owns the install. MuJoCo's
// function gets no user pointer, so registries are attached per model in a process-wide table and
// looked up from the `const mjModel*` of each call. Attaching and detaching take a mutex; a call's
// lookup does not (a fixed table of atomic slots, scanned). Not thread-safe for concurrent
// install/uninstall while models step; attach/detach may run while other models step.
#pragma once

#include <mujoco/mujoco.h>

#include "graspcd/mujoco/registry.h"

namespace graspcd::mujoco {

// The most registries attached at once (one per live model that graspcd serves).
inline constexpr int kMaxAttachedModels = 64;

// True for the types whose entries install() replaces: sphere, capsule, ellipsoid, cylinder, box,
// mesh.
bool installable_type(int geom_type);
// Installs graspcd's function in every non-NULL entry of the installable type pairs (idempotent).
// Returns false when already installed. Programs use ScopedInstall, which calls this.
bool install();
// Restores every saved original entry (idempotent). Returns false when not installed.
bool uninstall();
bool installed();
// The original entry of the type pair (either order) saved by install(); nullptr when not
// installed, when the pair is not installable, or when the entry was NULL. Lock-free.
mjfCollision original_collision(int type1, int type2);
// graspcd's collision function itself (what install() puts into the table): a pair its model's
// registry serves runs collide_served_pair (collision_served.h) with the saved box-box original;
// every other call goes to the saved original of its own type pair, unchanged, with the same
// arguments.
int collide_geoms(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2, mjtNum margin);

class Attachment;
// Attaches `registry` to its model (replacing any registry attached to the same model) for as long
// as the returned Attachment lives. Throws std::runtime_error when kMaxAttachedModels registries
// are attached already.
[[nodiscard]] Attachment attach(Registry& registry);
// The registry attached to `m`, or nullptr.
Registry* find_registry(const mjModel* m);

// RAII: a registry attached to its model, detached when this is destroyed or released (if it is
// still the one attached). Whoever attaches owns it, and destroys it before the registry.
class Attachment {
 public:
  Attachment() = default;
  Attachment(Attachment&& other) noexcept : registry_(other.registry_) {
    other.registry_ = nullptr;
  }
  Attachment& operator=(Attachment&& other) noexcept {
    if (this != &other) {
      release();
      registry_ = other.registry_;
      other.registry_ = nullptr;
    }
    return *this;
  }
  Attachment(const Attachment&) = delete;
  Attachment& operator=(const Attachment&) = delete;
  ~Attachment() { release(); }
  // Detaches now (nothing when empty or released already).
  void release();

 private:
  friend Attachment attach(Registry& registry);
  explicit Attachment(const Registry* registry) : registry_(registry) {}
  const Registry* registry_ = nullptr;
};

// RAII, the owner of the table's install: the first live ScopedInstall installs (unless the table
// was installed already by install(), which it then leaves alone), the last one destroyed restores
// what it installed. Any number may live at once (a program's own, each NonconvexContacts').
// Construction and destruction are thread-safe.
class ScopedInstall {
 public:
  ScopedInstall();
  ~ScopedInstall();
  ScopedInstall(const ScopedInstall&) = delete;
  ScopedInstall& operator=(const ScopedInstall&) = delete;
};

}  // namespace graspcd::mujoco
