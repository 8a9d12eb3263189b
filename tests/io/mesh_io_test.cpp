#include "graspcd/io/mesh_io.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "helpers/mesh_load_error.h"
#include "helpers/temp_dir.h"

namespace graspcd::io {
namespace {

namespace fs = std::filesystem;

// A fresh temporary folder per test, removed afterwards.
class MeshIoTest : public testing::TempDirTest {
 protected:
  // A binary STL of the given triangles (9 floats each), with the given header text.
  std::string write_stl(const std::string& name, const std::vector<std::array<float, 9>>& tris,
                        const std::string& header = "graspcd test") {
    std::string bytes(80, '\0');
    bytes.replace(0, header.size(), header);
    const auto append_u32 = [&](std::uint32_t x) {
      for (int i = 0; i < 4; ++i) bytes += static_cast<char>((x >> (8 * i)) & 0xff);
    };
    const auto append_f32 = [&](float f) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &f, sizeof(bits));
      append_u32(bits);
    };
    append_u32(static_cast<std::uint32_t>(tris.size()));
    for (const auto& t : tris) {
      for (int i = 0; i < 3; ++i) append_f32(0.0f);  // normal, ignored
      for (float f : t) append_f32(f);
      bytes += std::string(2, '\0');  // attribute byte count
    }
    return write(name, bytes);
  }
};

using testing::load_error;

const char* const kTetrahedron =
    "# a tetrahedron\n"
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0 0.5 0\n"
    "v 0 0 -2.25\n"
    "f 1 3 2\n"
    "f 1 2 4\n"
    "f 1 4 3\n"
    "f 2 3 4\n";

TEST_F(MeshIoTest, LoadsAnObjTetrahedron) {
  const TriangleMesh mesh = load_mesh(write("tet.obj", kTetrahedron));
  ASSERT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.faces.size(), 4u);
  EXPECT_EQ(mesh.vertices[2], Vec3(0, 0.5, 0));
  EXPECT_EQ(mesh.vertices[3], Vec3(0, 0, -2.25));
  EXPECT_EQ(mesh.faces[0], (std::array<std::int32_t, 3>{0, 2, 1}));
  EXPECT_EQ(mesh.faces[3], (std::array<std::int32_t, 3>{1, 2, 3}));
}

TEST_F(MeshIoTest, ObjExtensionIsCaseInsensitive) {
  EXPECT_EQ(load_mesh(write("TET.OBJ", kTetrahedron)).faces.size(), 4u);
}

TEST_F(MeshIoTest, ObjPolygonsAreTriangulatedAndObjectsConcatenated) {
  const std::string obj =
      "o square\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
      "o triangle\n"
      "v 5 5 5\nv 6 5 5\nv 5 6 5\n"
      "f -3 -2 -1\n";  // relative indices: the last three vertices
  const TriangleMesh mesh = load_mesh(write("two.obj", obj));
  ASSERT_EQ(mesh.vertices.size(), 7u);
  ASSERT_EQ(mesh.faces.size(), 3u);  // the square as 2 triangles, then the triangle
  EXPECT_EQ(mesh.faces[2], (std::array<std::int32_t, 3>{4, 5, 6}));
  for (int f = 0; f < 2; ++f) {
    for (int k = 0; k < 3; ++k) EXPECT_LT(mesh.faces[f][k], 4);
  }
}

TEST_F(MeshIoTest, ObjCoordinatesAreDoubles) {
  // A float build would give 123456792 and 1e-20 * (1 +- 6e-8). tinyobjloader's own number parser
  // is not correctly rounded (it is off from strtod by a few ulps on many decimals), so the check
  // is to well within float precision, not to the last bit.
  const TriangleMesh mesh = load_mesh(write("d.obj",
                                            "v 1e-20 0 0\nv 0 1 0\nv 0 0 123456789.125\n"
                                            "f 1 2 3\n"));
  EXPECT_NEAR(mesh.vertices[2][2], 123456789.125, 1e-6);
  EXPECT_NEAR(mesh.vertices[0][0], 1e-20, 1e-33);
}

