// A program written against graspcd 0.1's include paths: "bridge/..." and "core/..." (forwarding
// headers in 0.2, removed in 0.3) and the namespace graspcd::bridge (an alias of graspcd::mujoco
// since 0.3), plus the mesh reader graspcd::io. It reads a mesh, builds its OBB tree and prints
// "faces N boxes M". Usage: legacy_includes MESH.obj. Errors: one line, exit 2.
#include <cstdio>
#include <exception>
#include <memory>

#include "bridge/contact.h"
#include "bridge/nonconvex_contacts.h"
#include "core/obb_tree.h"
#include "graspcd/io/mesh_io.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: legacy_includes MESH.obj\n");
    return 2;
  }
  try {
    const graspcd::TriangleMesh mesh = graspcd::io::load_mesh(argv[1]);
    const graspcd::ObbTree tree = graspcd::ObbTree::build(mesh);
    const graspcd::bridge::TriContact unused{};  // the 0.1 name of graspcd::TriContact
    const graspcd::bridge::BridgeStats stats{};  // the 0.2 name of graspcd::mujoco::BridgeStats
    std::printf("faces %zu boxes %zu depth %.0f\n", mesh.faces.size(), tree.nodes().size(),
                unused.depth + static_cast<double>(stats.calls));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
