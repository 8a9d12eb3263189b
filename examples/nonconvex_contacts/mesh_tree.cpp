// mesh_tree: a program that uses the installed mesh reader and geometry core without MuJoCo
// (graspcd::io, which links graspcd::core). It reads a mesh, builds its OBB tree and prints
// "faces N boxes M". Usage: mesh_tree MESH. Errors: one line, exit 2.
#include <cstdio>
#include <exception>

#include "graspcd/core/obb_tree.h"
#include "graspcd/io/mesh_io.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mesh_tree MESH\n");
    return 2;
  }
  try {
    const graspcd::TriangleMesh mesh = graspcd::io::load_mesh(argv[1]);
    const graspcd::ObbTree tree = graspcd::ObbTree::build(mesh);
    std::printf("faces %zu boxes %zu\n", mesh.faces.size(), tree.nodes().size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
