// `graspcd judge SCENE RECORD`: a record that does not fit the scene is one line naming the
// record's file and line, exit code 2; a record that ended "cannot start" is judged "cannot
// start" with its message, in text and JSON. (The verdicts themselves: tests/study/
// run_judge_test.cpp.) Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

// A record header for example 2 (the project's hand, its can on the floor) with `nq`.
std::string header(int nq) {
  return "{\"format\": \"graspcd-run\", \"version\": 1, \"scene\": \"example2\", \"simulator\": "
         "\"a test\", \"configuration\": \"none\", \"timestep\": 0.002, \"nq\": " +
         std::to_string(nq) +
         ", \"nv\": 1, \"object\": \"object\", \"hand\": \"palm\", \"support\": \"world\", "
         "\"contacts\": false, \"max_steps\": 5}\n";
}

TEST_F(CliTest, JudgeRefusesARecordThatDoesNotFitTheSceneInOneLine) {
  const std::string record = write("run.jsonl", header(3) + "{\"end\": {\"status\": \"ok\"}}\n");
  const Result r = run("judge " + shipped_scene("example2") + " " + record);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find(record + ":1: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nq"), std::string::npos) << r.err;

  const std::string bad_json = write("bad.jsonl", "{\"format\": \"graspcd-run\",\n");
  const Result b = run("judge " + shipped_scene("example2") + " " + bad_json + " --json");
  EXPECT_EQ(b.exit_code, 2) << b.err;
  ASSERT_EQ(lines(b.err).size(), 1u) << b.err;
  EXPECT_NE(b.err.find(bad_json + ":1: "), std::string::npos) << b.err;

  const Result missing =
      run("judge " + shipped_scene("example2") + " " + (dir_ / "no.jsonl").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
  EXPECT_NE(missing.err.find("no.jsonl"), std::string::npos) << missing.err;
}

// The scene's nq and nv, read back from the judge's refusal of a record that has them wrong.
std::pair<int, int> scene_sizes(const std::string& err) {
  std::smatch m;
  if (!std::regex_search(err, m, std::regex("the scene has nq = ([0-9]+), nv = ([0-9]+)"))) {
    return {-1, -1};
  }
  return {std::stoi(m[1]), std::stoi(m[2])};
}

TEST_F(CliTest, JudgeSaysARunThatCouldNotStartCannotStart) {
  const std::string scene = shipped_scene("example2");
  const std::string wrong = write("wrong.jsonl", header(3) + "{\"end\": {\"status\": \"ok\"}}\n");
  const auto [nq, nv] = scene_sizes(run("judge " + scene + " " + wrong).err);
  ASSERT_GT(nq, 0);
  // A record of a simulator that refused the scene: no states at all.
  std::string text = header(nq);
  text.replace(text.find("\"nv\": 1"), 7, "\"nv\": " + std::to_string(nv));
  const std::string record = write(
      "refused.jsonl",
      text +
          "{\"end\": {\"status\": \"cannot start\", \"message\": \"the model did not load\"}}\n");
  const Result r = run("judge " + scene + " " + record);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("# outcome: cannot start"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the model did not load"), std::string::npos) << r.out;
  const Result j = run("judge " + scene + " " + record + " --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const nlohmann::json doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["outcome"], "cannot start");
  EXPECT_EQ(doc["message"], "the model did not load");
}

}  // namespace
