// The study driver: the quick study as a smoke test of the report's files and of the
// answer hashes, the sweep's shards against one unsharded run, bad options, and the error counts
// of replay.h on fabricated answers.
#include "graspcd/study/study.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "graspcd/mujoco/model_loading.h"
#include "graspcd/study/recording.h"
#include "graspcd/study/replay.h"
#include "helpers/command_test.h"
#include "helpers/envelope_check.h"
#include "helpers/test_scale.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using graspcd::testing::Outcome;
using graspcd::testing::read_file;

class StudyTest : public graspcd::testing::CommandTest {};

TEST_F(StudyTest, QuickStudyWritesTheReportAndEveryMethodAgreesWithCgal) {
  const fs::path out = dir_ / "quick";
  // The sanitizer pass (GRASPCD_TEST_SCALE < 1, docs/testing.md) times one replay per method
  // instead of --quick's 3: every replay's answers are checked all the same.
  const std::size_t repeats = graspcd::testing::test_scale() < 1 ? 1 : 3;
  // Not a terminal: a progress line every GRASPCD_PROGRESS_SECONDS (app/progress.h), here longer
  // than the run, so none; and one final line.
  ::setenv("GRASPCD_PROGRESS_SECONDS", "100000", 1);
  const Outcome r = graspcd("study --quick --out '" + out.string() + "'" +
                            (repeats == 3 ? "" : " --repeats " + std::to_string(repeats)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ::unsetenv("GRASPCD_PROGRESS_SECONDS");
  EXPECT_EQ(r.err.find("[study] recorded example1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[study] wrote " + out.string() + "\n"), std::string::npos) << r.err;
  for (const char* f : {"study.json", "table1.csv", "box_hand.csv", "sweep.json", "sweep.csv"})
    EXPECT_GT(fs::file_size(out / f), 100u) << f;

  const json study = load(out / "study.json");
  graspcd::testing::expect_envelope(study, -1);
  graspcd::testing::expect_envelope(load(out / "sweep.json"), -1);
  ASSERT_EQ(study["recordings"].size(), 1u);
  const json& rec = study["recordings"][0];
  EXPECT_TRUE(rec["held"].get<bool>()) << "the recorded grasp lifts and holds the cup";
  const std::string truth = rec["truth_pairs_hash"];
  ASSERT_GE(study["table1"]["methods"].size(), 3u);
  // The perceptron methods that run to their cap replay 2 times at most (--perceptron-repeats).
  EXPECT_EQ(study["perceptron_repeats"].get<std::size_t>(), std::min<std::size_t>(repeats, 2));
  // The executable hands FCL's two trees to the study as Table 1's last rows (study.h, peers); a
  // build without FCL (GRASPCD_WITH_FCL=OFF) has no FCL row.
  const json& methods = study["table1"]["methods"];
#if GRASPCD_STUDY_FCL_ROWS
  EXPECT_EQ(methods[methods.size() - 2]["name"], "fcl-obb");
  EXPECT_EQ(methods.back()["name"], "fcl-rss");
#else
  for (const json& m : methods)
    EXPECT_EQ(m["name"].get<std::string>().rfind("fcl-", 0), std::string::npos) << m["name"];
#endif
  for (const json& m : study["table1"]["methods"]) {
    const json& x = m["examples"][0];
    EXPECT_EQ(x["pairs_hash"].get<std::string>(), truth) << m["name"];
    EXPECT_TRUE(x["agrees_with_cgal"].get<bool>()) << m["name"];
    EXPECT_EQ(x["repeats_ms"].size(), repeats) << "--quick: 3 repeats (1 when scaled down)";
    EXPECT_EQ(x["repeats"].get<std::size_t>(), repeats) << m["name"];
    EXPECT_LE(x["min_ms"].get<double>(), x["median_ms"].get<double>());
    EXPECT_LE(x["median_ms"].get<double>(), x["max_ms"].get<double>());
  }
  // Contacts happen in the recording: the hash is not the hash of "no contact anywhere".
  std::uint64_t tri_pairs = 0;
  for (const json& m : study["table1"]["methods"])
    tri_pairs += m["examples"][0]["counters"]["tri_pairs"].get<std::uint64_t>();
  EXPECT_GT(tri_pairs, 0u);

  const json& box = study["box_hand"];
  EXPECT_TRUE(box["no_false_separated"].get<bool>());
  EXPECT_GT(box["overlapping_exact"].get<std::uint64_t>(), 0u) << "the box hand touches";
  for (const json& m : box["methods"]) {
    EXPECT_EQ(m["false_separated"].get<std::uint64_t>(), 0u) << m["name"];
    EXPECT_EQ(m["segments"]["B"]["passes"].size(), box["steps"].get<std::size_t>());
  }

  // The exact points of the sweep never miss or invent a contact.
  const json sweep = load(out / "sweep.json");
  for (const json& c : sweep["configs"]) {
    const std::string name = c["name"];
    if (name.find("naive") != std::string::npos || name.find("plain") != std::string::npos ||
        name == "sat float nodes")
      continue;
    EXPECT_EQ(c["missed"].get<std::uint64_t>(), 0u) << name;
    EXPECT_EQ(c["false_contacts"].get<std::uint64_t>(), 0u) << name;
    EXPECT_EQ(c["false_tri_pairs"].get<std::uint64_t>(), 0u) << name;
    if (!c["first_contact_mode"].get<bool>()) {
      EXPECT_EQ(c["missed_tri_pairs"].get<std::uint64_t>(), 0u) << name;
      EXPECT_EQ(c["position_error_max_mm"].get<double>(), 0.0) << name;
    }
  }

  // The report: figures and REPORT.md from Debian's python3 with matplotlib.
  const Outcome p =
      run("/usr/bin/python3 '" GRASPCD_SOURCE_DIR "/report/make_report.py' '" + out.string() + "'");
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const std::string report = read_file(out / "REPORT.md");
  EXPECT_NE(report.find("## Table 1"), std::string::npos);
  EXPECT_NE(report.find(truth), std::string::npos) << "the report quotes CGAL's hash";
  EXPECT_NE(report.find("- Commit: `" + graspcd::provenance().commit + "` ("), std::string::npos)
      << "the report names the commit its study was built from";
  // The paper's own seconds stand beside ours (its Table 1, SAT on example 1).
  EXPECT_NE(report.find("| 75.18 [1] |"), std::string::npos);
  for (const char* f : {"fig13_time_per_step.png", "fig14_passes.png", "fig15_time_saved.png",
                        "table1_ratios.png", "sweep_pareto.png"}) {
    const fs::path png = out / "figures" / f;
    ASSERT_TRUE(fs::exists(png)) << f;
    EXPECT_EQ(read_file(png).substr(1, 3), "PNG") << f;
  }
  // The pictures: a trajectory file per grasp, drawn into the report's own section.
  const json traj = load(out / "trajectories" / "example1.json");
  EXPECT_EQ(traj["grasp_steps"], rec["grasp_steps"]);
  EXPECT_EQ(traj["times_ns"].size(), study["table1"]["methods"].size())
      << "per-step times of every Table 1 method";
  EXPECT_TRUE(fs::exists(out / "trajectories" / "hand_boxes.json"));
  EXPECT_NE(report.find("## Pictures of the grasps and the trees"), std::string::npos);
  for (const char* f : {"fig18_example1.png", "fig17_obb_depths.png", "contacts_native.png",
                        "fig12_box_hand.png"}) {
    EXPECT_NE(report.find(std::string("figures/") + f), std::string::npos) << f;
    EXPECT_EQ(read_file(out / "figures" / f).substr(1, 3), "PNG") << f;
  }
}

// The committed reference report/REPORT.md is what make_report.py draws from report/data (every
// section: the study's, stress, performance, real hands), but for the pictures' section, which
// is drawn from trajectory files that report/data does not keep (report/README.md).
TEST_F(StudyTest, ReferenceReportIsWhatMakeReportDrawsFromItsData) {
  if (graspcd::testing::test_scale() < 1) {
    GTEST_SKIP() << "GRASPCD_TEST_SCALE < 1: Python only, checked in the Release pass";
  }
  const fs::path source = GRASPCD_SOURCE_DIR "/report";
  const fs::path data = dir_ / "reference";
  fs::create_directories(data);
  for (const fs::directory_entry& e : fs::directory_iterator(source / "data")) {
    fs::copy_file(e.path(), data / e.path().filename());
  }
  const Outcome p = run("/usr/bin/python3 '" + (source / "make_report.py").string() + "' '" +
                        data.string() + "'");
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const std::string drawn = read_file(data / "REPORT.md");
  for (const char* section :
       {"## Table 1", "## Numerical stability (stress)", "## Performance against FCL and MuJoCo",
        "## Real hands and objects", "## Contacts and the solver",
        "## The race: the hull, convex decompositions and graspcd", "## Reproduce"}) {
    EXPECT_NE(drawn.find(section), std::string::npos) << section;
  }
  std::string committed = read_file(source / "REPORT.md");
  const std::size_t pictures = committed.find("## Pictures of the grasps and the trees");
  ASSERT_NE(pictures, std::string::npos);
  const std::size_t next = committed.find("\n## ", pictures);
  ASSERT_NE(next, std::string::npos);
  committed.erase(pictures, next + 1 - pictures);
  EXPECT_TRUE(committed == drawn)
      << "report/REPORT.md is not what make_report.py draws from report/data: redraw it "
         "(report/README.md)";
}

TEST_F(StudyTest, MergedShardsGiveTheAnswersOfOneUnshardedSweep) {
  if (graspcd::testing::test_scale() < 1) {
    // Three more quick sweeps (2.5 min under the sanitizers): QuickStudy runs the same sweep code
    // there; the merge is checked in the Release pass.
    GTEST_SKIP() << "GRASPCD_TEST_SCALE < 1: the sweep runs under the sanitizers in QuickStudy";
  }
  const fs::path whole = dir_ / "whole";
  const fs::path parts = dir_ / "parts";
  ASSERT_EQ(
      graspcd("study --quick --no-table --repeats 1 --out '" + whole.string() + "'").exit_code, 0);
  for (int i = 0; i < 2; ++i) {
    const Outcome r = graspcd("study --quick --repeats 1 --shard " + std::to_string(i) +
                              "/2 --out '" + parts.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto shard = [&](int i) {
    return "'" + (parts / ("sweep.shard-" + std::to_string(i) + "-of-2.json")).string() + "'";
  };
  const Outcome m = graspcd("study --merge " + shard(0) + " " + shard(1) + " --out '" +
                            (dir_ / "merged").string() + "'");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const json a = load(whole / "sweep.json");
  const json b = load(dir_ / "merged" / "sweep.json");
  ASSERT_EQ(a["configs"].size(), b["configs"].size());
  ASSERT_GE(a["configs"].size(), 6u);
  EXPECT_EQ(a["recordings"], b["recordings"]) << "the same recorded poses";
  for (std::size_t i = 0; i < a["configs"].size(); ++i) {
    const json& x = a["configs"][i];
    const json& y = b["configs"][i];
    EXPECT_EQ(x["name"], y["name"]);
    for (const char* k : {"missed", "false_contacts", "missed_tri_pairs", "false_tri_pairs",
                          "first_contact_step_error_sum", "counters"})
      EXPECT_EQ(x[k], y[k]) << x["name"] << " " << k;
    EXPECT_EQ(x["examples"][0]["pairs_hash"], y["examples"][0]["pairs_hash"]) << x["name"];
  }
  // A missing shard is an error that names the shard's file and a configuration, exit code 2.
  const Outcome missing =
      graspcd("study --merge " + shard(1) + " --out '" + (dir_ / "bad").string() + "'");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("shard 0 of 2 (sweep.shard-0-of-2.json) is missing: configuration 0"),
            std::string::npos)
      << missing.err;
  EXPECT_NE(missing.err.find("is in no shard given"), std::string::npos) << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1);
  // The same shard twice.
  const Outcome twice = graspcd("study --merge " + shard(0) + " " + shard(0) + " --out '" +
                                (dir_ / "bad").string() + "'");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("appears twice"), std::string::npos) << twice.err;
}

TEST_F(StudyTest, BadOptionsAreOneLineErrorsWithExitCode2) {
  for (const char* args :
       {"study --shard 3/3", "study --shard 1", "study --shard a/b", "study --repeats 0",
        "study --perceptron-repeats 0", "study --merge /nonexistent/shard.json",
        "study --no-table --no-sweep"}) {
    const Outcome r = graspcd(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  // A scene folder without the scenes: the error names the missing file.
  const Outcome r =
      graspcd("study --quick --mjcf '" + dir_.string() + "' --out '" + (dir_ / "o").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("example1.xml"), std::string::npos) << r.err;
}

TEST(ParseShard, AcceptsIOverNOnly) {
  const graspcd::study::Shard s = graspcd::study::parse_shard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  for (const char* bad : {"5/5", "-1/2", "1/0", "1/2x", "x1/2", "12", ""})
    EXPECT_THROW(graspcd::study::parse_shard(bad), std::invalid_argument) << bad;
}

// compare() on fabricated answers: one hidden hit is one missed contact, one invented triangle
// pair one false pair.
TEST(CompareAnswers, CountsWhatDiffersFromTheTruth) {
  using namespace graspcd;
  using namespace graspcd::study;
  const std::string scene = std::string(GRASPCD_SOURCE_DIR) + "/mjcf/example1.xml";
  const MeshScene ms(scene);
  const mujoco::ModelPtr model = mujoco::load_model(scene);
  mjData* d = mj_makeData(model.get());
  mj_forward(model.get(), d);
  Recording rec;
  rec.scene = scene;
  rec.ngeom = model->ngeom;
  for (int s = 0; s < 2; ++s) {
    rec.xpos.emplace_back(d->geom_xpos, d->geom_xpos + 3 * model->ngeom);
    rec.xmat.emplace_back(d->geom_xmat, d->geom_xmat + 9 * model->ngeom);
  }
  mj_deleteData(d);
  const Answers truth = exact_answers(ms, rec);
  const auto querier = make_detector_querier(Method::kSat, {}, QueryMode::kAllContacts);
  const ReplayStats st = replay(ms, rec, *querier, 2);
  EXPECT_EQ(st.answers.pairs_hash, truth.pairs_hash);
  EXPECT_EQ(st.total_ns.size(), 2u);
  ErrorStats e = compare(ms, rec, st.answers, truth, false);
  EXPECT_EQ(e.missed + e.false_contacts + e.missed_tri_pairs + e.false_tri_pairs, 0u);

  Answers fake_truth = truth;
  fake_truth.hit[1] = 1;  // step 0, pair 1 (open hand: no real contact)
  ASSERT_EQ(truth.hit[1], 0);
  fake_truth.tri_pairs[1] = {{0, 0}};
  e = compare(ms, rec, st.answers, fake_truth, false);
  EXPECT_EQ(e.missed, 1u);
  EXPECT_EQ(e.false_contacts, 0u);
  EXPECT_EQ(e.first_contact_error_max, 3 - 1) << "seen at step 1 instead of never (step 3)";

  Answers extra = truth;
  extra.hit[1] = 1;
  extra.tri_pairs[1] = {{0, 0}, {1, 2}};
  e = compare(ms, rec, extra, fake_truth, false);
  EXPECT_EQ(e.missed, 0u);
  EXPECT_EQ(e.false_tri_pairs, 1u);
  EXPECT_EQ(e.missed_tri_pairs, 0u);
  e = compare(ms, rec, fake_truth, extra, false);
  EXPECT_EQ(e.missed_tri_pairs, 1u);
  EXPECT_EQ(compare(ms, rec, fake_truth, extra, true).missed_tri_pairs, 0u)
      << "first-contact mode finds one pair by design";
}

}  // namespace
