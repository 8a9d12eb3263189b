#include "graspcd/mujoco/nonconvex_contacts.h"

namespace graspcd::mujoco {
namespace {

RegistryConfig config_with_method(RegistryConfig config, std::optional<Method> method) {
  if (method) config.method = *method;
  return config;
}

}  // namespace

// The members in order: the registry (throws for a bad config), its attachment (throws when too
// many models are attached), then the install, so nothing is installed when construction throws,
// and destruction restores the table before it detaches.
NonconvexContacts::NonconvexContacts(const mjModel* m, const std::string& config_path,
                                     std::optional<Method> method)
    : registry_(m, config_with_method(load_registry_config(config_path), method), config_path),
      attachment_(attach(registry_)) {}

NonconvexContacts::NonconvexContacts(const mjModel* m, const RegistryConfig& config,
                                     const std::string& source)
    : registry_(m, config, source), attachment_(attach(registry_)) {}

NonconvexContacts::~NonconvexContacts() = default;

}  // namespace graspcd::mujoco
