// A user's object in any format graspcd reads (io/mesh_io.h), through the executable: a PLY, a GLB
// and an ASCII STL grasped with `grasp --object` (a format MuJoCo 2.2 cannot read is converted to
// an OBJ beside the scene) and compared by `meshpair`; --scale on meshpair and decompose; a
// millimetre file refused with the units hint on the same line; decompose's warning when the
// pieces lose volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "graspcd/core/geometry.h"
#include "helpers/command_test.h"
#include "helpers/mesh_export.h"
#include "helpers/mesh_text.h"

namespace graspcd::testing {
namespace {

namespace fs = std::filesystem;

// A closed box 50 x 40 x 60 mm in millimetres, off the origin (x 100..150, z 10..70).
TriangleMesh user_box() {
  TriangleMesh m;
  m.vertices = {Vec3(100, -20, 10), Vec3(150, -20, 10), Vec3(150, 20, 10), Vec3(100, 20, 10),
                Vec3(100, -20, 70), Vec3(150, -20, 70), Vec3(150, 20, 70), Vec3(100, 20, 70)};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
             {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return m;
}

// A 30 mm cube at the origin, in millimetres.
TriangleMesh cube30() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back(30 * (i & 1), 30 * ((i >> 1) & 1), 30 * ((i >> 2) & 1));
  }
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

class ObjectFormats : public CommandTest {
 protected:
  // graspcd ARGS with stdout kept: {exit code, stdout, stderr}.
  struct Run {
    int exit_code;
    std::string out;
    std::string err;
  };
  Run graspcd_out(const std::string& args) {
    const fs::path out = dir_ / "stdout.txt";
    const Outcome r =
        run(std::string("{ '") + GRASPCD_EXE + "' " + args + " > '" + out.string() + "'; }");
    return {r.exit_code, read_file(out), r.err};
  }
  // The three files of the user's box: PLY (ASCII), GLB (Assimp's exporter), ASCII STL.
  std::vector<std::string> box_files() {
    const TriangleMesh m = user_box();
    const std::string glb = (dir_ / "box_glb.glb").string();
    EXPECT_EQ(export_mesh(m, "glb2", glb), "");
    return {write("box_ply.ply", ascii_ply(m)), glb, write("box_stl.stl", ascii_stl(m))};
  }
};

TEST_F(ObjectFormats, GraspObjectReadsPlyGlbAndAsciiStlConvertingThemForMuJoCo) {
  for (const std::string& file : box_files()) {
    SCOPED_TRACE(file);
    const fs::path scene = dir_ / ("scene_" + fs::path(file).stem().string());
    const Run r =
        graspcd_out("grasp --object '" + file +
                    "' --scale 0.001 --max-steps 2 --json --write-scene '" + scene.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["object"]["file"], file);
    const std::array<double, 3> size = doc["object"]["size"].get<std::array<double, 3>>();
    EXPECT_NEAR(size[0], 0.05, 1e-12);
    EXPECT_NEAR(size[1], 0.04, 1e-12);
    EXPECT_NEAR(size[2], 0.06, 1e-12);
    // MuJoCo 2.2 reads OBJ and binary STL only: the scene names the converted OBJ, which moves
    // with the scene (STEM.meshes/object/), and not the user's file.
    const std::string stem = fs::path(file).stem().string();
    const std::string xml = read_file(scene / (stem + ".xml"));
    // (the scene's meshdir is STEM.meshes/)
    EXPECT_NE(xml.find("file=\"object/" + stem + ".converted.obj\""), std::string::npos) << xml;
    EXPECT_EQ(xml.find(fs::path(file).filename().string() + '"'), std::string::npos) << xml;
    EXPECT_TRUE(fs::exists(scene / (stem + ".meshes") / "object" / (stem + ".converted.obj")));
  }
}

TEST_F(ObjectFormats, MeshpairAnswersAsForTheObjAndScalesBothMeshes) {
  const std::string obj = (dir_ / "box.obj").string();
  {
    std::ostringstream text;
    const TriangleMesh m = user_box();
    for (const Vec3& v : m.vertices) text << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& f : m.faces)
      text << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
    write("box.obj", text.str());
  }
  // B shifted along x by 40 (overlapping) and by 60 (apart) file units; with --scale 0.001 the
  // same poses in metres.
  write("poses_mm.txt", "1 0 0 0 1 0 0 0 1 40 0 0\n1 0 0 0 1 0 0 0 1 60 0 0\n");
  write("poses_m.txt", "1 0 0 0 1 0 0 0 1 0.04 0 0\n1 0 0 0 1 0 0 0 1 0.06 0 0\n");
  const auto answers = [&](const std::string& a, const std::string& b, const std::string& extra) {
    const Run r = graspcd_out("meshpair '" + a + "' '" + b + "' " + extra + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::pair<bool, int>> out;
    if (r.exit_code != 0) return out;
    const nlohmann::json doc = nlohmann::json::parse(r.out);
    for (const auto& x : doc["answers"]) {
      out.emplace_back(x["intersect"].get<bool>(), x["pairs"].get<int>());
    }
    return out;
  };
  const std::string mm = "--poses '" + (dir_ / "poses_mm.txt").string() + "'";
  const std::string m = "--poses '" + (dir_ / "poses_m.txt").string() + "' --scale 0.001";
  const auto expected = answers(obj, obj, mm);
  ASSERT_EQ(expected.size(), 2u);
  EXPECT_TRUE(expected[0].first);
  EXPECT_FALSE(expected[1].first);
  EXPECT_EQ(answers(obj, obj, m), expected);
  for (const std::string& file : box_files()) {
    SCOPED_TRACE(file);
    EXPECT_EQ(answers(file, obj, mm), expected);
    EXPECT_EQ(answers(obj, file, m), expected);
  }
}

TEST_F(ObjectFormats, AMillimetreFileRefusedSaysItsUnitsOnTheSameLine) {
  const std::string ply = box_files()[0];
  const Outcome r = graspcd("grasp --object '" + ply + "' --max-steps 2");
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind(ply + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("lies wholly inside the object"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("; the object is 60 m across at --scale 1: is the file in millimetres? "
                       "try --scale 0.001"),
            std::string::npos)
      << r.err;
  // A bad file is one line naming it (Assimp's reader: a face of two vertices).
  const std::string line = write("line.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 1\n"
                                 "property list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  const Outcome bad = graspcd("grasp --object '" + line + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, line + ": mesh 1 face 1: 2 vertices (a point or a line; a face needs 3)\n");
}

TEST_F(ObjectFormats, DecomposeScalesAndWarnsWhenThePiecesLoseVolume) {
  const std::string cube = write("cube.off", off_of(cube30()));
  // 16 pieces of a cube come out as thin slabs along its faces: most of the volume is lost.
  const Run slabs = graspcd_out("decompose '" + cube + "' --out '" + (dir_ / "d16").string() +
                                "' --pieces 16 --scale 0.001 --json");
  ASSERT_EQ(slabs.exit_code, 0) << slabs.err;
  const nlohmann::json doc = nlohmann::json::parse(slabs.out);
  EXPECT_NEAR(doc["volume"]["original"].get<double>(), 2.7e-5, 1e-15);
  const double fraction = doc["volume"]["added_fraction"].get<double>();
  ASSERT_LT(fraction, -0.1);
  bool warned = false;
  for (const auto& w : doc["warnings"]) {
    warned |= w.dump().find("decompose_volume_lost") != std::string::npos;
  }
  EXPECT_TRUE(warned) << doc["warnings"].dump();
  EXPECT_NE(slabs.err.find(cube + ": the pieces hold"), std::string::npos) << slabs.err;
  // One piece is the cube itself: nothing lost, no warning; without --scale, file units.
  const Run one = graspcd_out("decompose '" + cube + "' --out '" + (dir_ / "d1").string() +
                              "' --pieces 1 --json");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const nlohmann::json doc1 = nlohmann::json::parse(one.out);
  EXPECT_NEAR(doc1["volume"]["original"].get<double>(), 27000, 1e-9);
  EXPECT_EQ(one.err.find("decompose_volume_lost"), std::string::npos) << one.err;
  EXPECT_EQ(one.err.find("less volume"), std::string::npos) << one.err;
}

// --fit leaves each hand the margin it closes on (docs/objects.md, "--fit and each hand's
// margin"): a cube fitted to the Shadow hand's whole room (3.4 cm) penetrates a finger at the
// start and was refused; at the hand's fraction it starts (and is gripped: measured in the docs).
TEST_F(ObjectFormats, FitLeavesTheShadowHandItsMargin) {
  if (!fs::exists(fs::path(GRASPCD_MODELS_DIR) / "hands/shadow_hand/right_hand.xml")) {
    GTEST_SKIP() << "real models not found at " << GRASPCD_MODELS_DIR;
  }
  TriangleMesh cube = cube30();
  const std::string file = write("cube.off", off_of(cube));
  const Run r =
      graspcd_out("grasp --object '" + file + "' --fit --hand shadow --max-steps 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_TRUE(doc["object"]["fitted"]);
  EXPECT_NEAR(doc["object"]["size"][2].get<double>(), 0.9 * 0.034, 1e-12);
  const Outcome full = graspcd("grasp --object '" + file + "' --scale " +
                               std::to_string(0.034 / 30) + " --hand shadow --max-steps 1");
  EXPECT_EQ(full.exit_code, 2);
  EXPECT_NE(full.err.find("penetrates"), std::string::npos) << full.err;
}

}  // namespace
}  // namespace graspcd::testing
