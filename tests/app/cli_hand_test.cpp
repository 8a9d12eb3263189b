// `graspcd hand check`: what a template hand, or a hand file with its drive, lacks, each missing
// piece named where it belongs with how to add it (docs/hands.md).
// Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

const char* const kCube =
    "v -0.01 -0.01 -0.01\nv 0.01 -0.01 -0.01\nv -0.01 0.01 -0.01\nv 0.01 0.01 -0.01\n"
    "v -0.01 -0.01 0.01\nv 0.01 -0.01 0.01\nv -0.01 0.01 0.01\nv 0.01 0.01 0.01\n"
    "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
    "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";

// A scene with an object body that has no free joint and no pair config beside it: both named,
// with their file (and line) and how to add them; exit 1.
TEST_F(CliTest, HandCheckNamesEachMissingPieceAndHowToAddIt) {
  write("cube.obj", kCube);
  const std::string scene = write("my_hand.xml",
                                  "<mujoco>\n"
                                  "  <asset><mesh name=\"m\" file=\"cube.obj\"/></asset>\n"
                                  "  <worldbody>\n"
                                  "    <body name=\"object\" pos=\"0 0 0.1\">\n"
                                  "      <geom type=\"mesh\" mesh=\"m\"/>\n"
                                  "    </body>\n"
                                  "  </worldbody>\n"
                                  "</mujoco>\n");
  const std::string pairs = (dir_ / "my_hand.pairs.json").string();
  Result r = run("hand check " + scene);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const std::vector<std::string> out = lines(r.out);
  ASSERT_GE(out.size(), 5u) << r.out;
  EXPECT_EQ(out[0], "missing: " + scene + ":4: the object body has no free joint");
  EXPECT_EQ(out[1].rfind("  add: add <freejoint/> to the object body", 0), 0u) << out[1];
  EXPECT_EQ(out[2], "missing: " + pairs + ": no pair config " + pairs + " beside the scene");
  EXPECT_NE(out[3].find("\"grasp\": {\"hand\": BODY"), std::string::npos) << out[3];
  EXPECT_EQ(out.back(),
            scene + ": 2 pieces missing (docs/hands.md builds a template step by step)");
  // The same as one JSON document.
  r = run("hand check " + scene + " --json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_FALSE(doc["complete"]);
  ASSERT_EQ(doc["missing"].size(), 2u);
  EXPECT_EQ(doc["missing"][0]["file"], scene);
  EXPECT_EQ(doc["missing"][0]["line"], 4);
  EXPECT_EQ(doc["missing"][1]["file"], pairs);

  // With the free joint and a pair config whose "grasp" names an actuator the scene lacks.
  write("my_hand.xml",
        "<mujoco>\n"
        "  <asset><mesh name=\"m\" file=\"cube.obj\"/></asset>\n"
        "  <worldbody>\n"
        "    <body name=\"palm\" pos=\"0 0 0.2\"><geom name=\"palm\" type=\"box\" "
        "size=\"0.05 0.05 0.01\"/></body>\n"
        "    <body name=\"object\" pos=\"0 0 0.1\"><freejoint/><geom type=\"mesh\" "
        "mesh=\"m\"/></body>\n"
        "  </worldbody>\n"
        "</mujoco>\n");
  write("my_hand.pairs.json",
        "{\"pairs\": [{\"a\": \"body:palm\", \"b\": \"body:object\"}],\n"
        " \"grasp\": {\"hand\": \"palm\", \"close\": [{\"actuator\": \"close\", \"step\": 0.1, "
        "\"touch\": [\"body:palm\"]}], \"lift\": {\"actuator\": \"lift\", \"by\": 0.06}}}\n");
  r = run("hand check " + scene);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("missing: " + pairs + ": 'grasp': no actuator named 'close'\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("missing: " + pairs + ": 'grasp': no actuator named 'lift'\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(scene + ": 2 pieces missing"), std::string::npos) << r.out;
}

// A scene tinyxml2 cannot read, and --drive with a built-in template: one line, exit 2.
TEST_F(CliTest, HandCheckRefusesWhatItCannotRead) {
  const std::string bad = write("bad.xml", "<mujoco>\n<worldbody>\n");
  Result r = run("hand check " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
  r = run("hand check robotiq --drive " + write("d.json", "{}"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "graspcd: hand check: --drive goes with a hand file, not the built-in template "
            "'robotiq' (which has its drive)\n");
}

// The Allegro hand (../shared/models): the Menagerie's own scene lacks a mesh object and a pair
// config; the shipped template is complete; a hand file with a drive that has no "mount" is told
// so, naming the drive file.
TEST_F(CliTest, HandCheckOnTheAllegroHand) {
  const fs::path models = fs::path(GRASPCD_MODELS_DIR) / "hands" / "wonik_allegro";
  if (!fs::exists(models / "right_hand.xml")) GTEST_SKIP() << "Allegro hand not in " << models;
  const std::string scene = (models / "scene_right.xml").string();
  Result r = run("hand check " + scene);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("missing: " + scene + ":23: the object body has no mesh geom\n"),
            std::string::npos)
      << r.out;
  r = run("hand check allegro");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find(": complete ("), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("missing:"), std::string::npos) << r.out;
  const std::string drive = write("drive.json", "{\"grasp\": {\"hand\": \"palm\"}}");
  r = run("hand check " + (models / "right_hand.xml").string() + " --drive " + drive);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(lines(r.out).front().rfind("missing: " + drive + ": no \"mount\"", 0), 0u) << r.out;
}

}  // namespace