// docs/design.md "Semantics": mesh loading drops zero-area faces with a warning; the loaded faces
// map back to the file's.
TEST_F(MeshIoTest, ZeroAreaFacesAreDroppedWithAWarningAndFacesMapBack) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\n"
      "f 1 2 3\n"  // collinear
      "f 1 2 4\n"
      "f 1 1 1\n"  // a point
      "f 2 3 4\n";
  MeshStats stats;
  const std::string path = write("flat.obj", obj);
  const TriangleMesh mesh = load_mesh(path, &stats);
  ASSERT_EQ(mesh.faces.size(), 2u);
  EXPECT_EQ(stats.zero_area_faces, 2u);
  EXPECT_EQ(stats.dropped_faces, (std::vector<std::int32_t>{0, 2}));
  EXPECT_EQ(stats.source_face, (std::vector<std::int32_t>{1, 3}));
  EXPECT_EQ(mesh.faces[0], (std::array<std::int32_t, 3>{0, 1, 3}));
  EXPECT_EQ(mesh.faces[1], (std::array<std::int32_t, 3>{1, 2, 3}));
  const std::vector<std::string> w = mesh_warnings(path, stats);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0], path +
                      ": dropped 2 zero-area faces (faces 1, 3 counted from 1 in the file's order; "
                      "each spans a segment or a point)");
  EXPECT_EQ(w[1].rfind(path + ": the mesh is not closed: ", 0), 0u) << w[1];
  // For commands without a containment check (meshpair) only the dropped faces are news.
  EXPECT_EQ(mesh_warnings(path, stats, true), std::vector<std::string>{w[0]});
  // A file of zero-area faces only is an error.
  const std::string flat = write("flatter.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_EQ(load_error(flat),
            flat + ": every face has zero area (1 faces, each a segment or a point)");
}

// Duplicate vertices are welded (a file with a vertex per face corner, as exporters and MuJoCo
// write them), restoring a closed surface; a clean closed mesh loads without any warning.
TEST_F(MeshIoTest, DuplicateVerticesAreWeldedWithAWarning) {
  std::string soup;
  const char* corners[4] = {"0 0 0", "1 0 0", "0 1 0", "0 0 1"};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& f : faces) {
    for (int k = 0; k < 3; ++k) soup += std::string("v ") + corners[f[k]] + "\n";
  }
  soup += "f 1 2 3\nf 4 5 6\nf 7 8 9\nf 10 11 12\n";
  MeshStats stats;
  const std::string path = write("soup.obj", soup);
  const TriangleMesh mesh = load_mesh(path, &stats);
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(stats.welded_vertices, 8u);
  EXPECT_TRUE(stats.closedness.closed()) << stats.closedness.describe();
  EXPECT_EQ(mesh_warnings(path, stats),
            std::vector<std::string>{path + ": welded 8 duplicate vertices (12 in the file, 4 "
                                            "distinct)"});
  const std::string clean = write("clean.obj", kTetrahedron);
  MeshStats clean_stats;
  load_mesh(clean, &clean_stats);
  EXPECT_TRUE(mesh_warnings(clean, clean_stats).empty());
}

