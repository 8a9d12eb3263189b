// `graspcd --version`, `--help` of each subcommand, and the example inputs of data/.
// Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

TEST_F(CliTest, VersionListsTheLibraries) {
  const Result r = run("--version");
  EXPECT_EQ(r.exit_code, 0);
  const std::vector<std::string> out = lines(r.out);
  ASSERT_GE(out.size(), 4u) << r.out;
  EXPECT_TRUE(std::regex_match(out[0], std::regex("graspcd [0-9]+\\.[0-9]+\\.[0-9]+"))) << out[0];
  EXPECT_EQ(out[1].rfind("MuJoCo ", 0), 0u);
  EXPECT_TRUE(std::regex_match(out[2], std::regex("Eigen [0-9]+\\.[0-9]+\\.[0-9]+"))) << out[2];
  EXPECT_TRUE(std::regex_match(out[3], std::regex("CGAL [0-9]+\\.[0-9]+(\\.[0-9]+)?"))) << out[3];
  // The commit this build was made from (git describe, "-dirty" for a changed tree; "unknown"
  // outside git).
  EXPECT_TRUE(std::regex_match(out.back(), std::regex("commit: [^ ]+"))) << out.back();
}

TEST_F(CliTest, HelpTeachesEachSubcommand) {
  Result r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* sub : {"tritri", "boxbox", "meshpair"}) {
    EXPECT_NE(r.out.find(sub), std::string::npos) << sub;
  }
  r = run("tritri --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("18 numbers"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Example"), std::string::npos) << r.out;
  r = run("boxbox --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("30 numbers"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("perceptron-warm"), std::string::npos) << r.out;
  r = run("meshpair --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("12 numbers"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
}

// The example inputs of docs/design.md ("The command line") stay valid.
TEST_F(CliTest, ExampleInputsRun) {
  const fs::path data = fs::path(GRASPCD_DATA_DIR) / "examples";
  Result r = run("tritri " + (data / "tritri.txt").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(r.out.empty());
  r = run("boxbox " + (data / "boxbox.txt").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(r.out.empty());
}
}  // namespace
