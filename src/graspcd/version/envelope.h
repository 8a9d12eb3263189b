// The JSON envelope every graspcd document carries (docs/design.md, "The command line"):
//
//   "graspcd":  {"version": "X.Y.Z", "commit": "<git describe --always --dirty>", "dirty": false}
//   "warnings": [{"source": "mujoco", "code": "...", "message": "...", "count": 1}, ...]
//
// beside the document's own keys, which it never changes. The commit is taken at build time
// (provenance.h), so a committed reference report names the code it was made from; the warnings
// are the process's sink (graspcd/io/warnings.h) when the document is written.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "graspcd/io/warnings.h"

namespace graspcd {

// {"version", "commit", "dirty"} of this build.
nlohmann::json provenance_json();

// The warnings as the envelope's array.
nlohmann::json warnings_json(const std::vector<Warning>& warnings);

// Adds "graspcd" (provenance_json) and "warnings" (the process's sink) to a JSON object.
void add_envelope(nlohmann::json& document);

}  // namespace graspcd