// MuJoCo 2.2 keeps only the first object of an OBJ file; graspcd reads them all and warns.
TEST_F(MeshIoTest, SeveralObjectsInAnObjAreWarnedAbout) {
  const std::string path = write("two.obj",
                                 "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                                 "o  second  \nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n");
  MeshStats stats;
  const TriangleMesh mesh = load_mesh(path, &stats);
  EXPECT_EQ(mesh.faces.size(), 2u);
  EXPECT_EQ(stats.obj_objects, (std::vector<std::string>{"first", "second"}));
  const std::vector<std::string> w = mesh_warnings(path, stats);
  ASSERT_EQ(w.size(), 2u);  // open, and two objects
  EXPECT_EQ(w[1], path +
                      ": 2 objects ('first', 'second'): graspcd reads them all, but MuJoCo 2.2 "
                      "keeps only the first ('first'); merge them into one object for a scene");
}

TEST_F(MeshIoTest, ObjErrors) {
  const std::string bad_index = write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_EQ(load_error(bad_index),
            bad_index + ":4: face 1: vertex index 9 out of range (the file has 3 vertices)");

  const std::string bad_quad = write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 7\n");
  EXPECT_EQ(load_error(bad_quad),
            bad_quad + ":4: face 1: vertex index 7 out of range (the file has 3 vertices)");
  const std::string before = write("before.obj", "v 0 0 0\nf -1 -2 -3\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(load_error(before), before +
                                    ":2: face 1: vertex index -2 points before the first vertex "
                                    "(1 vertices precede it)");
  const std::string word = write("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x/1\n");
  EXPECT_EQ(load_error(word), word + ":4: face 1: bad vertex index \"x/1\"");

  const std::string zero = write("zero.obj", "v 0 0 0\nv 1 0 0\nf 0 1 2\n");
  EXPECT_EQ(load_error(zero), zero + ":3: face 1: vertex index 0 (OBJ indices start at 1)");

  const std::string no_faces = write("nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(load_error(no_faces), no_faces + ": the mesh has no faces");

  const std::string empty = write("empty.obj", "");
  EXPECT_EQ(load_error(empty), empty + ": the mesh has no faces");

  const std::string two = write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  EXPECT_EQ(load_error(two), two + ":3: face 1: 2 vertices (a face needs 3)");

  const std::string huge = write("huge.obj", "v 0 0 0\nv 1e400 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(load_error(huge), huge + ":2: vertex 2: number \"1e400\" overflows a double");

  const std::string tiny = write("tiny.obj", "v 0 0 0\nv 1 0 0\nv 0 1e-60 0\nf 1 2 3\n");
  EXPECT_EQ(load_error(tiny), tiny +
                                  ":3: vertex 3: number \"1e-60\" is outside the exact-arithmetic "
                                  "range (0 or 1e-50 <= |x| <= 1e+50)");

  const std::string big = write("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -3e55\nf 1 2 3\n");
  EXPECT_EQ(load_error(big), big +
                                 ":3: vertex 3: number \"-3e55\" is outside the exact-arithmetic "
                                 "range (0 or 1e-50 <= |x| <= 1e+50)");
}

// tinyobjloader alone reads "nan" and other words as 0 and "1e999" as inf, without a line; the
// loader reads every vertex line with the command line's grammar first (mesh_io.h).
// A UTF-8 byte-order mark hid the first vertex from both OBJ readers, and every
// face then named the next vertex (meshpair answered "1 11" where the file without it gives "0 0").
TEST_F(MeshIoTest, ObjByteOrderMarkIsRefusedAtLineOne) {
  const std::string cube =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string bom = write("bom.obj", "\xEF\xBB\xBF" + cube);
  EXPECT_EQ(load_error(bom), bom + ":1: UTF-8 byte-order mark");
  try {
    check_mesh_file(bom);
    ADD_FAILURE() << "check_mesh_file accepted a byte-order mark";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), bom + ":1: UTF-8 byte-order mark");
  }
  EXPECT_EQ(load_mesh(write("plain.obj", cube)).faces.size(), 4u);
}

// check_mesh_file: what a scene's mesh must pass before MuJoCo reads it (MuJoCo reads "nan" as 0).
TEST_F(MeshIoTest, CheckMeshFileRefusesWhatMujocoWouldMisread) {
  const std::string nan = write("nan.obj", "v 0 0 0\nv nan 1 1\nv 0 1 0\nf 1 2 3\n");
  try {
    check_mesh_file(nan);
    ADD_FAILURE() << "check_mesh_file accepted nan";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), nan);
    EXPECT_EQ(e.line(), 2u);
  }
  check_mesh_file(write("ok.obj", "v 0 0 0\nv 1 1 1\nv 0 1 0\nf 1 2 3\n"));
  check_mesh_file(write("other.msh", "not read here"));
}

