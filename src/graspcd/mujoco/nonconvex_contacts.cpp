#include "graspcd/mujoco/nonconvex_contacts.h"

#include <mutex>

namespace graspcd::mujoco {
namespace {

// How many NonconvexContacts are alive, and whether the first of them installed the table (it was
// not installed by the program before). Guarded by g_users_mutex.
std::mutex g_users_mutex;
int g_users = 0;
bool g_owns_install = false;

void add_user() {
  std::lock_guard<std::mutex> lock(g_users_mutex);
  if (g_users++ == 0) g_owns_install = install();
}

void remove_user() {
  std::lock_guard<std::mutex> lock(g_users_mutex);
  if (--g_users == 0 && g_owns_install) {
    uninstall();
    g_owns_install = false;
  }
}

RegistryConfig config_with_method(RegistryConfig config, std::optional<Method> method) {
  if (method) config.method = *method;
  return config;
}

}  // namespace

NonconvexContacts::NonconvexContacts(const mjModel* m, const std::string& config_path,
                                     std::optional<Method> method)
    : registry_(m, config_with_method(load_registry_config(config_path), method), config_path) {
  attach(registry_);  // throws before anything is installed
  add_user();
}

NonconvexContacts::NonconvexContacts(const mjModel* m, const RegistryConfig& config,
                                     const std::string& source)
    : registry_(m, config, source) {
  attach(registry_);
  add_user();
}

NonconvexContacts::~NonconvexContacts() {
  remove_user();
  detach(registry_);
}

}  // namespace graspcd::mujoco
