// graspcd judge's library side (study/run_judge.h, docs/run-record.md): a grasp judged from its
// own run record gives the run's verdict fields exactly; the same record with the hold edited so
// that the object sinks 2 cm away from the hand is "dropped", and with the object thrown across
// the scene "ejected"; a record written by the test from the scene's start state (no grasp run)
// judges without a grasp, and records that do not fit the scene are refused naming the line.
#include "graspcd/study/run_judge.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/grasp/grasp.h"
#include "graspcd/grasp/grasp_output.h"
#include "graspcd/io/input_error.h"
#include "graspcd/mujoco/model_loading.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "helpers/temp_dir.h"
#include "helpers/test_scale.h"

namespace graspcd::study {
namespace {

using json = nlohmann::json;

const std::string kMjcf = GRASPCD_MJCF_DIR;

class RunJudgeTest : public graspcd::testing::TempDirTest {
 protected:
  std::vector<json> read_lines(const std::string& path) {
    std::vector<json> out;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) out.push_back(json::parse(line));
    return out;
  }
  std::string write_lines(const std::string& name, const std::vector<json>& lines) {
    std::ostringstream out;
    for (const json& j : lines) out << j.dump() << '\n';
    return write(name, out.str());
  }
};

// The object's free joint: its qpos and qvel addresses.
std::pair<int, int> object_joint(const std::string& scene) {
  const mujoco::ModelPtr m = mujoco::load_model(scene);
  const int body = mj_name2id(m.get(), mjOBJ_BODY, "object");
  const int joint = m->body_jntadr[body];
  return {m->jnt_qposadr[joint], m->jnt_dofadr[joint]};
}

// Changes every hold line of `lines`: edit(i, n, line) for the i-th of n.
void edit_hold(std::vector<json>& lines, const std::function<void(int, int, json&)>& edit) {
  int n = 0;
  for (const json& j : lines) n += j.contains("phase") && j["phase"] == "hold" ? 1 : 0;
  int i = 0;
  for (json& j : lines) {
    if (j.contains("phase") && j["phase"] == "hold") edit(++i, n, j);
  }
}

// Example 2's can, gripped and lifted by the project's hand: about 2,000 physics steps (a few
// seconds in the Release pass, too long for the sanitizer pass).
TEST_F(RunJudgeTest, AGraspJudgedFromItsOwnRecordHasItsVerdictsAndEditsChangeThem) {
  if (graspcd::testing::test_scale() < 1) GTEST_SKIP() << "a whole grasp: Release pass only";
  const std::string scene = kMjcf + "/example2.xml";
  grasp::GraspOptions options;
  options.true_penetration = true;
  options.six_directions = true;
  options.write_run = (dir_ / "run.jsonl").string();
  const grasp::GraspResult run = grasp::run_grasp(scene, options);
  ASSERT_TRUE(run.held) << run.reason;
  // The six-direction test (grasp/six_directions.h): the can the project's hand holds stays in
  // it in all six directions, and its record judges to the same directions (verdict_json).
  ASSERT_EQ(run.directions.size(), 6u);
  for (const grasp::DirectionResult& d : run.directions) {
    EXPECT_TRUE(d.passed) << d.name << " moved " << d.moved;
  }

  const JudgedRun judged = judge_run(scene, options.write_run);
  ASSERT_TRUE(judged.judged) << judged.message;
  const json live = grasp::verdict_json(run);
  const json again = grasp::verdict_json(judged.result);
  EXPECT_EQ(live, again) << live.dump(1) << "\n" << again.dump(1);
  EXPECT_EQ(judged.result.outcome, run.outcome);
  ASSERT_TRUE(judged.contacts.has_value());
  EXPECT_EQ(judged.contacts->phantom, 0);

  // The hold edited: the object sinks to 2 cm below where the hand holds it, and stays there
  // (between the fingers, still touching them): it slipped, the race's "dropped".
  // (Plain names, not a structured binding: the lambdas below capture them.)
  const std::pair<int, int> joint = object_joint(scene);
  const int qpos = joint.first;
  const int qvel = joint.second;
  // The edits are judged without the six directions (the header's parameters and the lines of
  // the directions taken out): the verdicts of the motion are what they change.
  std::vector<json> lines;
  for (json& j : read_lines(options.write_run)) {
    if (j.contains("phase") && j["phase"].get<std::string>().rfind("dir", 0) == 0) continue;
    j.erase("six_directions");
    lines.push_back(std::move(j));
  }
  std::vector<json> sunk = lines;
  edit_hold(sunk, [&](int i, int n, json& j) {
    const double share = std::min(1.0, 2.0 * i / n);
    j["qpos"][qpos + 2] = j["qpos"][qpos + 2].get<double>() - 0.02 * share;
  });
  const JudgedRun slipped = judge_run(scene, write_lines("sunk.jsonl", sunk));
  ASSERT_TRUE(slipped.judged) << slipped.message;
  EXPECT_FALSE(slipped.result.held);
  EXPECT_FALSE(slipped.result.ejected.has_value());
  EXPECT_EQ(slipped.result.outcome, "dropped");
  EXPECT_EQ(slipped.result.reason.rfind("slipped at t = ", 0), 0u) << slipped.result.reason;
  EXPECT_GT(slipped.result.hold_drift, 0.019);

  // The hold edited: the object moves 2 cm down and 2 cm out of the hand, away from every
  // finger: it left the hand behind its path, "dropped" when it let go.
  std::vector<json> away = lines;
  edit_hold(away, [&](int i, int n, json& j) {
    const double share = std::min(1.0, 2.0 * i / n);
    j["qpos"][qpos + 2] = j["qpos"][qpos + 2].get<double>() - 0.02 * share;
    j["qpos"][qpos] = j["qpos"][qpos].get<double>() + 0.2 * share;
  });
  const JudgedRun dropped = judge_run(scene, write_lines("away.jsonl", away));
  ASSERT_TRUE(dropped.judged) << dropped.message;
  EXPECT_FALSE(dropped.result.held);
  EXPECT_FALSE(dropped.result.ejected.has_value());
  EXPECT_EQ(dropped.result.outcome, "dropped");
  ASSERT_TRUE(dropped.result.dropped_at.has_value()) << dropped.result.reason;
  EXPECT_EQ(dropped.result.reason.rfind("dropped at t = ", 0), 0u) << dropped.result.reason;

  // The hold edited: from its middle the object flies sideways at 30 m/s.
  std::vector<json> thrown = lines;
  edit_hold(thrown, [&](int i, int n, json& j) {
    if (2 * i < n) return;
    const double t = (i - n / 2) * 0.002;
    j["qpos"][qpos] = j["qpos"][qpos].get<double>() + 30 * t;
    j["qvel"][qvel] = 30.0;
  });
  const JudgedRun ejected = judge_run(scene, write_lines("thrown.jsonl", thrown));
  ASSERT_TRUE(ejected.judged) << ejected.message;
  EXPECT_FALSE(ejected.result.held);
  ASSERT_TRUE(ejected.result.ejected.has_value());
  EXPECT_EQ(ejected.result.outcome, "ejected");
  EXPECT_EQ(ejected.result.ejected->cause, "speed");
  EXPECT_NEAR(ejected.result.ejected->speed, 30.0, 1.0);
}

// The six-direction test (grasp/six_directions.h) where the grip does not hold: example 2's can
// made slippery (friction 0.05) and five times as dense leaves the hand in the lift and is lost in
// every direction; judged from its record it gives the run's directions. (The held can's six
// directions: AGraspJudgedFromItsOwnRecordHasItsVerdictsAndEditsChangeThem.) A whole grasp: the
// Release pass only.
TEST_F(RunJudgeTest, TheSixDirectionsLoseASlipperyCan) {
  if (graspcd::testing::test_scale() < 1) GTEST_SKIP() << "a whole grasp: Release pass only";
  std::ifstream in(kMjcf + "/example2.xml");
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = xml.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    xml.replace(at, from.size(), to);
  };
  replace("meshdir=\"meshes\"", "meshdir=\"" + kMjcf + "/meshes\"");
  replace("mesh=\"can\" contype=\"1\" conaffinity=\"3\"",
          "mesh=\"can\" contype=\"1\" conaffinity=\"3\" friction=\"0.05 0.005 0.0001\" "
          "density=\"5000\"");
  const std::string scene = write("slippery.xml", xml);
  grasp::GraspOptions options;
  options.true_penetration = true;
  options.six_directions = true;
  options.native = true;
  options.write_run = (dir_ / "six.jsonl").string();
  const grasp::GraspResult lost = grasp::run_grasp(scene, options);
  const JudgedRun judged = judge_run(scene, options.write_run);
  EXPECT_TRUE(judged.judged) << judged.message;
  EXPECT_EQ(grasp::verdict_json(lost), grasp::verdict_json(judged.result));
  EXPECT_FALSE(lost.held);
  ASSERT_EQ(lost.directions.size(), 6u);
  int passed = 0;
  for (const grasp::DirectionResult& d : lost.directions) passed += d.passed ? 1 : 0;
  EXPECT_EQ(passed, 0);
}

