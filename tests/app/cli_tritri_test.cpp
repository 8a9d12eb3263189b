// `graspcd tritri`: triangle pairs from a file or stdin, with the exact test beside.
// Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

TEST_F(CliTest, TritriAnswersFromAFile) {
  const std::string path = write("t.txt", std::string(kTouching) + kSeparated + kTouching);
  const Result r = run("tritri " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1\n0\n1\n");
  EXPECT_EQ(r.err, "");
}

TEST_F(CliTest, TritriReadsStdinByDefaultAndWithDash) {
  const std::string input = std::string(kSeparated) + kTouching;
  EXPECT_EQ(run("tritri", input).out, "0\n1\n");
  EXPECT_EQ(run("tritri -", input).out, "0\n1\n");
}

TEST_F(CliTest, TritriExactAgrees) {
  const std::string path = write("t.txt", std::string(kTouching) + kSeparated);
  const Result r = run("tritri --exact " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1\n0\n");
}

TEST_F(CliTest, CommentsBlankLinesAndCrlfAreAccepted) {
  const std::string path = write("crlf.txt",
                                 "# touching, then separated\r\n"
                                 "\r\n"
                                 "0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 0 1\r\n"
                                 "  # an indented comment\r\n"
                                 "0x0p0 0 0 0x1p0 0 0 0 1 0  0 0 1 0 0 2 1e0 0 2\r\n");
  const Result r = run("tritri " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1\n0\n");
}

TEST_F(CliTest, EmptyInputHasNoAnswers) {
  const Result r = run("tritri", "");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
}
}  // namespace
