// `graspcd grasp SCENE`: the shipped scenes' grasps in text and JSON, native, with reused
// contacts, and the errors of a bad scene, config or mesh.
// Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

TEST_F(CliTest, GraspPrintsAHeaderOneLinePerGraspStepAndASummary) {
  const Result r = run("grasp " + shipped_scene("example2") + " --max-steps 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), 1u + 8u + 4u) << r.out;
  EXPECT_EQ(out[0], "step contacts detection_ns box_tests triangle_tests object_z segments");
  const std::regex step_line(R"(^(\d+) \d+ \d+ \d+ \d+ -?\d+\.\d{6} \S+$)");
  for (int k = 1; k <= 8; ++k) {
    std::smatch match;
    ASSERT_TRUE(std::regex_match(out[static_cast<std::size_t>(k)], match, step_line))
        << out[static_cast<std::size_t>(k)];
    EXPECT_EQ(std::stoi(match[1]), k);
  }
  // Eight grasp steps of 0.003 rad do not reach the object: no grip, nothing lifted.
  EXPECT_EQ(out[9].rfind("# method sat; first contact (grasp step): finger1_A=-", 0), 0u) << out[9];
  EXPECT_EQ(out[10].rfind("# gripped no; held no, the closing was cut short at grasp step 8 "
                          "(--max-steps): the hand did not touch it at the start of the lift (",
                          0),
            0u)
      << out[10];
  EXPECT_EQ(out[10].find("(gripped)"), std::string::npos) << out[10];
  EXPECT_EQ(out[11].rfind("# detection ns ", 0), 0u) << out[11];
  EXPECT_NE(out[11].find(" 0 non-finite skips"), std::string::npos) << out[11];
  // Where its time went: the parts that took some, and the time before the first physics step.
  EXPECT_EQ(out[12].rfind("# cost ", 0), 0u) << out[12];
  EXPECT_NE(out[12].find(" compile "), std::string::npos) << out[12];
  EXPECT_NE(out[12].find(" physics "), std::string::npos) << out[12];
  EXPECT_NE(out[12].find(" s CPU before the first physics step"), std::string::npos) << out[12];
}

TEST_F(CliTest, GraspJsonIsOneDocumentWithTheSameRecords) {
  const Result r = run("grasp " + shipped_scene("example1") +
                       " --max-steps 5 --json --method perceptron --cap 20");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc.at("method"), "perceptron");
  EXPECT_EQ(doc.at("native"), false);
  ASSERT_EQ(doc.at("steps").size(), 5u);
  // Where its time went, per part; the parts sum to the whole.
  const nlohmann::json& cost = doc.at("cost");
  double parts = 0;
  for (const char* part : {"scene", "compile", "trees", "placement", "start_check", "physics",
                           "true_penetration", "judge", "write"}) {
    parts += cost.at("parts").at(part).at("cpu_s").get<double>();
  }
  EXPECT_GT(cost.at("parts").at("physics").at("cpu_s").get<double>(), 0);
  EXPECT_NEAR(parts, cost.at("cpu_s").get<double>(), 1e-9);
  EXPECT_EQ(doc.at("steps")[4].at("step"), 5);
  EXPECT_TRUE(doc.at("steps")[0].contains("detection_ns"));
  EXPECT_EQ(doc.at("first_contact").size(), 12u);
  EXPECT_TRUE(doc.at("first_contact").at("finger2_C").is_null());
  EXPECT_EQ(doc.at("held"), false);
  // Five steps reach nothing; the squeeze closes the fingers onto the cup without moving it, and
  // the lift leaves it behind: dropped when it left the hand, the closing cut short beside it.
  EXPECT_GE(doc.at("pushed").get<double>(), 0.0);
  EXPECT_LT(doc.at("pushed").get<double>(), 0.01);
  EXPECT_EQ(doc.at("pushed_during_squeeze"), false);
  EXPECT_EQ(doc.at("outcome"), "dropped");
  ASSERT_TRUE(doc.at("dropped_at").is_number()) << doc.at("reason");
  EXPECT_EQ(doc.at("dropped_at"), doc.at("release_time"));
  EXPECT_EQ(doc.at("closing"), "max_steps");
  EXPECT_EQ(doc.at("notes"),
            nlohmann::json::array({"the closing was cut short at grasp step 5 (--max-steps)"}));
  graspcd::testing::expect_envelope(doc);
}