TEST_F(MeshIoTest, ObjNonFiniteCoordinatesAreErrorsAtTheirLine) {
  const std::string head = "# comment\nv 0 0 0\nv 1 0 0\n";
  const std::string tail = "f 1 2 3\n";
  for (const std::string token : {"nan", "NaN", "-nan", "inf", "-Infinity", "INF"}) {
    const std::string path = write("nan.obj", head + "v 0 " + token + " 0\n" + tail);
    EXPECT_EQ(load_error(path), path + ":4: vertex 3: non-finite number \"" + token +
                                    "\" (nan and inf are not accepted)");
  }
  const std::string over = write("over.obj", head + "  v\t1e999 0 0\n" + tail);
  EXPECT_EQ(load_error(over), over + ":4: vertex 3: number \"1e999\" overflows a double");
  const std::string word = write("word.obj", head + "v 0 zero 0\n" + tail);
  EXPECT_EQ(load_error(word), word + ":4: vertex 3: malformed number \"zero\"");
  const std::string comma = write("comma.obj", head + "v 0 1,5 0\n" + tail);
  EXPECT_EQ(load_error(comma), comma + ":4: vertex 3: malformed number \"1,5\"");
  const std::string hex = write("hex.obj", head + "v 0 0x1p3 0\n" + tail);
  EXPECT_EQ(load_error(hex),
            hex + ":4: vertex 3: hexadecimal number \"0x1p3\" (OBJ files take decimals)");
  const std::string two = write("two.obj", head + "v 0 1\n" + tail);
  EXPECT_EQ(load_error(two), two +
                                 ":4: vertex 3: expected x y z (optionally followed by w, or by "
                                 "r g b), got 2 numbers");
  // A decimal that tinyobjloader's parser loses (its digits scaled by 10^-331, which underflows)
  // though strtod reads it as 1e-31: caught by comparing the two readings.
  const std::string lost =
      write("lost.obj", head + "v 0 0." + std::string(330, '0') + "1e300 0\n" + tail);
  EXPECT_EQ(
      load_error(lost).rfind(lost + ":4: vertex 3: the OBJ parser read coordinate 2 as 0 where "
                                    "strtod reads 1",
                             0),
      0u)
      << load_error(lost);
  // A colour, a weight and a trailing comment are fine; "vn" and "vt" lines are not vertices.
  const TriangleMesh mesh = load_mesh(write("fine.obj",
                                            "v 0 0 0 1 0.5 0\nv 1 0 0 1\nv 0 1 0 # third\n"
                                            "vn nan 0 1\nvt inf 0\nf 1 2 3\n"));
  EXPECT_EQ(mesh.vertices[2], Vec3(0, 1, 0));
}

TEST_F(MeshIoTest, FileErrors) {
  const std::string missing = (dir_ / "missing.obj").string();
  EXPECT_EQ(load_error(missing), missing + ": cannot open: No such file or directory");
  const std::string folder = (dir_ / "folder.obj").string();
  fs::create_directory(folder);
  EXPECT_EQ(load_error(folder), folder + ": not a regular file (a folder)");
  const std::string ply = write("mesh.3ds", "ply\n");
  EXPECT_EQ(load_error(ply), ply +
                                 ": unknown mesh format (expected .obj, .stl, .ply, .off, .gltf, "
                                 ".glb or .dae)");
  const std::string none = write("mesh", kTetrahedron);
  EXPECT_EQ(load_error(none), none +
                                  ": unknown mesh format (expected .obj, .stl, .ply, .off, .gltf, "
                                  ".glb or .dae)");
}

