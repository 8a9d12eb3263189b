// Mesh hygiene (core/mesh_hygiene.h): welding by coordinate equality, zero-area faces dropped
// exactly, kept faces mapped to their input ids, order and winding kept.
#include "graspcd/core/mesh_hygiene.h"

#include <gtest/gtest.h>

#include "graspcd/core/containment.h"

namespace graspcd {
namespace {

// A unit cube as 12 faces with their own three vertices each (a triangle soup, as MuJoCo stores
// an OBJ mesh), outward winding.
TriangleMesh soup_cube() {
  const std::array<Vec3, 8> c = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                 Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  TriangleMesh m;
  for (const auto& face : f) {
    std::array<std::int32_t, 3> ids{};
    for (int k = 0; k < 3; ++k) {
      ids[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(m.vertices.size());
      m.vertices.push_back(c[static_cast<std::size_t>(face[k])]);
    }
    m.faces.push_back(ids);
  }
  return m;
}

TEST(MeshHygiene, ZeroAreaIsExact) {
  EXPECT_FALSE(is_zero_area(Triangle{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}}));
  EXPECT_TRUE(is_zero_area(Triangle{{Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)}}));
  EXPECT_TRUE(is_zero_area(Triangle{{Vec3(3, 4, 5), Vec3(3, 4, 5), Vec3(3, 4, 5)}}));
  EXPECT_TRUE(is_zero_area(Triangle{{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 2, 3)}}));
  // Nearly collinear: the third point off the line by one ulp of 1 in y.
  const double up = std::nextafter(1.0, 2.0);
  EXPECT_FALSE(is_zero_area(Triangle{{Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2 * up, 0)}}));
}

TEST(MeshHygiene, WeldingASoupRestoresAClosedCube) {
  const TriangleMesh soup = soup_cube();
  HygieneReport r;
  const TriangleMesh cube = clean_mesh(soup, &r);
  EXPECT_EQ(r.input_vertices, 36u);
  EXPECT_EQ(r.welded_vertices, 28u);
  ASSERT_EQ(cube.vertices.size(), 8u);
  ASSERT_EQ(cube.faces.size(), 12u);
  EXPECT_TRUE(r.dropped_faces.empty());
  ASSERT_EQ(r.source_face.size(), 12u);
  // Every face keeps its place and its winding: the same triangle, vertex for vertex.
  for (std::size_t f = 0; f < 12; ++f) {
    EXPECT_EQ(r.source_face[f], static_cast<std::int32_t>(f));
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(cube.triangle(f).v[k], soup.triangle(f).v[k]);
    }
  }
  EXPECT_TRUE(closedness(cube).closed()) << closedness(cube).describe();
}

TEST(MeshHygiene, NegativeZeroWeldsWithZero) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-0.0, 0, -0.0)};
  m.faces = {{0, 1, 2}, {3, 2, 1}};
  HygieneReport r;
  const TriangleMesh out = clean_mesh(m, &r);
  EXPECT_EQ(r.welded_vertices, 1u);
  EXPECT_EQ(out.vertices.size(), 3u);
  EXPECT_EQ(out.faces[1], (std::array<std::int32_t, 3>{0, 2, 1}));
}

TEST(MeshHygiene, ZeroAreaFacesAreDroppedAndTheRestMapBack) {
  TriangleMesh m = soup_cube();
  // Insert degenerate faces at the front, in the middle and at the end: a point, a segment with
  // a repeated vertex, three distinct collinear points.
  const auto add = [&](std::size_t at, Vec3 a, Vec3 b, Vec3 c) {
    const auto n = static_cast<std::int32_t>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), {a, b, c});
    m.faces.insert(m.faces.begin() + static_cast<std::ptrdiff_t>(at), {n, n + 1, n + 2});
  };
  add(0, Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1));
  add(7, Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0));
  add(14, Vec3(0, 0, 0), Vec3(0.5, 0.5, 0.5), Vec3(1, 1, 1));
  ASSERT_EQ(m.faces.size(), 15u);
  HygieneReport r;
  const TriangleMesh out = clean_mesh(m, &r);
  EXPECT_EQ(r.dropped_faces, (std::vector<std::int32_t>{0, 7, 14}));
  ASSERT_EQ(out.faces.size(), 12u);
  ASSERT_EQ(r.source_face.size(), 12u);
  const TriangleMesh cube = soup_cube();
  for (std::size_t f = 0; f < out.faces.size(); ++f) {
    const auto src = static_cast<std::size_t>(r.source_face[f]);
    EXPECT_NE(src, 0u);
    EXPECT_NE(src, 7u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(out.triangle(f).v[k], m.triangle(src).v[k]);   // the map is right
      EXPECT_EQ(out.triangle(f).v[k], cube.triangle(f).v[k]);  // and the order kept
    }
  }
  EXPECT_TRUE(closedness(out).closed()) << closedness(out).describe();

  // The same on the soup of triangles.
  std::vector<Triangle> tris;
  for (std::size_t f = 0; f < m.faces.size(); ++f) tris.push_back(m.triangle(f));
  HygieneReport rs;
  const std::vector<Triangle> kept = drop_zero_area_faces(tris, &rs);
  EXPECT_EQ(rs.dropped_faces, r.dropped_faces);
  EXPECT_EQ(rs.source_face, r.source_face);
  ASSERT_EQ(kept.size(), 12u);
  EXPECT_EQ(kept[6].v[2], tris[8].v[2]);
  EXPECT_EQ(rs.welded_vertices, 0u);
}

}  // namespace
}  // namespace graspcd
