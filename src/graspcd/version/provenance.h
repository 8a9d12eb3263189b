// Where a result comes from: the graspcd version and the commit of the tree it was built from,
// taken at build time (`git describe --always --dirty`, "unknown" outside git;
// cmake/git_describe.cmake). Every JSON output and report records it (docs/design.md, "The command
// line"), so that a committed reference can be matched to its code.
#pragma once

#include <string>

namespace graspcd {

struct Provenance {
  std::string version;  // the project's version (CMakeLists.txt), e.g. "0.2.0"
  std::string commit;   // `git describe --always --dirty --abbrev=12`, or "unknown"
  bool dirty = false;   // the work tree had uncommitted changes to tracked files at build time
};

// This build's provenance.
const Provenance& provenance();

}  // namespace graspcd
