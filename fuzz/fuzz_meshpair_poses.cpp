// libFuzzer target: the pose lines of `graspcd meshpair` (12 numbers a line: R row-major, t),
// each pose placing a fixed tetrahedron B in the frame of a fixed cube A. Oracle: every method's
// tree query (core/separators.h, all contacts) finds exactly the intersecting triangle pairs of
// CGAL's brute force on the same posed doubles (exact::mesh_mesh_pairs). Bad input must end in
// io::InputError or io::ValueError.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "graspcd/core/obb_tree.h"
#include "graspcd/core/separators.h"
#include "graspcd/exact/exact.h"
#include "graspcd/io/text_input.h"

namespace {

using graspcd::TriangleMesh;
using graspcd::Vec3;

// The cube [-1, 1]^3 (12 outward triangles) and a tetrahedron with a vertex at the origin.
TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0, 0.75, 0), Vec3(0, 0, -1.25)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static graspcd::fuzz::InputFile file("poses.txt");
  static const TriangleMesh mesh_a = cube();
  static const TriangleMesh mesh_b = tetrahedron();
  static const graspcd::ObbTree tree_a = graspcd::ObbTree::build(mesh_a);
  static const graspcd::ObbTree tree_b = graspcd::ObbTree::build(mesh_b);
  static const std::vector<graspcd::Triangle> triangles_a =
      graspcd::posed_triangles(mesh_a, graspcd::Pose{});
  constexpr std::size_t kNumbers = 12;
  graspcd::DetectorOptions options;
  options.cap = 50;
  options.switch_passes = 10;
  options.cache_slots = 64;
  try {
    graspcd::io::TextReader reader(file.write(data, size));
    std::vector<double> v;
    while (reader.next(kNumbers, v)) {
      graspcd::Pose pose;
      try {
        pose = graspcd::io::pose_from_numbers(v.data(), "pose");
      } catch (const graspcd::io::ValueError&) {
        continue;  // the command reports it at this line
      }
      const std::vector<graspcd::TrianglePair> truth =
          graspcd::exact::mesh_mesh_pairs(triangles_a, graspcd::posed_triangles(mesh_b, pose));
      for (const graspcd::Method method : graspcd::all_methods()) {
        graspcd::Detector detector(method, options);
        graspcd::QueryCounters counters;
        std::vector<graspcd::TrianglePair> pairs;
        detector.collide(tree_a, tree_b, pose, graspcd::QueryMode::kAllContacts, counters, &pairs);
        std::sort(pairs.begin(), pairs.end());
        if (pairs != truth) {
          const std::string what = std::string(graspcd::method_name(method)) +
                                   ": the tree query's triangle pairs differ from CGAL's";
          graspcd::fuzz::disagreement(what.c_str());
        }
      }
    }
  } catch (const graspcd::io::InputError&) {
  }
  return 0;
}