TEST_F(MeshIoTest, LoadsABinaryStlWeldingItsVertices) {
  // A unit square as two triangles sharing an edge; the header even begins with "solid".
  const std::string path =
      write_stl("square.stl", {{0, 0, 0, 1, 0, 0, 1, 1, 0.5f}, {0, 0, 0, 1, 1, 0.5f, 0, 1, 0}},
                "solid but binary");
  MeshStats stats;
  const TriangleMesh mesh = load_mesh(path, &stats);
  ASSERT_EQ(mesh.faces.size(), 2u);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.faces[0], (std::array<std::int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.faces[1], (std::array<std::int32_t, 3>{0, 2, 3}));
  EXPECT_EQ(mesh.vertices[2], Vec3(1, 1, 0.5));
  EXPECT_EQ(stats.zero_area_faces, 0u);
  EXPECT_EQ(stats.welded_vertices, 2u);  // STL gives every triangle its own three vertices
  // Floats widen to doubles exactly.
  const std::string fine = write_stl("fine.STL", {{0.1f, 0, 0, 1, 0, 0, 0, 1, 0}});
  EXPECT_EQ(load_mesh(fine).vertices[0][0], static_cast<double>(0.1f));
}

TEST_F(MeshIoTest, StlErrors) {
  const std::string ascii = write("ascii.stl",
                                  "solid cube\n  facet normal 0 0 1\n    outer loop\n"
                                  "      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
                                  "    endloop\n  endfacet\nendsolid cube\n");
  // An ASCII STL is read (mesh_import_test.cpp tests it); one without facets has no faces.
  EXPECT_EQ(load_error(ascii), "");
  const std::string short_ascii = write("short.stl", "solid x\nendsolid x\n");
  EXPECT_EQ(load_error(short_ascii), short_ascii + ": the mesh has no faces");

  const std::string tiny = write("tiny.stl", std::string(40, 'x'));
  EXPECT_EQ(load_error(tiny),
            tiny + ": too short for a binary STL (40 bytes; header and count take 84)");

  // One triangle, with a byte cut off the end.
  const std::string good = write_stl("good.stl", {{0, 0, 0, 1, 0, 0, 0, 1, 0}});
  std::string bytes;
  {
    std::ifstream in(good, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string cut = write("cut.stl", bytes.substr(0, bytes.size() - 1));
  EXPECT_EQ(load_error(cut), cut +
                                 ": binary STL size mismatch: the header says 1 triangles (134 "
                                 "bytes) but the file has 133 bytes");

  EXPECT_EQ(load_error(write_stl("empty.stl", {})),
            (dir_ / "empty.stl").string() + ": the mesh has no faces");

  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::string bad =
      write_stl("nan.stl", {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, nan, 0, 0, 1, 0}});
  EXPECT_EQ(load_error(bad),
            bad + ": triangle 2 vertex 2 has coordinate nan (coordinates must be finite)");
  const float inf = std::numeric_limits<float>::infinity();
  const std::string infinite = write_stl("inf.stl", {{0, 0, -inf, 1, 0, 0, 0, 1, 0}});
  EXPECT_EQ(load_error(infinite),
            infinite + ": triangle 1 vertex 1 has coordinate -inf (coordinates must be finite)");
}

TEST(MeshIoModels, LoadsTheCubeCup) {
  const fs::path path = fs::path(GRASPCD_MODELS_DIR) / "objects" / "mujoco" / "cube_cup.obj";
  if (!fs::exists(path)) GTEST_SKIP() << "model not found: " << path;
  MeshStats stats;
  const TriangleMesh mesh = load_mesh(path.string(), &stats);
  // 48 vertex lines, 16 distinct positions: welded on load.
  EXPECT_EQ(mesh.vertices.size(), 16u);
  EXPECT_EQ(stats.welded_vertices, 32u);
  EXPECT_EQ(mesh.faces.size(), 28u);
  EXPECT_EQ(stats.zero_area_faces, 0u);
  Vec3 lo = mesh.vertices[0];
  Vec3 hi = mesh.vertices[0];
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  EXPECT_EQ(lo, Vec3(-0.05, -0.05, 0.0));
  EXPECT_EQ(hi, Vec3(0.05, 0.05, 0.1));
}

}  // namespace
}  // namespace graspcd::io