// A record the test writes from example 2's start state: the hand never moves, so nothing is
// gripped; the judge measures the motion without running a grasp.
std::vector<json> still_record(const std::string& scene) {
  const mujoco::ModelPtr m = mujoco::load_model(scene);
  const std::vector<double> qpos(m->qpos0, m->qpos0 + m->nq);
  const std::vector<double> qvel(static_cast<std::size_t>(m->nv), 0.0);
  std::vector<json> lines;
  lines.push_back({{"format", "graspcd-run"},
                   {"version", 1},
                   {"scene", scene},
                   {"simulator", "a test"},
                   {"configuration", "still"},
                   {"timestep", m->opt.timestep},
                   {"nq", m->nq},
                   {"nv", m->nv},
                   {"object", "object"},
                   {"hand", "palm"},
                   {"support", "world"},
                   {"contacts", false},
                   {"max_steps", 2}});
  lines.push_back({{"t", 0}, {"phase", "start"}, {"qpos", qpos}, {"qvel", qvel}});
  double t = 0;
  const auto add = [&](const char* phase, int count, int grasp_step) {
    for (int i = 0; i < count; ++i) {
      t += m->opt.timestep;
      json j = {{"t", t}, {"phase", phase}, {"qpos", qpos}, {"qvel", qvel}};
      if (grasp_step > 0) j["grasp_step"] = grasp_step;
      lines.push_back(j);
    }
  };
  add("close", 5, 1);
  add("close", 5, 2);
  for (const char* phase : {"squeeze", "settle", "lift", "hold"}) add(phase, 5, 0);
  lines.push_back({{"end", {{"closing", "max_steps"}, {"status", "ok"}}}});
  return lines;
}

