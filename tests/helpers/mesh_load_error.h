// The one-line refusal of load_mesh (io/mesh_io.h) as a string, for the mesh readers' tests.
#pragma once

#include <string>

#include "graspcd/io/mesh_io.h"
#include "graspcd/io/text_input.h"

namespace graspcd::testing {

// The message of the InputError load_mesh throws, or "" if it loads.
inline std::string load_error(const std::string& path) {
  try {
    io::load_mesh(path);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace graspcd::testing