TEST_F(CliTest, GraspNativeHasNoDetectionTime) {
  const Result r = run("grasp " + shipped_scene("example3") + " --max-steps 5 --json --native");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc.at("method"), "native");
  EXPECT_EQ(doc.at("detection_ns_total"), 0);
  EXPECT_GT(doc.at("physics_steps").get<long>(), 0);
}

// --multiccd: MuJoCo's multi-point convex collision for what MuJoCo collides itself. Natively,
// example 1's fingers (meshes) on the cup's hull get one contact per pair without it and more with
// it; a scene whose MJCF enables it runs with it unless --multiccd=false; the JSON and the text
// say what ran; a value that is not a truth value is one line and exit code 2.
TEST_F(CliTest, GraspMulticcdReachesMujocosNativeCollision) {
  const std::string scene = shipped_scene("example1");
  const auto grasp = [&](const std::string& path, const std::string& args) {
    const Result r = run("grasp " + path + " --native --max-steps 150 --json " + args);
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
  };
  const nlohmann::json off = grasp(scene, "");
  const nlohmann::json on = grasp(scene, "--multiccd");
  ASSERT_TRUE(off.contains("multiccd") && on.contains("multiccd"));
  EXPECT_EQ(off.at("multiccd"), false);
  EXPECT_EQ(on.at("multiccd"), true);
  // The fingers reach the cup in both runs; one contact per convex pair is MuJoCo's without it.
  EXPECT_GT(off.at("max_contacts").get<int>(), 0);
  EXPECT_EQ(off.at("max_pair_contacts"), 1);
  EXPECT_GT(on.at("max_pair_contacts").get<int>(), 1);
  EXPECT_LE(on.at("max_pair_contacts").get<int>(), 5);  // the first and 4 tilted searches

  // The scene's own flag, and --multiccd=false against it.
  std::string xml = read_file(scene);
  const std::string option = "<option timestep=\"0.002\" gravity=\"0 0 -9.81\"/>";
  ASSERT_NE(xml.find(option), std::string::npos);
  xml.replace(xml.find(option), option.size(),
              "<option timestep=\"0.002\" gravity=\"0 0 -9.81\"><flag multiccd=\"enable\"/>"
              "</option>");
  const std::string mjcf = fs::path(scene).parent_path().string();
  const std::string meshdir = "meshdir=\"meshes\"";
  ASSERT_NE(xml.find(meshdir), std::string::npos);
  xml.replace(xml.find(meshdir), meshdir.size(), "meshdir=\"" + mjcf + "/meshes\"");
  const std::string flagged = write("flagged.xml", xml);
  fs::copy_file(fs::path(mjcf) / "example1.pairs.json", dir_ / "flagged.pairs.json");
  const nlohmann::json scene_on = grasp(flagged, "");
  ASSERT_TRUE(scene_on.contains("multiccd"));
  EXPECT_EQ(scene_on.at("multiccd"), true);
  EXPECT_EQ(scene_on.at("max_pair_contacts"), on.at("max_pair_contacts"));
  const nlohmann::json turned_off = grasp(flagged, "--multiccd=false");
  ASSERT_TRUE(turned_off.contains("multiccd"));
  EXPECT_EQ(turned_off.at("multiccd"), false);
  EXPECT_EQ(turned_off.at("max_pair_contacts"), 1);

  const Result text = run("grasp " + shipped_scene("example2") + " --max-steps 2 --multiccd");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("; multiccd on\n"), std::string::npos) << text.out;
  const Result bad = run("grasp " + scene + " --native --multiccd=sometimes");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("--multiccd"), std::string::npos) << bad.err;
}

// --contact-reuse (registry.h, "contact_reuse"): touching pairs answered by their kept contacts,
// counted in reused_calls; 20 um is the default, 0 (or --exact) exact contacts every step; out of
// range, not a number, with --native, or --exact beside --contact-reuse, one line and exit code 2.
TEST_F(CliTest, GraspContactReuseIsCountedAndCheckedOnTheCommandLine) {
  const std::string scene = shipped_scene("example1");
  const auto reused = [&](const std::string& args) {
    const Result r = run("grasp " + scene + " --max-steps 60 --json" + args);
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out).at("reused_calls").get<long>() : -1L;
  };
  EXPECT_GT(reused(" --contact-reuse 2e-5"), 0);
  EXPECT_GT(reused(""), 0);  // the default
  EXPECT_EQ(reused(" --contact-reuse 0"), 0);
  EXPECT_EQ(reused(" --exact"), 0);
  for (const std::string bad :
       {"--contact-reuse -1e-5", "--contact-reuse 0.01", "--contact-reuse nan",
        "--contact-reuse 2e-5 --native", "--exact --native", "--exact --contact-reuse 0"}) {
    const Result e = run("grasp " + scene + " " + bad);
    EXPECT_EQ(e.exit_code, 2) << bad;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
    EXPECT_NE(e.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << bad << ": " << e.err;
  }
}