TEST_F(RunJudgeTest, ARecordWrittenByHandIsJudgedFromItsMotion) {
  const std::string scene = kMjcf + "/example2.xml";
  const JudgedRun judged = judge_run(scene, write_lines("still.jsonl", still_record(scene)));
  ASSERT_TRUE(judged.judged) << judged.message;
  EXPECT_EQ(judged.states, 31);
  EXPECT_FALSE(judged.result.held);
  EXPECT_FALSE(judged.result.ejected.has_value());
  EXPECT_EQ(judged.result.outcome, "dropped");
  EXPECT_EQ(judged.result.reason, "the hand did not touch it at the start of the lift");
  EXPECT_FALSE(judged.contacts.has_value());
  // The closing's limit, from the record's end line, said beside the verdict.
  ASSERT_EQ(judged.result.notes.size(), 1u);
  EXPECT_EQ(judged.result.notes[0], "the closing was cut short at grasp step 2 (--max-steps)");
}

// Each refusal: the record's file, the line and what is wrong, in one line.
TEST_F(RunJudgeTest, ARecordThatDoesNotFitTheSceneIsRefusedNamingItsLine) {
  const std::string scene = kMjcf + "/example2.xml";
  const std::vector<json> good = still_record(scene);
  struct Case {
    const char* name;
    std::function<void(std::vector<json>&)> edit;
    std::string line;
    std::string what;
  };
  const std::vector<Case> cases = {
      {"short_qpos", [](std::vector<json>& l) { l[4]["qpos"].erase(0); }, ":5: ", "\"qpos\""},
      {"backwards", [](std::vector<json>& l) { l[6]["t"] = 0.001; }, ":7: ", "time"},
      {"no_body", [](std::vector<json>& l) { l[0]["object"] = "teapot"; }, ":1: ", "teapot"},
      {"bad_phase", [](std::vector<json>& l) { l[14]["phase"] = "close"; }, ":15: ", "phase"},
      {"no_end", [](std::vector<json>& l) { l.pop_back(); }, ":", "end line"},
      {"nq", [](std::vector<json>& l) { l[0]["nq"] = 3; }, ":1: ", "nq"},
  };
  for (const Case& c : cases) {
    std::vector<json> lines = good;
    c.edit(lines);
    const std::string path = write_lines(std::string(c.name) + ".jsonl", lines);
    try {
      judge_run(scene, path);
      ADD_FAILURE() << c.name << ": not refused";
    } catch (const io::InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + c.line, 0), 0u) << c.name << ": " << message;
      EXPECT_NE(message.find(c.what), std::string::npos) << c.name << ": " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
    }
  }
  // A number that is not finite cannot be written as JSON: a writer's "NaN" is bad JSON, refused.
  std::ostringstream text;
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::string line = good[i].dump();
    if (i == 3) line.replace(line.find("\"qvel\":[") + 8, 3, "NaN");
    text << line << '\n';
  }
  const std::string nan = write("nan.jsonl", text.str());
  try {
    judge_run(scene, nan);
    ADD_FAILURE() << "NaN: not refused";
  } catch (const io::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(nan + ":4: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace graspcd::study
