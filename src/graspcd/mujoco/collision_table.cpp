// The process-wide side of the MuJoCo layer (collision_table.h): graspcd's entries in
// mjCOLLISIONFUNC and the model -> registry table that its function looks registries up in.
#include "graspcd/mujoco/collision_table.h"

#include <array>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "graspcd/mujoco/collision_served.h"
#include "graspcd/mujoco/primitives.h"

namespace graspcd::mujoco {
namespace {

// The process-wide model -> registry table. Writers hold g_mutex; readers (every collision call)
// scan the slots up to g_used without locking. A slot is published registry first, model second
// (release), and read model first, registry second (acquire); detaching clears the model first,
// so a reader sees either a consistent pair or a null registry, which delegates.
struct Slot {
  std::atomic<const mjModel*> model{nullptr};
  std::atomic<Registry*> registry{nullptr};
};
std::array<Slot, kMaxAttachedModels> g_slots;
std::atomic<int> g_used{0};  // high-water mark of used slots
std::mutex g_mutex;

// The saved original entries by [type1][type2] (type1 <= type2), read by every delegated call;
// g_replaced marks the entries install() replaced (under g_mutex), g_installed guards
// install/uninstall. Zero-initialised (static storage).
std::array<std::array<std::atomic<mjfCollision>, mjNGEOMTYPES>, mjNGEOMTYPES> g_originals;
bool g_replaced[mjNGEOMTYPES][mjNGEOMTYPES] = {};
bool g_installed = false;
// The live ScopedInstalls, and whether the first of them installed the table (under g_mutex).
int g_scoped = 0;
bool g_scoped_installed = false;

// The saved original of a type pair, either order.
mjfCollision saved_original(int t1, int t2) {
  if (t1 > t2) std::swap(t1, t2);
  if (t1 < 0 || t2 >= mjNGEOMTYPES) return nullptr;
  return g_originals[static_cast<std::size_t>(t1)][static_cast<std::size_t>(t2)].load(
      std::memory_order_acquire);
}

// install() and uninstall() with g_mutex held.
bool install_locked() {
  if (g_installed) return false;
  for (int t1 = 0; t1 < mjNGEOMTYPES; ++t1) {
    for (int t2 = t1; t2 < mjNGEOMTYPES; ++t2) {
      if (!installable_type(t1) || !installable_type(t2) || !mjCOLLISIONFUNC[t1][t2]) continue;
      g_originals[static_cast<std::size_t>(t1)][static_cast<std::size_t>(t2)].store(
          mjCOLLISIONFUNC[t1][t2], std::memory_order_release);
      mjCOLLISIONFUNC[t1][t2] = &collide_geoms;
      g_replaced[t1][t2] = true;
    }
  }
  g_installed = true;
  return true;
}

bool uninstall_locked() {
  if (!g_installed) return false;
  for (int t1 = 0; t1 < mjNGEOMTYPES; ++t1) {
    for (int t2 = t1; t2 < mjNGEOMTYPES; ++t2) {
      if (!g_replaced[t1][t2]) continue;
      auto& saved = g_originals[static_cast<std::size_t>(t1)][static_cast<std::size_t>(t2)];
      mjCOLLISIONFUNC[t1][t2] = saved.load(std::memory_order_relaxed);
      saved.store(nullptr, std::memory_order_release);
      g_replaced[t1][t2] = false;
    }
  }
  g_installed = false;
  return true;
}

// MuJoCo's box-box function for the served box-box path: the saved original, or the table's entry
// when not installed (never graspcd's own).
mjfCollision mujoco_box_box() {
  mjfCollision box_box = saved_original(mjGEOM_BOX, mjGEOM_BOX);
  if (!box_box) box_box = mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX];
  return box_box == &collide_geoms ? nullptr : box_box;
}

}  // namespace

bool installable_type(int geom_type) { return geom_type == mjGEOM_MESH || is_primitive(geom_type); }

bool install() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return install_locked();
}

bool uninstall() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return uninstall_locked();
}

ScopedInstall::ScopedInstall() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_scoped++ == 0) g_scoped_installed = install_locked();
}

ScopedInstall::~ScopedInstall() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (--g_scoped == 0 && g_scoped_installed) {
    uninstall_locked();
    g_scoped_installed = false;
  }
}

bool installed() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_installed;
}

mjfCollision original_collision(int type1, int type2) { return saved_original(type1, type2); }

Attachment attach(Registry& registry) {
  std::lock_guard<std::mutex> lock(g_mutex);
  const mjModel* m = registry.model();
  int free_slot = -1;
  const int used = g_used.load(std::memory_order_relaxed);
  for (int i = 0; i < used; ++i) {
    Slot& s = g_slots[static_cast<std::size_t>(i)];
    const mjModel* sm = s.model.load(std::memory_order_relaxed);
    if (sm == m) {
      s.registry.store(&registry, std::memory_order_release);
      return Attachment(&registry);
    }
    if (!sm && free_slot < 0) free_slot = i;
  }
  if (free_slot < 0) {
    if (used == kMaxAttachedModels) {
      throw std::runtime_error("graspcd: more than " + std::to_string(kMaxAttachedModels) +
                               " models attached at once");
    }
    free_slot = used;
    g_used.store(used + 1, std::memory_order_release);
  }
  Slot& s = g_slots[static_cast<std::size_t>(free_slot)];
  s.registry.store(&registry, std::memory_order_release);
  s.model.store(m, std::memory_order_release);
  return Attachment(&registry);
}

// The slot is found by the registry's address alone, never by reading the registry, so that a
// release after the registry went (against the rule in collision_table.h) reads no freed memory.
void Attachment::release() {
  if (!registry_) return;
  const Registry* registry = registry_;
  registry_ = nullptr;
  std::lock_guard<std::mutex> lock(g_mutex);
  const int used = g_used.load(std::memory_order_relaxed);
  for (int i = 0; i < used; ++i) {
    Slot& s = g_slots[static_cast<std::size_t>(i)];
    if (s.registry.load(std::memory_order_relaxed) == registry) {
      s.model.store(nullptr, std::memory_order_release);
      s.registry.store(nullptr, std::memory_order_release);
    }
  }
}

Registry* find_registry(const mjModel* m) {
  const int used = g_used.load(std::memory_order_acquire);
  for (int i = 0; i < used; ++i) {
    const Slot& s = g_slots[static_cast<std::size_t>(i)];
    if (s.model.load(std::memory_order_acquire) == m) {
      return s.registry.load(std::memory_order_acquire);
    }
  }
  return nullptr;
}

// The table entry: served pairs to the registry, everything else to the saved original of the
// call's own type pair.
int collide_geoms(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                  mjtNum margin) {
  if (Registry* r = find_registry(m)) {
    const int index = r->find_pair(g1, g2);
    if (index >= 0) return collide_served_pair(*r, index, d, con, g1, g2, mujoco_box_box());
  }
  const mjfCollision original = saved_original(m->geom_type[g1], m->geom_type[g2]);
  return original ? original(m, d, con, g1, g2, margin) : 0;
}

}  // namespace graspcd::mujoco
