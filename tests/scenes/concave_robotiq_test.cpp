// The Robotiq 2F-85 on concave parts of real objects (mjcf/concave_robotiq_*.xml,
// docs/real-hands.md, "Concave grasps with the Robotiq 2F-85"): a pinch of the bowl's wall and of
// the mug's wall at the rim with one pad inside the cavity, and a pinch of the mug's handle bar
// with one pad through the handle's hole. graspcd grips, lifts and holds each (a bowl hung from its
// rim tilts, and the verdict says so), CGAL finds no contact graspcd missed or made up, and
// MuJoCo's own collision cannot start them: the pad inside the cavity lies inside the object's
// convex hull.
//
// Both pads meet the pinched part within a few grasp steps of each other: the 2F-85 closes its two
// fingers as mirror images (the equality of its driver joints), so on a centred object they touch
// together; the scenes place the pinched wall or bar on the gripper's mid-plane.
//
// Needs ../shared/models (skipped with a message without it); whole grasps and CGAL's checks:
// label "slow", the Release pass only.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "graspcd/grasp/grasp.h"
#include "graspcd/grasp/verdicts.h"
#include "helpers/command_test.h"

namespace graspcd::grasp {
namespace {

namespace fs = std::filesystem;

const std::string kMjcf = GRASPCD_MJCF_DIR;

// The pads' first contacts may differ by at most this many grasp steps on a centred object (a
// grasp step moves a pad about 0.15 mm).
constexpr int kPadLagSteps = 3;

class ConcaveRobotiq : public testing::CommandTest {
 protected:
  // A copy of mjcf/NAME.xml and its pair config in DIR/tree/mjcf, with DIR/shared the folder of
  // the models, so that the scene's ../../shared/models paths hold wherever the source tree lies;
  // "" without the models.
  std::string scene(const std::string& name) {
    const fs::path models(GRASPCD_MODELS_DIR);
    if (!fs::exists(models / "hands/robotiq_2f85/2f85.xml")) return "";
    const fs::path mjcf = dir_ / "tree" / "mjcf";
    if (!fs::exists(mjcf)) {
      fs::create_directories(mjcf);
      fs::create_directory_symlink(fs::absolute(models).parent_path(), dir_ / "shared");
    }
    for (const char* ext : {".xml", ".pairs.json"}) {
      fs::copy_file(kMjcf + "/" + name + ext, mjcf / (name + ext));
    }
    return (mjcf / (name + ".xml")).string();
  }

  // The grasp's verdicts, and the first contact of each pad.
  struct Grasped {
    GraspResult result;
    int left = -1;
    int right = -1;
  };
  static Grasped grasp(const std::string& path) {
    Grasped g;
    g.result = run_grasp(path);
    for (std::size_t s = 0; s < g.result.segments.size(); ++s) {
      if (g.result.segments[s] == "body:left_pad") g.left = g.result.first_contact[s];
      if (g.result.segments[s] == "body:right_pad") g.right = g.result.first_contact[s];
    }
    return g;
  }

  // `graspcd validate SCENE --json`: exit code 0, contacts to check, no missed and no false
  // collision of any pair.
  void expect_validated(const std::string& path) {
    const fs::path json = dir_ / "validate.json";
    const testing::Outcome r = run(std::string("{ '") + GRASPCD_EXE + "' validate '" + path +
                                   "' --json > '" + json.string() + "'; }");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json v = load(json);
    EXPECT_GT(v.at("steps_with_contact").get<int>(), 0);
    EXPECT_FALSE(v.at("cut_short").get<bool>());
    EXPECT_LT(v.at("steps").get<int>(), v.at("max_steps").get<int>());
    EXPECT_FALSE(v.at("missed_any").get<bool>());
    int pairs = 0;
    for (const nlohmann::json& method : v.at("methods")) {
      for (const nlohmann::json& pair : method.at("pairs")) {
        ++pairs;
        EXPECT_EQ(pair.at("missed").get<int>(), 0) << pair.at("pair");
        EXPECT_EQ(pair.at("false_contacts").get<int>(), 0) << pair.at("pair");
        EXPECT_EQ(pair.at("missed_tri_pairs").get<int>(), 0) << pair.at("pair");
        EXPECT_EQ(pair.at("false_tri_pairs").get<int>(), 0) << pair.at("pair");
      }
    }
    EXPECT_GT(pairs, 0);
  }

