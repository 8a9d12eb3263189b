// A shared library that holds graspcd's io, as a plugin or a Python module linking graspcd would:
// loaded with dlopen by mesh_import_test, which reads a mesh through it.
#include <cstring>
#include <exception>
#include <string>

#include "graspcd/io/mesh_io.h"

// The faces of the mesh at `path`, or -1 with the error (at most `size` bytes) in `error`.
extern "C" __attribute__((visibility("default"))) long graspcd_test_faces_of(const char* path,
                                                                             char* error,
                                                                             unsigned long size) {
  try {
    return static_cast<long>(graspcd::io::load_mesh(path).faces.size());
  } catch (const std::exception& e) {
    std::strncpy(error, e.what(), size - 1);
    error[size - 1] = '\0';
    return -1;
  }
}