// --quiet: the same run without the per-step table, so the '#' summary lines alone; with
// --object the object line stays first. With --json it changes nothing.
TEST_F(CliTest, GraspQuietPrintsOnlyTheHeaderAndTheVerdict) {
  const Result full = run("grasp " + shipped_scene("example2") + " --max-steps 8");
  const Result r = run("grasp " + shipped_scene("example2") + " --max-steps 8 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), 4u) << r.out;
  for (const std::string& line : out) EXPECT_EQ(line.rfind("# ", 0), 0u) << line;
  const std::vector<std::string> all = lines(full.out);
  ASSERT_EQ(all.size(), 1u + 8u + 4u) << full.out;
  // The verdict is the same run's (the detection times differ from run to run).
  EXPECT_EQ(out[0], all[9]);
  EXPECT_EQ(out[1], all[10]);

  const std::string box = write("box_m.obj", user_box_in_metres());
  const Result object = run("grasp --object " + box + " --max-steps 2 --quiet");
  ASSERT_EQ(object.exit_code, 0) << object.err;
  const std::vector<std::string> object_out = lines(object.out);
  ASSERT_EQ(object_out.size(), 5u) << object.out;
  EXPECT_EQ(object_out[0].rfind("# object " + box + " at scale 1 (given)", 0), 0u) << object_out[0];
  EXPECT_EQ(object_out[2].rfind("# gripped no; held no", 0), 0u) << object_out[2];

  const Result json = run("grasp " + shipped_scene("example2") + " --max-steps 8 --quiet --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["steps"].size(), 8u);
}

// An L-shaped block (6 x 3 x 7 cm, 1.5 cm thick) turned 37 degrees in the Robotiq: the pads meet
// its corner and the squeeze pushes it about 1.4 cm before the lift, squaring it to the pads;
// the hand then lifts it. Held, but the verdict says it was pushed (not pushed over: the turn
// about gravity is no tip), and --require-held still passes.
TEST_F(CliTest, GraspSaysWhenTheSqueezePushedAHeldObject) {
  SKIP_UNLESS_REAL_HAND_GRASPS("robotiq_2f85/2f85.xml");
  const std::string l_shape = write(
      "l_shape.obj",
      inside_out("v 0 0 0\nv 0.06 0 0\nv 0.06 0 0.015\nv 0.015 0 0.015\nv 0.015 0 0.07\n"
                 "v 0 0 0.07\nv 0 0.03 0\nv 0.06 0.03 0\nv 0.06 0.03 0.015\nv 0.015 0.03 0.015\n"
                 "v 0.015 0.03 0.07\nv 0 0.03 0.07\n"
                 "f 1 2 8\nf 1 8 7\nf 2 3 9\nf 2 9 8\nf 3 4 10\nf 3 10 9\nf 4 5 11\nf 4 11 10\n"
                 "f 5 6 12\nf 5 12 11\nf 6 1 7\nf 6 7 12\nf 1 3 2\nf 7 8 9\nf 1 4 3\nf 7 9 10\n"
                 "f 1 5 4\nf 7 10 11\nf 1 6 5\nf 7 11 12\n"));
  const std::string args = "grasp --object " + l_shape + " --hand robotiq --yaw 37 --require-held";
  const Result json = run(args + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json doc = nlohmann::json::parse(json.out);
  EXPECT_TRUE(doc["held"]) << doc["reason"];
  EXPECT_TRUE(doc["pushed_during_squeeze"]);
  EXPECT_GT(doc["pushed"].get<double>(), 0.01);
  EXPECT_LT(doc["pushed"].get<double>(), 0.03);
  EXPECT_TRUE(doc["dropped_at"].is_null());
  EXPECT_FALSE(doc["pushed_over"]);
  EXPECT_LT(doc["tilt_before_lift_deg"].get<double>(), 10.0);
  for (const nlohmann::json& w : doc["warnings"]) EXPECT_NE(w["code"], "mesh_inside_out") << w;
  const Result text = run(args + " --quiet");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::vector<std::string> out = lines(text.out);
  ASSERT_EQ(out.size(), 5u) << text.out;
  EXPECT_TRUE(std::regex_search(
      out[2], std::regex("^# gripped yes; held yes, (tilted \\d+\xc2\xb0, )?pushed 1\\.\\d cm "
                         "during the squeeze: carried")))
      << out[2];
  EXPECT_EQ(out[2].find("pushed over"), std::string::npos) << out[2];
  EXPECT_NE(out[2].find("; object z "), std::string::npos) << out[2];
}

// A grasp that never reaches the object is reported as failed, with the reason, and
// --require-held makes it exit 1.
TEST_F(CliTest, AGraspThatNeverTouchedTheObjectSaysWhyAndCanFail) {
  // (The text's summary line is checked by GraspPrintsAHeaderOneLinePerGraspStepAndASummary.)
  const std::string box = write("box.obj", kUserBox);
  const Result r =
      run("grasp --object " + box + " --scale 0.001 --max-steps 2 --json --require-held");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_FALSE(doc["gripped"]);
  EXPECT_FALSE(doc["held"]);
  EXPECT_EQ(doc["reason"], "the hand did not touch it at the start of the lift");
  EXPECT_TRUE(doc["slip_time"].is_null());
  // Not a usage error: the verdict is the answer, printed in full.
  EXPECT_EQ(doc["steps"].size(), 2u);
}

TEST_F(CliTest, GraspBadMjcfIsOneLineWithTheFileAndExitTwo) {
  const std::string path =
      write("bad.xml", "<mujoco>\n  <worldbody>\n    <bogus/>\n  </worldbody>\n</mujoco>\n");
  const Result r = run("grasp " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  const std::vector<std::string> err = lines(r.err);
  ASSERT_EQ(err.size(), 1u) << r.err;
  EXPECT_EQ(err[0].rfind(path + ": ", 0), 0u) << err[0];
  EXPECT_NE(err[0].find("bogus"), std::string::npos) << err[0];
}

TEST_F(CliTest, GraspMissingSceneOrConfigIsOneLineAndExitTwo) {
  const std::string missing = (dir_ / "nowhere.xml").string();
  Result r = run("grasp " + missing);
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(missing + ": ", 0), 0u) << r.err;
  const std::string config = (dir_ / "nowhere.pairs.json").string();
  r = run("grasp " + shipped_scene("example1") + " --config " + config);
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(config + ": ", 0), 0u) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST_F(CliTest, GraspMjcfWithAMissingMeshFileIsOneLineAndExitTwo) {
  const std::string scene = copy_scene(dir_ / "s", "example1", "cup.obj", "");
  const Result r = run("grasp " + scene + " --max-steps 2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  const std::vector<std::string> err = lines(r.err);
  ASSERT_EQ(err.size(), 1u) << r.err;
  EXPECT_EQ(err[0].rfind(scene + ": ", 0), 0u) << err[0];
  EXPECT_NE(err[0].find("cup.obj"), std::string::npos) << err[0];
}

TEST_F(CliTest, GraspConfigWhosePatternMatchesNothingIsOneLineAndExitTwo) {
  const std::string config =
      write("none.pairs.json", R"({"pairs": [{"a": "geom:nothing*", "b": "body:object"}]})");
  const Result r = run("grasp " + shipped_scene("example1") + " --config " + config);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, config + ": pattern 'geom:nothing*' matches no collidable geom\n");
  // A number that overflows a double is bad JSON, named like every other config error.
  const std::string depth =
      write("depth.pairs.json", R"({"max_depth": 1e999, "pairs": [{"a": "x", "b": "y"}]})");
  const Result d = run("grasp " + shipped_scene("example1") + " --config " + depth);
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_EQ(d.out, "");
  EXPECT_EQ(d.err, depth + ":1: bad JSON: number overflow parsing '1e999'\n");
}

// An open object mesh: the containment check cannot be decided inside it, so the registry warns
// on one line, once (the start check, which cannot see into it either, does not say it again),
// and the grasp goes on with surface contacts (exit 0).
TEST_F(CliTest, GraspWithAnOpenMeshWarnsAndGoesOn) {
  const std::string scene = copy_scene(dir_ / "s", "example1", "", "cup.obj");
  const Result r = run("grasp " + scene + " --max-steps 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> err = lines(r.err);
  ASSERT_EQ(err.size(), 1u) << r.err;
  const std::string config = (dir_ / "s" / "example1.pairs.json").string();
  EXPECT_EQ(err[0].rfind("warning: " + config + ": mesh ", 0), 0u) << err[0];
  EXPECT_NE(err[0].find("'cup' is not closed: "), std::string::npos) << err[0];
  EXPECT_NE(err[0].find("boundary edges"), std::string::npos) << err[0];
  EXPECT_NE(err[0].find("containment inside it is not checked"), std::string::npos) << err[0];
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  graspcd::testing::expect_envelope(doc, 1);
  EXPECT_EQ(doc.at("warnings")[0].at("code"), "mesh_open");
  EXPECT_EQ(doc.at("warnings")[0].at("source"), "mesh");
  EXPECT_EQ(doc.at("warnings")[0].at("count"), 1);
  EXPECT_EQ("warning: " + doc.at("warnings")[0].at("message").get<std::string>(), err[0]);
  EXPECT_EQ(doc.at("steps").size(), 2u);
  EXPECT_EQ(doc.at("nonfinite_skips"), 0);
}

// MuJoCo's own warnings (here a contact buffer too small for the grasp) go to stderr and the
// JSON's warnings, never to stdout after the document or to MUJOCO_LOG.TXT.
TEST_F(CliTest, MujocoWarningsGoToTheSinkNotToStdout) {
  const std::string scene = copy_scene(dir_ / "s", "example1", "", "");
  std::string xml = read_file(scene);
  const std::string size = "<size nconmax=\"300\"";
  ASSERT_NE(xml.find(size), std::string::npos);
  xml.replace(xml.find(size), size.size(), "<size nconmax=\"1\"");
  std::ofstream(scene, std::ios::trunc) << xml;
  // Where MuJoCo would append: the command's working folder, the test's own (other test programs
  // running beside this one may use MuJoCo without a warning hook in theirs).
  const fs::path cwd = dir_ / "cwd";
  fs::create_directories(cwd);
  const fs::path log = cwd / "MUJOCO_LOG.TXT";
  const Result r = run("grasp " + scene + " --max-steps 60 --json", "", cwd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);  // nothing after the document
  graspcd::testing::expect_envelope(doc, -1);
  bool buffer_full = false;
  for (const nlohmann::json& w : doc.at("warnings")) {
    if (w.at("code") == "mujoco_warning" &&
        w.at("message").get<std::string>().find("contact buffer is full") != std::string::npos) {
      buffer_full = true;
      EXPECT_EQ(w.at("source"), "mujoco");
      EXPECT_NE(r.err.find("warning: " + w.at("message").get<std::string>()), std::string::npos)
          << r.err;
    }
  }
  EXPECT_TRUE(buffer_full) << doc.at("warnings");
  EXPECT_FALSE(fs::exists(log));
  EXPECT_TRUE(fs::is_empty(cwd)) << "nothing is written into the working folder";
}

TEST_F(CliTest, GraspHelpDocumentsTheOutput) {
  const Result r = run("grasp --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("step contacts detection_ns"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--json"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--native"), std::string::npos) << r.out;
}

// MuJoCo's errors (mju_error; here its stack, too small for the contacts of the first step) used to
// print "Press Enter to exit ...", append to MUJOCO_LOG.TXT in the current folder and exit 1.
TEST_F(CliTest, AMujocoErrorWhileSteppingIsOneLineNamingTheSceneAndExitTwo) {
  const std::string scene = copy_scene(dir_ / "s", "example1", "", "");
  std::string xml = read_file(scene);
  const std::string size = "<size nconmax=\"300\" njmax=\"900\"/>";
  ASSERT_NE(xml.find(size), std::string::npos);
  xml.replace(xml.find(size), size.size(), "<size nconmax=\"300\" njmax=\"900\" nstack=\"1600\"/>");
  std::ofstream(scene, std::ios::trunc) << xml;
  const fs::path cwd = dir_ / "cwd";  // where MuJoCo would append, the command's own folder
  fs::create_directories(cwd);
  const fs::path log = cwd / "MUJOCO_LOG.TXT";
  const Result r = run("grasp " + scene + " --max-steps 5", "", cwd);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out.find("Press Enter"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, scene + ": MuJoCo error: Stack overflow\n");
  EXPECT_FALSE(fs::exists(log));
  EXPECT_TRUE(fs::is_empty(cwd)) << "nothing is written into the working folder";
}
}  // namespace