  // `graspcd grasp SCENE --native` is refused at the start: the pad inside the cavity lies inside
  // the hull MuJoCo collides the object as.
  void expect_native_refused(const std::string& path, const std::string& mesh) {
    const testing::Outcome r = graspcd("grasp '" + path + "' --native");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("cannot start with --native: MuJoCo collides mesh '" + mesh +
                         "' as its convex hull, which"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("a limit of the hull, not of the scene"), std::string::npos) << r.err;
  }
};

#define SKIP_WITHOUT_MODELS(path)                                                  \
  if ((path).empty()) {                                                            \
    GTEST_SKIP() << "real models not found at " << GRASPCD_MODELS_DIR              \
                 << " (../shared/models is absent): the concave scenes need them"; \
  }

// The expected verdict of a held grasp: gripped, held, no reason, and the tilt named exactly when
// the object ended 2 degrees or more from how it stood at the lift.
void expect_held(const GraspResult& r) {
  EXPECT_TRUE(r.gripped) << r.reason;
  EXPECT_TRUE(r.held) << r.reason;
  EXPECT_EQ(r.reason, "");
  EXPECT_FALSE(r.ejected.has_value());
  EXPECT_FALSE(r.dropped_at.has_value());
  EXPECT_GE(r.grip_rise, kHeldRiseShare * r.hand_travel);
  EXPECT_GT(r.hand_travel, 0.04);
  if (r.tilt_final_deg >= kTiltShownDeg) {
    char note[48];
    std::snprintf(note, sizeof note, "tilted %.0f\xc2\xb0", r.tilt_final_deg);
    EXPECT_EQ(tilt_note(r), note);
  } else {
    EXPECT_EQ(tilt_note(r), "");
  }
}

TEST_F(ConcaveRobotiq, BowlRimPinchIsHeldTiltedAndTheHullCannotStart) {
  const std::string path = scene("concave_robotiq_bowl_rim");
  SKIP_WITHOUT_MODELS(path);
  const Grasped g = grasp(path);
  expect_held(g.result);
  // The bowl hangs from its rim: it turns about 27 degrees about the pinch, and the verdict says
  // "held yes, tilted 27°".
  EXPECT_GT(g.result.tilt_final_deg, 15.0);
  EXPECT_LT(g.result.tilt_final_deg, 45.0);
  EXPECT_EQ(tilt_note(g.result).rfind("tilted ", 0), 0u) << tilt_note(g.result);
  ASSERT_GT(g.left, 0);
  ASSERT_GT(g.right, 0);
  EXPECT_LE(std::abs(g.left - g.right), kPadLagSteps) << g.left << " " << g.right;
  expect_validated(path);
  expect_native_refused(path, "bowl");
}

TEST_F(ConcaveRobotiq, MugRimPinchIsHeldAndTheHullCannotStart) {
  const std::string path = scene("concave_robotiq_mug_rim");
  SKIP_WITHOUT_MODELS(path);
  const Grasped g = grasp(path);
  expect_held(g.result);
  ASSERT_GT(g.left, 0);
  ASSERT_GT(g.right, 0);
  EXPECT_LE(std::abs(g.left - g.right), kPadLagSteps) << g.left << " " << g.right;
  expect_validated(path);
  expect_native_refused(path, "mug");
}

TEST_F(ConcaveRobotiq, MugHandlePinchIsHeldAndTheHullCannotStart) {
  const std::string path = scene("concave_robotiq_mug_handle");
  SKIP_WITHOUT_MODELS(path);
  const Grasped g = grasp(path);
  expect_held(g.result);
  // Hung from its handle, the mug turns about 10 degrees about the pinch: "held yes, tilted 10°".
  EXPECT_GT(g.result.tilt_final_deg, 5.0);
  EXPECT_LT(g.result.tilt_final_deg, 20.0);
  EXPECT_EQ(tilt_note(g.result).rfind("tilted ", 0), 0u) << tilt_note(g.result);
  ASSERT_GT(g.left, 0);
  ASSERT_GT(g.right, 0);
  EXPECT_LE(std::abs(g.left - g.right), kPadLagSteps) << g.left << " " << g.right;
  expect_validated(path);
  expect_native_refused(path, "mug");
}

// The bowl in 16 HACD pieces cannot start either: a piece fills the cavity the follower starts in.
// The refusal names that piece and its file, not the bowl's convex hull (which MuJoCo no longer
// collides here).
TEST_F(ConcaveRobotiq, ADecomposedBowlsRefusalNamesThePiece) {
  const std::string path = scene("concave_robotiq_bowl_rim");
  SKIP_WITHOUT_MODELS(path);
  const fs::path bowl = fs::path(GRASPCD_MODELS_DIR) / "objects/prl_assets/plastic_bowl_visual.obj";
  const std::string pieces = (dir_ / "bowl16").string();
  // With stderr to a file (not a terminal), progress lines all the same (here at every update):
  // HACD's merges with the share done and the time left.
  const testing::Outcome d =
      run("GRASPCD_PROGRESS_SECONDS=0 '" + std::string(GRASPCD_EXE) + "' decompose '" +
          bowl.string() + "' --out '" + pieces + "' --pieces 16");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_TRUE(std::regex_search(
      d.err,
      std::regex("\\[decompose\\] [^\\n]*: HACD: merging the faces' clusters down to 16 "
                 "\\(the share merged\\); \\d+ s so far, about \\d+ (s|min)[^\\n]* left\\n")))
      << d.err;
  EXPECT_NE(d.err.find("[decompose] wrote "), std::string::npos) << d.err;
  const testing::Outcome r = graspcd("grasp '" + path + "' --decomposed '" + pieces + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const std::regex named(
      "cannot start with --decomposed: the hull of geom \\d+ \\(mesh 'follower' "
      "of body '\\w+'\\) lies \\d+\\.\\d mm inside piece (\\d+) of mesh 'bowl' \\(" +
      pieces + "/plastic_bowl_visual_piece_(\\d+)\\.obj\\) at the start");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, named)) << r.err;
  EXPECT_EQ(m[1].str(), m[2].str()) << r.err;
  EXPECT_EQ(r.err.find("convex hull"), std::string::npos) << r.err;
}

// What validate checked, said in its header and its JSON: the closing, how many grasp steps,
// whether --max-steps cut it short, and the squeeze, where the pads press on the rim (before, it
// stopped at the pads' first touch: "1 of 193 grasp steps had a contact to check"); --phases all
// adds the lift and the hold; and progress lines on stderr when it is a file.
TEST_F(ConcaveRobotiq, ValidateSaysWhatItCheckedAndShowsProgress) {
  const std::string path = scene("concave_robotiq_mug_rim");
  SKIP_WITHOUT_MODELS(path);
  const fs::path json = dir_ / "cut.json";
  const testing::Outcome r =
      run("{ GRASPCD_PROGRESS_SECONDS=0 '" + std::string(GRASPCD_EXE) + "' validate '" + path +
          "' --max-steps 5 --json > '" + json.string() + "'; }");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json v = load(json);
  EXPECT_EQ(v.at("steps").get<int>(), 5);
  EXPECT_EQ(v.at("max_steps").get<int>(), 5);
  EXPECT_TRUE(v.at("cut_short").get<bool>());
  EXPECT_EQ(v.at("phases"), nlohmann::json::array({"closing", "squeeze"}));
  EXPECT_NE(r.err.find("[validate] " + path + ": closing grasp step 5 of at most 5 checked; "),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(
      std::regex_search(r.err, std::regex("checked; \\d+ s so far, at most \\d+ s left\\n")))
      << r.err;
  // The text says it too.
  const testing::Outcome text = run("{ '" + std::string(GRASPCD_EXE) + "' validate '" + path +
                                    "' --max-steps 5 > '" + (dir_ / "cut.txt").string() + "'; }");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(testing::read_file(dir_ / "cut.txt")
                .find("# checked: the closing, 5 grasp steps, each after its last physics step; "
                      "the squeeze and its settling, "),
            std::string::npos)
      << testing::read_file(dir_ / "cut.txt");
  EXPECT_NE(testing::read_file(dir_ / "cut.txt")
                .find("; --max-steps 5 cut the closing short (the hand had not finished "
                      "closing); the lift and the hold are not checked (--phases all checks every "
                      "phase)\n"),
            std::string::npos)
      << testing::read_file(dir_ / "cut.txt");

  // A whole grasp, every phase, on a block the Robotiq lifts (3 x 3 x 6 cm, 12 triangles, so
  // that CGAL's brute force over the lift's and the hold's 300 states stays cheap): the closing
  // ends at the pads' touch, and the squeeze, the lift and the hold each have states where the
  // pads touch it, every pair agreeing with CGAL.
  const fs::path block = dir_ / "block.obj";
  std::ofstream(block) << "v -0.015 -0.015 0\nv 0.015 -0.015 0\nv -0.015 0.015 0\n"
                          "v 0.015 0.015 0\nv -0.015 -0.015 0.06\nv 0.015 -0.015 0.06\n"
                          "v -0.015 0.015 0.06\nv 0.015 0.015 0.06\n"
                          "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
                          "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  const testing::Outcome written =
      graspcd("grasp --object '" + block.string() + "' --hand robotiq --quiet --write-scene '" +
              (dir_ / "kept").string() + "'");
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const fs::path all = dir_ / "all.json";
  const testing::Outcome whole = run(
      "{ '" + std::string(GRASPCD_EXE) + "' validate '" + (dir_ / "kept" / "block.xml").string() +
      "' --method sat --phases all --json > '" + all.string() + "'; }");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const nlohmann::json w = load(all);
  EXPECT_FALSE(w.at("cut_short").get<bool>());
  EXPECT_EQ(w.at("phases"), nlohmann::json::array({"closing", "squeeze", "lift", "hold"}));
  ASSERT_EQ(w.at("checks").size(), 4u);
  for (const nlohmann::json& c : w.at("checks")) {
    EXPECT_GT(c.at("states").get<int>(), 0) << c;
    EXPECT_GT(c.at("with_contact").get<int>(), 0) << c;
  }
  // The squeeze presses at every state checked; the closing touched only near its end.
  EXPECT_EQ(w.at("checks")[1].at("with_contact"), w.at("checks")[1].at("states"));
  EXPECT_LT(w.at("checks")[0].at("with_contact").get<int>(), w.at("steps").get<int>());
  EXPECT_FALSE(w.at("missed_any").get<bool>());
}

// A scene that starts from a keyframe is no template for a new object: the keyframe holds the
// mug's pose, which the new object's placement would not replace. One line naming the template
// and the keyframe's line, exit code 2.
TEST_F(ConcaveRobotiq, AKeyframedSceneIsRefusedAsATemplate) {
  const std::string path = scene("concave_robotiq_mug_handle");
  SKIP_WITHOUT_MODELS(path);
  const fs::path cup = fs::path(GRASPCD_MODELS_DIR) / "objects/mujoco/cube_cup.obj";
  const testing::Outcome r =
      graspcd("grasp --object '" + cup.string() + "' --hand '" + path + "' --max-steps 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(path + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("template scene: a template with a <keyframe> cannot take a new object"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// Why one pad used to touch first: not the gripper. On the centred cup the two pads stay mirror
// images across the gripper's mid-plane at every closing grasp step (x_left = -x_right within
// 0.05 mm, the same height), and both first touch in the same grasp step or the next.
TEST_F(ConcaveRobotiq, TheTwoPadsCloseAsMirrorImagesAndMeetACentredCupTogether) {
  const std::string path = scene("real_robotiq_cup");
  SKIP_WITHOUT_MODELS(path);
  GraspOptions options;
  double worst_x = 0, worst_z = 0;
  int steps = 0;
  options.on_grasp_step = [&](const mjModel* m, const mjData* d, int) {
    const int l = mj_name2id(m, mjOBJ_BODY, "left_pad");
    const int r = mj_name2id(m, mjOBJ_BODY, "right_pad");
    ASSERT_GE(l, 0);
    ASSERT_GE(r, 0);
    EXPECT_LT(d->xpos[3 * l], -0.01);  // the left pad on -x, the right on +x
    worst_x = std::max(worst_x, std::abs(d->xpos[3 * l] + d->xpos[3 * r]));
    worst_z = std::max(worst_z, std::abs(d->xpos[3 * l + 2] - d->xpos[3 * r + 2]));
    ++steps;
  };
  const GraspResult r = run_grasp(path, options);
  EXPECT_GT(steps, 20);
  EXPECT_LT(worst_x, 5e-5);
  EXPECT_LT(worst_z, 5e-5);
  int left = -1, right = -1;
  for (std::size_t s = 0; s < r.segments.size(); ++s) {
    if (r.segments[s] == "body:left_pad") left = r.first_contact[s];
    if (r.segments[s] == "body:right_pad") right = r.first_contact[s];
  }
  ASSERT_GT(left, 0);
  ASSERT_GT(right, 0);
  EXPECT_LE(std::abs(left - right), 1) << left << " " << right;
  EXPECT_TRUE(r.held) << r.reason;
}

// What made one pad touch first: the placement. A pad moves about 0.13 mm per grasp step; the cup
// moved off the mid-plane by 2 mm meets the near pad first, which pushes it towards the other, so
// that the other touches about 2 mm / 0.13 mm = 15 grasp steps later (measured 15 on either side).
TEST_F(ConcaveRobotiq, ACupTwoMillimetresOffTheMidPlaneMeetsTheNearPadFirst) {
  const std::string path = scene("real_robotiq_cup");
  SKIP_WITHOUT_MODELS(path);
  const std::string xml = testing::read_file(path);
  const std::string centred = "<body name=\"object\" pos=\"0 0 0.2\"";
  ASSERT_NE(xml.find(centred), std::string::npos);
  for (const double shift : {-0.002, 0.002}) {
    std::string moved = xml;
    moved.replace(moved.find(centred), centred.size(),
                  "<body name=\"object\" pos=\"" + std::to_string(shift) + " 0 0.2\"");
    const fs::path mjcf = fs::path(path).parent_path();
    const fs::path shifted = mjcf / "shifted.xml";
    std::ofstream(shifted) << moved;
    fs::copy_file(mjcf / "real_robotiq_cup.pairs.json", mjcf / "shifted.pairs.json",
                  fs::copy_options::overwrite_existing);
    const Grasped g = grasp(shifted.string());
    ASSERT_GT(g.left, 0);
    ASSERT_GT(g.right, 0);
    const int near = shift < 0 ? g.left : g.right;
    const int far = shift < 0 ? g.right : g.left;
    EXPECT_GE(far - near, 8) << shift;
    EXPECT_LE(far - near, 25) << shift;
    EXPECT_TRUE(g.result.held) << g.result.reason;
  }
}

}  // namespace
}  // namespace graspcd::grasp
