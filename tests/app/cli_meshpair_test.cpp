// `graspcd meshpair`: two meshes at a list of poses, text and JSON, against the exact answers.
// Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

TEST_F(CliTest, MeshpairCountsIntersectingPairs) {
  const std::string a = write("a.obj", kMeshA);
  const std::string b = write("b.obj", kMeshB);
  const std::string poses = write("poses.txt", kPoses);
  const std::vector<std::string> expected = {"1 2", "0 0", "1 2", "1 2", "0 0"};
  Result r = run("meshpair " + a + " " + b + " --poses " + poses);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(flags_and_counts(r.out), expected);
  r = run("meshpair " + a + " " + b + " --exact --poses " + poses);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(flags_and_counts(r.out), expected);
  // Poses from stdin by default, other options accepted.
  r = run("meshpair " + a + " " + b + " --method sat --leaf-size 2 --fit hull", kPoses);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(flags_and_counts(r.out), expected);
  // Every method gives the same answers.
  for (const std::string m : {"sat-cached", "perceptron", "perceptron-nodisp", "perceptron-scaled",
                              "perceptron-warm", "neurosat", "neurosat-sticky"}) {
    r = run("meshpair " + a + " " + b + " --cap 50 --switch 10 --method " + m, kPoses);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(flags_and_counts(r.out), expected) << m;
  }
}

TEST_F(CliTest, MeshpairFirstContactCountsAtMostOne) {
  const std::string a = write("a.obj", kMeshA);
  const std::string b = write("b.obj", kMeshB);
  const std::vector<std::string> expected = {"1 1", "0 0", "1 1", "1 1", "0 0"};
  Result r = run("meshpair " + a + " " + b + " --first-contact", kPoses);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(flags_and_counts(r.out), expected);
  r = run("meshpair " + a + " " + b + " --first-contact --exact", kPoses);
  EXPECT_EQ(flags_and_counts(r.out), expected);
}

TEST_F(CliTest, MeshpairErrors) {
  const std::string a = write("a.obj", kMeshA);
  const std::string b = write("b.obj", kMeshB);
  const std::string missing = (dir_ / "missing.obj").string();
  Result r = run("meshpair " + a + " " + missing, kPoses);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, missing + ": cannot open: No such file or directory\n");
  // A pose whose R is not a rotation, after a good one.
  const std::string poses =
      write("p.txt", "1 0 0 0 1 0 0 0 1  0 0 0\n\n1 0 0 0 1 0 0 0 2  0 0 0\n");
  r = run("meshpair " + a + " " + b + " --poses " + poses);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(flags_and_counts(r.out), std::vector<std::string>{"1 2"});
  EXPECT_EQ(r.err, poses +
                       ":3: pose: R is not a rotation (R^T R must equal I to within 1e-09 "
                       "entrywise, and det R > 0)\n");
  expect_usage_error(run("meshpair " + a + " " + b + " --fit box", kPoses));
  expect_usage_error(run("meshpair " + a + " " + b + " --leaf-size 0", kPoses));
  expect_usage_error(run("meshpair " + a + " " + b + " --poses", kPoses));
}

TEST_F(CliTest, MeshpairOnTheCubeCupAgreesWithExact) {
  const fs::path cup = fs::path(GRASPCD_MODELS_DIR) / "objects" / "mujoco" / "cube_cup.obj";
  if (!fs::exists(cup)) GTEST_SKIP() << "model not found: " << cup;
  const std::string poses = write("p.txt",
                                  "1 0 0 0 1 0 0 0 1  0 0 0\n"
                                  "1 0 0 0 1 0 0 0 1  0.03 0.01 0.02\n"
                                  "0 -1 0 1 0 0 0 0 1  0.02 0 0.05\n"
                                  "1 0 0 0 1 0 0 0 1  1 0 0\n");
  const std::string args = "meshpair " + cup.string() + " " + cup.string() + " --poses " + poses;
  const Result fast = run(args);
  const Result exact = run(args + " --exact");
  EXPECT_EQ(fast.exit_code, 0) << fast.err;
  EXPECT_EQ(exact.exit_code, 0) << exact.err;
  const std::vector<std::string> answers = flags_and_counts(fast.out);
  ASSERT_EQ(answers.size(), 4u);
  EXPECT_EQ(answers, flags_and_counts(exact.out));
  EXPECT_EQ(answers[0].substr(0, 2), "1 ");
  EXPECT_EQ(answers[3], "0 0");
}

// Meshpair's table as one JSON document, the same answers as the text, with the
// mesh hygiene warning (tagged "mesh", its face counted from 1 in the file) in the envelope.
TEST_F(CliTest, MeshpairPrintsItsTableAsJson) {
  const std::string a = write("a.obj", cube_obj() + "f 1 2 1\n");  // a 13th face of zero area
  const std::string b = write("b.obj", cube_obj());
  const std::string poses =
      write("p.txt", "1 0 0 0 1 0 0 0 1  0.5 0 0\n1 0 0 0 1 0 0 0 1  3 0 0\n");
  const Result text = run("meshpair " + a + " " + b + " --poses " + poses);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const Result r = run("meshpair " + a + " " + b + " --poses " + poses + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  graspcd::testing::expect_envelope(doc, 1);
  EXPECT_EQ(doc["method"], "sat");
  ASSERT_EQ(doc["answers"].size(), 2u);
  const std::vector<std::string> rows = lines(text.out);
  ASSERT_EQ(rows.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const nlohmann::json& answer = doc["answers"][i];
    EXPECT_EQ(rows[i].rfind(std::string(answer["intersect"] ? "1 " : "0 ") +
                                std::to_string(answer["pairs"].get<int>()) + " ",
                            0),
              0u)
        << rows[i];
  }
  EXPECT_TRUE(doc["answers"][0]["intersect"]);
  EXPECT_FALSE(doc["answers"][1]["intersect"]);
  EXPECT_EQ(doc["warnings"][0]["source"], "mesh");
  EXPECT_NE(doc["warnings"][0]["message"].get<std::string>().find(
                "(faces 13 counted from 1 in the file's order"),
            std::string::npos)
      << doc["warnings"][0]["message"];
}
}  // namespace
