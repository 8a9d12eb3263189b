// A program written against graspcd 0.2's namespace graspcd::bridge, an alias of graspcd::mujoco
// for the 0.3 versions (graspcd/mujoco/bridge_namespace.h), with the include paths of 0.3
// (<graspcd/core/...>, <graspcd/mujoco/...>; the 0.1 paths "bridge/..." and "core/..." are gone),
// plus the mesh reader graspcd::io. It reads a mesh, builds its OBB tree and prints
// "faces N boxes M". Usage: bridge_alias MESH.obj. Errors: one line, exit 2.
#include <cstdio>
#include <exception>
#include <type_traits>

#include "graspcd/core/obb_tree.h"
#include "graspcd/core/triangle_contact.h"
#include "graspcd/io/mesh_io.h"
#include "graspcd/mujoco/nonconvex_contacts.h"

// The 0.2 names still name the seam's types.
static_assert(
    std::is_same_v<graspcd::bridge::NonconvexContacts, graspcd::mujoco::NonconvexContacts>);
static_assert(std::is_same_v<graspcd::bridge::BridgeStats, graspcd::mujoco::BridgeStats>);

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bridge_alias MESH.obj\n");
    return 2;
  }
  try {
    const graspcd::TriangleMesh mesh = graspcd::io::load_mesh(argv[1]);
    const graspcd::ObbTree tree = graspcd::ObbTree::build(mesh);
    const graspcd::TriContact unused{};          // graspcd::bridge::TriContact up to 0.2
    const graspcd::bridge::BridgeStats stats{};  // the 0.2 name of graspcd::mujoco::BridgeStats
    graspcd::bridge::NonconvexContacts* contacts = nullptr;  // the 0.2 name, as a type
    std::printf("faces %zu boxes %zu depth %.0f\n", mesh.faces.size(), tree.nodes().size(),
                unused.depth + static_cast<double>(stats.calls) + (contacts ? 1.0 : 0.0));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
