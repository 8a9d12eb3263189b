// The stress suite: a reduced run keeps every method's contract (no false separation,
// false overlaps inside their band), every class really holds both truths (so the contract could
// fail), a deliberately broken separator is caught, the cases are deterministic, and the command
// line prints the table and JSON with the right exit codes.
#include "graspcd/study/stress.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "graspcd/core/sat.h"
#include "helpers/envelope_check.h"
#include "helpers/temp_dir.h"
#include "helpers/test_scale.h"

namespace graspcd::study {
namespace {

// Cases per class of the reduced run: 600 each at scale 1 (the sanitizer pass: 60).
int reduced_cases() { return testing::scaled(600, 40); }

// One row per class and method.
std::size_t row_count() {
  std::size_t rows = 0;
  for (const StressClass& cls : stress_classes()) {
    rows += cls.kind == StressKind::kBoxes ? default_box_methods().size()
                                           : default_triangle_methods().size();
  }
  return rows;
}

const StressReport& reduced_report() {
  static const StressReport report = [] {
    StressOptions options;
    options.cases = reduced_cases();
    return run_stress(options);
  }();
  return report;
}

TEST(StressTest, ReducedRunHasNoFalseSeparationAndStaysInBand) {
  const StressReport& report = reduced_report();
  ASSERT_EQ(report.rows.size(),
            6 * default_box_methods().size() + 8 * default_triangle_methods().size());
  for (const StressRow& row : report.rows) {
    SCOPED_TRACE(row.class_name + " / " + row.method);
    EXPECT_EQ(row.cases, reduced_cases());
    if (row.reference) continue;
    EXPECT_EQ(row.false_separated, 0);
    EXPECT_EQ(row.outside_band, 0);
    if (row.kind == StressKind::kTriangles) {
      EXPECT_EQ(row.false_overlap, 0) << "exact test";
    }
  }
  EXPECT_FALSE(report.contract_broken());
}

// A class whose pairs all overlap (or none do) could not catch a false separation (or a false
// overlap): each must hold both, with neither below a tenth.
TEST(StressTest, EveryClassHoldsOverlappingAndDisjointPairs) {
  std::map<std::string, const StressRow*> first_row;
  for (const StressRow& row : reduced_report().rows) first_row.emplace(row.class_name, &row);
  ASSERT_EQ(first_row.size(), stress_classes().size());
  for (const auto& [name, row] : first_row) {
    SCOPED_TRACE(name);
    EXPECT_GE(row->overlapping * 10, row->cases);
    EXPECT_GE((row->cases - row->overlapping) * 10, row->cases);
  }
}

// The box methods' false overlaps: the SAT family's inside the SAT's slack (checked per pair as
// outside_band above); the perceptrons' come with the cap, which every overlapping pair reaches.
TEST(StressTest, PerceptronsReachTheirCapOnEveryOverlappingPair) {
  for (const StressRow& row : reduced_report().rows) {
    if (row.kind != StressKind::kBoxes || row.method == "sat" || row.method == "sat-cached") {
      continue;
    }
    SCOPED_TRACE(row.class_name + " / " + row.method);
    EXPECT_GE(row.perceptron_capped, row.overlapping);
  }
}

// SAT on boxes shrunk by 1e-6 of their size: a separator with the slack's sign turned. The gap
// class must catch it as false separations (and the contract as broken).
TEST(StressTest, ShrunkBoxesAreCaughtAsFalseSeparations) {
  BoxMethod broken;
  broken.name = "sat-shrunk";
  broken.test = [](const Obb& a, const Obb& b) {
    const auto shrunk = [](Obb box) {
      box.half *= 1.0 - 1e-6;
      return box;
    };
    return BoxAnswer{sat_disjoint(shrunk(a), shrunk(b)), false};
  };
  StressOptions options;
  options.cases = testing::scaled(400, 100);
  options.classes = {"box_gap"};
  options.box_methods = {broken};
  const StressReport report = run_stress(options);
  ASSERT_EQ(report.rows.size(), 1u);
  EXPECT_GT(report.rows[0].false_separated, 0);
  EXPECT_TRUE(report.contract_broken());
}

// The band check can fail: a "SAT" that never separates leaves gaps of up to a tenth of the size
// unproven, far outside the slack.
TEST(StressTest, FalseOverlapsFarOutsideTheSlackLeaveTheBand) {
  BoxMethod lazy;
  lazy.name = "never-separates";
  lazy.test = [](const Obb&, const Obb&) { return BoxAnswer{false, false}; };
  lazy.sat_band = true;
  StressOptions options;
  options.cases = testing::scaled(200, 50);
  options.classes = {"box_scale"};
  options.box_methods = {lazy};
  const StressReport report = run_stress(options);
  ASSERT_EQ(report.rows.size(), 1u);
  EXPECT_EQ(report.rows[0].false_separated, 0);
  EXPECT_GT(report.rows[0].outside_band, 0);
  EXPECT_GT(report.rows[0].max_false_overlap_gap_rel, 1e-4);
  EXPECT_TRUE(report.contract_broken());
}

TEST(StressTest, CasesDependOnTheSeedAlone) {
  for (std::size_t index = 0; index < stress_classes().size(); ++index) {
    SCOPED_TRACE(stress_classes()[index].name);
    if (stress_classes()[index].kind == StressKind::kBoxes) {
      const auto x = make_box_cases(index, 20, 5), y = make_box_cases(index, 30, 5);
      const auto z = make_box_cases(index, 20, 6);
      for (std::size_t i = 0; i < x.size(); ++i) {
        EXPECT_EQ(x[i].b.center, y[i].b.center);
        EXPECT_EQ(x[i].a.axes, y[i].a.axes);
      }
      EXPECT_NE(x[0].b.center, z[0].b.center);
    } else {
      const auto x = make_triangle_cases(index, 20, 5), y = make_triangle_cases(index, 30, 5);
      const auto z = make_triangle_cases(index, 20, 6);
      for (std::size_t i = 0; i < x.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
          EXPECT_EQ(x[i].t1.v[k], y[i].t1.v[k]);
          EXPECT_EQ(x[i].t2.v[k], y[i].t2.v[k]);
        }
      }
      EXPECT_NE(x[0].t2.v[0], z[0].t2.v[0]);
    }
  }
}

TEST(StressTest, UnknownClassIsAnError) {
  StressOptions options;
  options.classes = {"no_such_class"};
  EXPECT_THROW(run_stress(options), std::invalid_argument);
}

// ---- The command line --------------------------------------------------------------------------

namespace fs = std::filesystem;

class StressCommandTest : public testing::TempDirTest {
 protected:
  struct Outcome {
    int exit_code = -1;
    std::string out, err;
  };
  Outcome graspcd(const std::string& args) {
    const fs::path out = dir_ / "out.txt", err = dir_ / "err.txt";
    const std::string line = std::string("'") + GRASPCD_EXE + "' " + args + " > '" + out.string() +
                             "' 2> '" + err.string() + "'";
    const int status = std::system(line.c_str());
    Outcome r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read(out);
    r.err = read(err);
    return r;
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
};

TEST_F(StressCommandTest, JsonHasEveryClassAndMethodAndExitsZero) {
  const Outcome r = graspcd("stress --json --cases 20 --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("[stress] box_scale: 20 cases"), std::string::npos) << "progress";
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["seed"], 3);
  graspcd::testing::expect_envelope(j);
  EXPECT_EQ(j["contract_broken"], false);
  EXPECT_EQ(j["classes"].size(), stress_classes().size());
  EXPECT_EQ(j["rows"].size(), row_count());
  for (const auto& row : j["rows"]) {
    EXPECT_EQ(row["cases"], 20);
    EXPECT_TRUE(row.contains("max_false_overlap_gap_rel"));
    EXPECT_TRUE(row.contains("perceptron_capped"));
  }
}

TEST_F(StressCommandTest, TableHasAHeaderAndOneLinePerRow) {
  const Outcome r = graspcd("stress --cases 10");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("class", 0), 0u);
  EXPECT_NE(r.out.find("false_separated"), std::string::npos);
  EXPECT_EQ(static_cast<std::size_t>(std::count(r.out.begin(), r.out.end(), '\n')),
            row_count() + 1);
}

TEST_F(StressCommandTest, HelpExplainsClassesAndColumnsAndBadOptionsExitTwo) {
  const Outcome help = graspcd("stress --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const StressClass& cls : stress_classes()) {
    EXPECT_NE(help.out.find(cls.name), std::string::npos) << cls.name;
  }
  EXPECT_NE(help.out.find("outside_band"), std::string::npos);
  EXPECT_EQ(graspcd("stress --cases 0").exit_code, 2);
  EXPECT_EQ(graspcd("stress --seed x").exit_code, 2);
}

}  // namespace
}  // namespace graspcd::study
