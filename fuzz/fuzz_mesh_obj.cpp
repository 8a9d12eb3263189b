// libFuzzer target: OBJ loading (io/mesh_io.h: tinyobjloader in double precision plus graspcd's
// own checks). A mesh that loads is built into an OBB tree, its closedness computed, and (when
// small) queried against a fixed tetrahedron. Oracles: the tree query's intersecting triangle
// pairs equal CGAL's brute force (exact::mesh_mesh_pairs), and for a closed mesh the tree's
// point_side equals the brute-force one (core/containment.h). Bad input must end in
// io::InputError.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.h"
#include "graspcd/core/containment.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/core/separators.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/mesh_io.h"

namespace {

// Meshes up to this many faces are checked against CGAL (brute force, kept cheap).
constexpr std::size_t kMaxCheckedFaces = 256;

graspcd::TriangleMesh tetrahedron() {
  graspcd::TriangleMesh m;
  m.vertices = {graspcd::Vec3(0, 0, 0), graspcd::Vec3(0.5, 0, 0), graspcd::Vec3(0, 0.75, 0),
                graspcd::Vec3(0, 0, -1.25)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static graspcd::fuzz::InputFile file("input.obj");
  static const graspcd::TriangleMesh probe = tetrahedron();
  static const graspcd::ObbTree probe_tree = graspcd::ObbTree::build(probe);
  graspcd::TriangleMesh mesh;
  graspcd::io::MeshStats stats;
  try {
    mesh = graspcd::io::load_mesh(file.write(data, size), &stats);
  } catch (const graspcd::io::InputError&) {
    return 0;  // bad input, reported as the command line would
  }
  const graspcd::ObbTree tree = graspcd::ObbTree::build(mesh);
  const graspcd::Closedness closed = graspcd::closedness(tree);
  if (closed.faces != mesh.faces.size()) graspcd::fuzz::disagreement("closedness lost faces");
  if (mesh.faces.size() > kMaxCheckedFaces) return 0;

  const std::vector<graspcd::Triangle> triangles = graspcd::posed_triangles(mesh, graspcd::Pose{});
  const std::vector<graspcd::TrianglePair> truth =
      graspcd::exact::mesh_mesh_pairs(triangles, graspcd::posed_triangles(probe, graspcd::Pose{}));
  graspcd::Detector detector(graspcd::Method::kSat);
  graspcd::QueryCounters counters;
  std::vector<graspcd::TrianglePair> pairs;
  detector.collide(tree, probe_tree, graspcd::Pose{}, graspcd::QueryMode::kAllContacts, counters,
                   &pairs);
  std::sort(pairs.begin(), pairs.end());
  if (pairs != truth) graspcd::fuzz::disagreement("tree query differs from CGAL on a loaded mesh");

  // Containment's point query, on a few points: the mesh's first vertex and the probe's.
  if (!closed.closed()) return 0;
  for (const graspcd::Vec3& p : {mesh.vertices[mesh.faces[0][0]], probe.vertices[1],
                                 probe.vertices[3], graspcd::Vec3(0.125, 0.25, -0.5)}) {
    if (graspcd::point_side(tree, p) != graspcd::point_side(triangles, p)) {
      graspcd::fuzz::disagreement("point_side: tree and brute force differ");
    }
  }
  return 0;
}
