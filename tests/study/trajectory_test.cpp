// Trajectory files: the OBB levels cover their mesh, a recorded grasp written as a
// trajectory keeps its poses, contacts and times, `graspcd trajectory` and its errors, and
// report/draw_figures.py draws the report's pictures from such files.
#include "graspcd/study/trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "graspcd/core/obb_tree.h"
#include "graspcd/mujoco/registry.h"
#include "graspcd/study/recording.h"
#include "helpers/command_test.h"
#include "helpers/test_scale.h"

namespace {

namespace fs = std::filesystem;
using graspcd::Obb;
using graspcd::ObbTree;
using graspcd::Vec3;
using nlohmann::json;
namespace study = graspcd::study;

const std::string kMjcf = GRASPCD_SOURCE_DIR "/mjcf/";

using graspcd::testing::Outcome;
using graspcd::testing::read_file;

class TrajectoryTest : public graspcd::testing::CommandTest {};

bool inside(const Obb& box, const Vec3& p, double tol) {
  const Vec3 local = box.axes.transpose() * (p - box.center);
  return (local.cwiseAbs() - box.half).maxCoeff() <= tol;
}

TEST(BoxesAtDepth, EveryLevelCoversTheMeshAndDoublesUntilTheLeaves) {
  const study::MeshScene scene(kMjcf + "example1.xml");
  for (int mesh : scene.meshes()) {
    const ObbTree& tree = scene.tree(mesh);
    std::size_t previous = 0;
    for (int depth = 0; depth < study::kObbLevels; ++depth) {
      const std::vector<Obb> boxes = study::boxes_at_depth(tree, depth);
      if (depth == 0) {
        ASSERT_EQ(boxes.size(), 1u);
        EXPECT_EQ(boxes[0].center, tree.root().box.center);
      } else {
        EXPECT_GT(boxes.size(), previous) << "depth " << depth << " splits (meshes of > 8 faces)";
        EXPECT_LE(boxes.size(), 2 * previous);
      }
      previous = boxes.size();
      // Every vertex of every face lies in some box of the level: the boxes are in the mesh's
      // frame, with columns as axes (the convention the viewer and the figures draw).
      for (const graspcd::Triangle& t : scene.faces(mesh)) {
        for (const Vec3& p : t.v) {
          bool covered = false;
          for (const Obb& b : boxes) covered = covered || inside(b, p, 1e-9);
          ASSERT_TRUE(covered) << "mesh " << mesh << " depth " << depth;
        }
      }
    }
  }
}

TEST_F(TrajectoryTest, ARecordedGraspKeepsItsPosesContactsAndTimes) {
  const study::Recording rec = study::record_grasp("example1", kMjcf + "example1.xml", false, 400);
  const study::MeshScene scene(rec.scene);
  const study::StepTimes times = {{"sat", std::vector<double>(rec.steps(), 1000.0)}};
  const fs::path path = dir_ / "sub" / "example1.json";
  study::write_trajectory(path.string(), rec, &scene, times);
  const json t = load(path);

  ASSERT_EQ(t["steps"].size(), static_cast<std::size_t>(rec.steps()));
  EXPECT_EQ(t["grasp_steps"].get<int>(), rec.steps());
  EXPECT_EQ(t["times_ns"]["sat"].size(), t["steps"].size());
  // Every geom but the floor plane, with its segment letter and role.
  const json& geoms = t["geoms"];
  EXPECT_EQ(geoms.size(), static_cast<std::size_t>(rec.ngeom - 1));
  std::set<std::string> letters;
  int objects = 0;
  for (const json& g : geoms) {
    EXPECT_NE(g["name"].get<std::string>(), "floor");
    if (g["role"] == "segment") letters.insert(g["segment"].get<std::string>());
    objects += g["role"] == "object";
  }
  EXPECT_EQ(letters, (std::set<std::string>{"A", "B", "C"}));
  EXPECT_EQ(objects, 1);
  // Meshes once, faces indexing their vertices, OBB levels on the served meshes.
  for (const json& m : t["meshes"]) {
    const std::size_t nv = m["vertices"].size() / 3;
    for (const json& f : m["faces"]) EXPECT_LT(f.get<std::size_t>(), nv);
    ASSERT_TRUE(m.contains("obb_levels")) << m["name"];
    EXPECT_EQ(m["obb_levels"].size(), static_cast<std::size_t>(study::kObbLevels));
  }
  // The poses are the recording's, to the 1e-6 rounding; the geom list skips geom 0 (the floor).
  const int last = rec.steps() - 1;
  const json& step = t["steps"][last];
  ASSERT_EQ(step["pos"].size(), 3 * geoms.size());
  for (std::size_t g = 0; g < geoms.size(); ++g) {
    for (std::size_t i = 0; i < 3; ++i)
      EXPECT_NEAR(step["pos"][3 * g + i].get<double>(), rec.xpos[last][3 * (g + 1) + i], 6e-7);
    for (std::size_t i = 0; i < 9; ++i)
      EXPECT_NEAR(step["rot"][9 * g + i].get<double>(), rec.xmat[last][9 * (g + 1) + i], 6e-7);
  }
  // At the grip our contacts and MuJoCo's native ones both touch the object: each contact joins a
  // segment and the object, with a unit normal.
  for (const char* key : {"contacts", "native_contacts"}) {
    ASSERT_FALSE(step[key].empty()) << key;
    for (const json& c : step[key]) {
      const std::string r1 = geoms[c["geoms"][0].get<std::size_t>()]["role"];
      const std::string r2 = geoms[c["geoms"][1].get<std::size_t>()]["role"];
      EXPECT_EQ(std::set<std::string>({r1, r2}), (std::set<std::string>{"segment", "object"}))
          << key;
      const double n = std::hypot(c["normal"][0].get<double>(), c["normal"][1].get<double>(),
                                  c["normal"][2].get<double>());
      EXPECT_NEAR(n, 1.0, 1e-5) << key;
    }
  }
  // Ours come from the triangle meshes, MuJoCo's from the convex hulls: not the same sets.
  EXPECT_NE(step["contacts"], step["native_contacts"]);
  // Before the first contact, none of ours.
  EXPECT_TRUE(t["steps"][0]["contacts"].empty());
}

TEST_F(TrajectoryTest, CommandWritesTimesPerMethodAndFiguresAreDrawnFromItsFiles) {
  // The sanitizer pass (GRASPCD_TEST_SCALE < 1) runs the same recording, replays and writer in
  // ARecordedGrasp... and in StudyTest.QuickStudy...; the figures are Python: Release pass only.
  if (graspcd::testing::test_scale() < 1) GTEST_SKIP() << "Release pass only";
  const fs::path traj = dir_ / "trajectories";
  Outcome r = graspcd("trajectory '" + kMjcf + "example1.xml' --methods sat,sat-cached --out '" +
                      (traj / "example1.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = graspcd("trajectory '" + kMjcf + "hand_boxes.xml' --out '" +
              (traj / "hand_boxes.json").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json e1 = load(traj / "example1.json");
  ASSERT_EQ(e1["times_ns"].size(), 2u);
  for (const char* m : {"sat", "sat-cached"}) {
    ASSERT_EQ(e1["times_ns"][m].size(), e1["steps"].size()) << m;
    double total = 0;
    for (const json& v : e1["times_ns"][m]) total += v.get<double>();
    EXPECT_GT(total, 0) << m;
  }
  const json boxes = load(traj / "hand_boxes.json");
  EXPECT_TRUE(boxes["times_ns"].empty()) << "the box hand has no served meshes";
  EXPECT_TRUE(boxes["meshes"].empty());
  EXPECT_EQ(boxes["geoms"][0]["type"], "cylinder");

  const fs::path figures = dir_ / "figures";
  // Any trajectory files, named as their user likes (the folder form is make_report.py's).
  fs::rename(traj / "example1.json", traj / "my_grasp.json");
  r = run("/usr/bin/python3 '" GRASPCD_SOURCE_DIR "/report/draw_figures.py' '" +
          (traj / "hand_boxes.json").string() + "' '" + (traj / "my_grasp.json").string() + "' '" +
          figures.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"fig18_example1.png", "fig17_obb_depths.png", "contacts_native.png",
                        "fig12_box_hand.png"}) {  // fig18 is named after the scene
    const std::string png = read_file(figures / f);
    ASSERT_GT(png.size(), 10000u) << f;
    EXPECT_EQ(png.substr(1, 3), "PNG") << f;
  }
}

TEST_F(TrajectoryTest, BadInputIsOneLineNamingTheFileWithExitCode2) {
  const std::string missing = (dir_ / "missing.xml").string();
  Outcome r = graspcd("trajectory '" + missing + "' --out '" + (dir_ / "t.json").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = graspcd("trajectory '" + kMjcf + "example1.xml' --methods sat,nope --out '" +
              (dir_ / "t.json").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope"), std::string::npos) << r.err;
  // The figure script: a folder without trajectories, and a file that is not one.
  if (graspcd::testing::test_scale() < 1) GTEST_SKIP() << "draw_figures.py: Release pass only";
  const fs::path bad = dir_ / "bad";
  fs::create_directories(bad);
  const std::string script = "/usr/bin/python3 '" GRASPCD_SOURCE_DIR "/report/draw_figures.py' '";
  r = run(script + bad.string() + "' '" + (dir_ / "f").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
  // Not JSON, then JSON that is not a trajectory: each one line naming the file.
  for (const char* text : {"not json", "{\"schema\": 1}"}) {
    std::ofstream(bad / "example1.json") << text;
    r = run(script + bad.string() + "' '" + (dir_ / "f").string() + "'");
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_NE(r.err.find((bad / "example1.json").string()), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
