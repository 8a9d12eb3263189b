// The formats load_mesh reads besides OBJ and binary STL (io/mesh_io.h): ASCII STL and OFF (read by
// graspcd), PLY, glTF/GLB and COLLADA (Assimp, in a process of its own). Each is written here from
// one small mesh (by hand for the text formats, by Assimp's exporter for the others) and must load
// as the OBJ of the same mesh does; bad files are one line naming the file.
#include "graspcd/io/mesh_import.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "graspcd/io/mesh_io.h"
#include "helpers/mesh_export.h"
#include "helpers/mesh_load_error.h"
#include "helpers/mesh_text.h"
#include "helpers/temp_dir.h"

namespace graspcd::io {
namespace {

using testing::ascii_ply;
using testing::ascii_stl;
using testing::off_of;

// A box 2 x 3 x 4 with a corner at (1, -1, 0.5): every coordinate exact in single precision.
TriangleMesh box() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back(1 + 2 * (i & 1), -1 + 3 * ((i >> 1) & 1), 0.5 + 4 * ((i >> 2) & 1));
  }
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// The mesh's triangles as corner triples, each turned to start at its smallest corner (winding
// kept), sorted: equal for two meshes of the same faces whatever their vertex order.
using Corner = std::array<double, 3>;
std::vector<std::array<Corner, 3>> triangles_of(const TriangleMesh& m, double scale = 1) {
  std::vector<std::array<Corner, 3>> out;
  for (const auto& f : m.faces) {
    std::array<Corner, 3> t;
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = m.vertices[f[k]];
      t[k] = {scale * v.x(), scale * v.y(), scale * v.z()};
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

class MeshImportTest : public testing::TempDirTest {
 protected:
  // The mesh exported by Assimp in `format` (its exporter id) as `name`.
  std::string exported(const std::string& name, const char* format, const TriangleMesh& m,
                       const aiMatrix4x4& root = aiMatrix4x4()) {
    const std::string path = (dir_ / name).string();
    EXPECT_EQ(testing::export_mesh(m, format, path, root), "");
    return path;
  }
  std::string obj_of(const TriangleMesh& m) {
    const std::string path = (dir_ / "box.obj").string();
    write_obj(path, m);
    return path;
  }
};

using testing::load_error;

TEST_F(MeshImportTest, EveryFormatLoadsAsTheObjOfTheSameMesh) {
  const TriangleMesh m = box();
  MeshStats obj_stats;
  const auto expected = triangles_of(load_mesh(obj_of(m), &obj_stats));
  ASSERT_EQ(expected.size(), 12u);
  ASSERT_TRUE(obj_stats.closedness.closed());
  const std::vector<std::pair<std::string, std::string>> files = {
      {write("box_ascii.stl", ascii_stl(m)), "ASCII STL"},
      {write("box.off", off_of(m)), "OFF"},
      {write("box_ascii.ply", ascii_ply(m)), "PLY"},
      {exported("box_binary.ply", "plyb", m), "PLY"},
      {exported("box.glb", "glb2", m), "glTF"},
      {exported("box.gltf", "gltf2", m), "glTF"},
      {exported("box.dae", "collada", m), "COLLADA"}};
  for (const auto& [path, format] : files) {
    SCOPED_TRACE(path);
    MeshStats stats;
    const TriangleMesh loaded = load_mesh(path, &stats);
    EXPECT_EQ(stats.format, format);
    EXPECT_EQ(triangles_of(loaded), expected);
    EXPECT_TRUE(stats.closedness.closed());
    EXPECT_EQ(stats.zero_area_faces, 0u);
    EXPECT_EQ(stats.in_metres, format == "glTF" || format == "COLLADA");
  }
}

TEST_F(MeshImportTest, GltfNodeTransformsAndColladaUnitsApply) {
  const TriangleMesh m = box();
  // A glTF whose root node moves the mesh by (1, 2, 3) and doubles it: the placed mesh is read.
  aiMatrix4x4 moved;
  aiMatrix4x4::Scaling(aiVector3D(2, 2, 2), moved);
  moved.a4 = 1;
  moved.b4 = 2;
  moved.c4 = 3;
  TriangleMesh placed = m;
  for (Vec3& v : placed.vertices) v = 2 * v + Vec3(1, 2, 3);
  EXPECT_EQ(triangles_of(load_mesh(exported("moved.glb", "glb2", m, moved))), triangles_of(placed));
  // A COLLADA file in millimetres with Z up: its axes are kept and its unit turned to metres.
  const std::string dae = write(
      "mm.dae",
      "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" "
      "version=\"1.4.1\"><asset><unit name=\"millimeter\" meter=\"0.001\"/>"
      "<up_axis>Z_UP</up_axis></asset><library_geometries><geometry id=\"g\"><mesh>"
      "<source id=\"p\"><float_array id=\"pa\" count=\"9\">0 0 0 10 0 0 0 20 30</float_array>"
      "<technique_common><accessor source=\"#pa\" count=\"3\" stride=\"3\"><param name=\"X\" "
      "type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/>"
      "</accessor></technique_common></source><vertices id=\"v\"><input semantic=\"POSITION\" "
      "source=\"#p\"/></vertices><triangles count=\"1\"><input semantic=\"VERTEX\" "
      "source=\"#v\" offset=\"0\"/><p>0 1 2</p></triangles></mesh></geometry>"
      "</library_geometries><library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
      "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes><scene>"
      "<instance_visual_scene url=\"#s\"/></scene></COLLADA>\n");
  const TriangleMesh tri = load_mesh(dae);
  ASSERT_EQ(tri.vertices.size(), 3u);
  // (Assimp computes in single precision: 20 * 0.001 to within a float's rounding.)
  constexpr double kFloat = 1.0 / (1 << 22);
  EXPECT_NEAR(tri.vertices[1].x(), 0.01, 0.01 * kFloat);
  EXPECT_NEAR(tri.vertices[2].y(), 0.02, 0.02 * kFloat);
  EXPECT_NEAR(tri.vertices[2].z(), 0.03, 0.03 * kFloat);
  EXPECT_EQ(tri.vertices[2].x(), 0);
}

TEST_F(MeshImportTest, OffPolygonsAndSeveralSolidsAreOneMesh) {
  // A square as one OFF quad: two triangles, a fan from its first vertex.
  const std::string quad = write("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  const TriangleMesh q = load_mesh(quad);
  ASSERT_EQ(q.faces.size(), 2u);
  EXPECT_EQ(q.faces[1], (std::array<std::int32_t, 3>{0, 2, 3}));
  // Two solids in an ASCII STL are concatenated (as an OBJ's objects are).
  TriangleMesh one;
  one.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  one.faces = {{0, 1, 2}};
  TriangleMesh two = one;
  for (Vec3& v : two.vertices) v.z() = 1;
  const std::string both = write("two.stl", ascii_stl(one) + ascii_stl(two));
  EXPECT_EQ(load_mesh(both).faces.size(), 2u);
}

TEST_F(MeshImportTest, ZeroAreaFacesAreDroppedInEveryFormat) {
  // The box plus one face along an edge (vertices 0, 1 and their midpoint): dropped, counted.
  TriangleMesh m = box();
  m.vertices.emplace_back(2, -1, 0.5);
  m.faces.push_back({0, 8, 1});
  for (const std::string& path :
       {write("flat.stl", ascii_stl(m)), write("flat.off", off_of(m)),
        write("flat.ply", ascii_ply(m)), exported("flat.glb", "glb2", m)}) {
    SCOPED_TRACE(path);
    MeshStats stats;
    const TriangleMesh loaded = load_mesh(path, &stats);
    EXPECT_EQ(loaded.faces.size(), 12u);
    EXPECT_EQ(stats.zero_area_faces, 1u);
    ASSERT_EQ(mesh_warnings(path, stats, true).size(), 1u);
  }
}

TEST_F(MeshImportTest, BadFilesAreOneLineNamingTheFile) {
  const auto one_line = [](const std::string& message, const std::string& path) {
    EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  const std::string nan_stl =
      write("nan.stl",
            "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\n"
            "endloop\nendfacet\nendsolid x\n");
  EXPECT_EQ(load_error(nan_stl).rfind(nan_stl + ":5: facet 1 vertex 2: ", 0), 0u)
      << load_error(nan_stl);
  const std::string two_corners = write(
      "two.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n");
  EXPECT_EQ(load_error(two_corners), two_corners + ":6: facet 1: 2 vertices (a facet needs 3)");
  const std::string cut = write("cut.stl", "solid x\nfacet normal 0 0 1\nouter loop\n");
  EXPECT_EQ(load_error(cut), cut + ":2: ASCII STL: the file ends inside facet 1");

  const std::string off_range = write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_EQ(load_error(off_range),
            off_range + ":6: face 0: vertex index 3 out of range (3 vertices, counted from 0)");
  const std::string off_short = write("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n");
  EXPECT_EQ(load_error(off_short), off_short + ": the file ends at vertex 2 (3 declared)");
  const std::string not_off = write("not.off", "PLY\n");
  EXPECT_EQ(load_error(not_off), not_off + ":1: expected 'OFF' first, found \"PLY\"");

  // PLY: a truncated file, and a face of two vertices (a line).
  std::string ply = ascii_ply(box());
  const std::string truncated = write("truncated.ply", ply.substr(0, ply.size() / 2));
  one_line(load_error(truncated), truncated);
  EXPECT_NE(load_error(truncated), "");
  const std::string line = write("line.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 1\n"
                                 "property list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  one_line(load_error(line), line);
  EXPECT_NE(load_error(line), "");
  // glTF: a buffer file that is missing; garbage in a .glb.
  const std::string gltf = exported("lost.gltf", "gltf2", box());
  std::filesystem::remove(dir_ / "lost.bin");
  one_line(load_error(gltf), gltf);
  EXPECT_NE(load_error(gltf), "");
  const std::string glb = write("garbage.glb", std::string("glTF\x02\x00\x00\x00garbage", 15));
  one_line(load_error(glb), glb);
  EXPECT_NE(load_error(glb), "");
}

// graspcd reads while other threads run (the progress line's, a study's workers): the reader's
// process must not depend on what they hold at the fork. A thread allocating without pause held
// the sanitizer's allocator lock at some fork, and a reader that ran Assimp in the forked child
// waited for it until the import timeout.
TEST_F(MeshImportTest, FilesReadWhileAnotherThreadAllocatesAreRead) {
  const std::string ply = write("box.ply", ascii_ply(box()));
  std::atomic<bool> stop{false};
  std::thread allocator([&stop] {
    while (!stop) {
      std::vector<std::unique_ptr<int>> held;
      for (int i = 0; i < 64; ++i) held.push_back(std::make_unique<int>(i));
    }
  });
  set_import_timeout(10);
  int failed = 0;
  std::string first_error;
  for (int i = 0; i < 40; ++i) {
    const ImportedMesh read = import_with_assimp(ply, "ply");
    if (!read.error.empty() || read.mesh.faces.size() != 12) {
      if (failed++ == 0) first_error = read.error;
    }
  }
  set_import_timeout(kImportTimeout);
  stop = true;
  allocator.join();
  EXPECT_EQ(failed, 0) << first_error;
}

// graspcd linked into a shared library that another program loaded (the test's executable here,
// a Python interpreter or a simulator elsewhere): that program run again would not read the file,
// so the reader is a forked child; the file is read, and a bad one is still one error line.
TEST_F(MeshImportTest, AProgramThatLoadedGraspcdAsALibraryReadsToo) {
  void* module = dlopen(GRASPCD_READER_MODULE, RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(module, nullptr) << dlerror();
  using FacesOf = long (*)(const char*, char*, unsigned long);
  const auto faces_of = reinterpret_cast<FacesOf>(dlsym(module, "graspcd_test_faces_of"));
  ASSERT_NE(faces_of, nullptr) << dlerror();
  char error[512] = "";
  EXPECT_EQ(faces_of(write("box.ply", ascii_ply(box())).c_str(), error, sizeof error), 12) << error;
  const std::string bad = write("bad.glb", std::string("glTF\x02\x00\x00\x00garbage", 15));
  EXPECT_EQ(faces_of(bad.c_str(), error, sizeof error), -1);
  EXPECT_EQ(std::string(error).rfind(bad + ": ", 0), 0u) << error;
  dlclose(module);
#if !GRASPCD_SANITIZED
  // A program without graspcd of its own, Python, loads the library and reads through it (in the
  // sanitizer build the library needs the sanitizer's runtime first, which Python has not).
  const std::string host =
      write("host.py",
            "import ctypes, sys\n"
            "lib = ctypes.CDLL(sys.argv[1])\n"
            "lib.graspcd_test_faces_of.restype = ctypes.c_long\n"
            "error = ctypes.create_string_buffer(512)\n"
            "print(lib.graspcd_test_faces_of(sys.argv[2].encode(), error, 512),"
            " error.value.decode())\n");
  const std::string printed = (dir_ / "printed.txt").string();
  const std::string command = "/usr/bin/python3 '" + host + "' '" + GRASPCD_READER_MODULE + "' '" +
                              (dir_ / "box.ply").string() + "' < /dev/null > '" + printed + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(printed);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()),
            "12 \n");
#endif
}

// Assimp 5.2.5 loops forever on a PLY whose header ends early: its child process is killed after
// the import timeout (shortened here) and the file is one error line. A file that is not what its
// extension says is refused before Assimp (which would try its other readers on it: a ".gltf"
// holding an OFF text made it abort in the fuzzer).
TEST_F(MeshImportTest, AHangOfAssimpOrAFileNotOfItsExtensionIsOneErrorLine) {
  set_import_timeout(1);
  const std::string hang = write("hang.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  const std::string error = load_error(hang);
  set_import_timeout(kImportTimeout);
  EXPECT_EQ(error, hang + ": the import library did not finish reading it in 1 s");
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string gltf = write("off.gltf", off);
  EXPECT_EQ(load_error(gltf),
            gltf + ": not a glTF file (a .gltf file is a JSON object, starting with '{')");
  const std::string glb = write("off.glb", off);
  EXPECT_EQ(load_error(glb), glb + ": not a GLB file (it does not start with 'glTF')");
  const std::string ply = write("off.ply", off);
  EXPECT_EQ(load_error(ply), ply + ":1: not a PLY file (it does not start with 'ply')");
  const std::string dae = write("off.dae", off);
  EXPECT_EQ(load_error(dae), dae + ": not a COLLADA file (no <COLLADA> in its first 4096 bytes)");
}

}  // namespace
}  // namespace graspcd::io
