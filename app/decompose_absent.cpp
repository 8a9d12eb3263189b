// graspcd decompose in a build without the convex decomposition (GRASPCD_WITH_HACD=OFF): the
// subcommand is there, takes any arguments, and says in one line that this build has none (exit 2).
#include <string>

#include "command.h"

namespace graspcd::cli {

Command add_decompose_command(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand(
      "decompose", "Approximate convex decomposition (HACD): not in this build");
  app->allow_extras();
  return Command{app, [] {
                   throw UsageError(
                       "decompose: this build has no convex decomposition (configured with "
                       "GRASPCD_WITH_HACD=OFF; HACD is in Debian's libbullet-extras-dev)");
                 }};
}

}  // namespace graspcd::cli
