// A mesh's features: vertices welded by exact coordinates and the sharp-edge masks.
#include "graspcd/core/mesh_features.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <stdexcept>
#include <vector>

#include "graspcd/support/meshes.h"

namespace graspcd::mesh_features_test {
namespace {

Triangle tri(Vec3 a, Vec3 b, Vec3 c) { return Triangle{{a, b, c}}; }

// A box's face diagonals are not feature edges, its 12 edges are; a finely tessellated sphere has
// none.
TEST(SharpEdges, BoxEdgesAreSharpDiagonalsAndSmoothSurfacesAreNot) {
  const TriangleMesh box = testing::make_box_mesh(0.01, 0.02, 0.03);
  std::vector<Triangle> faces;
  for (std::size_t f = 0; f < box.faces.size(); ++f) faces.push_back(box.triangle(f));
  const auto masks = sharp_edge_masks(faces);
  ASSERT_EQ(masks.size(), 12u);
  int sharp = 0;
  for (std::uint8_t m : masks) {
    const int bits = (m & 1) + (m >> 1 & 1) + (m >> 2 & 1);
    EXPECT_EQ(bits, 2);  // two box edges and the diagonal
    sharp += bits;
  }
  EXPECT_EQ(sharp, 24);  // 12 edges, each seen from its two faces
  const TriangleMesh sphere = testing::make_uv_sphere(0.05, 24, 48);
  faces.clear();
  for (std::size_t f = 0; f < sphere.faces.size(); ++f) faces.push_back(sphere.triangle(f));
  for (std::uint8_t m : sharp_edge_masks(faces)) EXPECT_EQ(m, 0);
  // With the welded ids given (as the registry calls it): the same masks; ids of another length
  // are refused.
  faces.clear();
  for (std::size_t f = 0; f < box.faces.size(); ++f) faces.push_back(box.triangle(f));
  EXPECT_EQ(sharp_edge_masks(faces, weld_vertex_ids(faces)), masks);
  EXPECT_THROW(sharp_edge_masks(faces, {}), std::invalid_argument);
  // An open triangle: every edge is a boundary.
  EXPECT_EQ(sharp_edge_masks({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0})})[0], 7);
}

// Welding: equal ids exactly for equal coordinates, -0.0 and 0.0 alike, the smallest difference
// apart.
TEST(WeldVertexIds, AreEqualExactlyForEqualCoordinates) {
  const auto ids = weld_vertex_ids({tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0}),
                                    tri({-0.0, 0, -0.0}, {1, 0, 0}, {0, 0, 1}),
                                    tri({1e-300, 0, 0}, {0, 1, 0}, {0, 0, 1})});
  ASSERT_EQ(ids.size(), 3u);
  EXPECT_EQ(ids[0][0], ids[1][0]);  // -0.0 is 0.0
  EXPECT_EQ(ids[0][1], ids[1][1]);
  EXPECT_EQ(ids[0][2], ids[2][1]);
  EXPECT_EQ(ids[1][2], ids[2][2]);
  EXPECT_NE(ids[0][0], ids[2][0]);  // 1e-300 is not 0
  EXPECT_NE(ids[0][2], ids[1][2]);
  std::set<std::uint32_t> distinct;
  for (const auto& f : ids) distinct.insert(f.begin(), f.end());
  EXPECT_EQ(distinct.size(), 5u);
  EXPECT_EQ(*distinct.rbegin(), 4u) << "ids are 0 .. distinct - 1";
}

}  // namespace
}  // namespace graspcd::mesh_features_test
