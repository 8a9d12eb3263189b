// Runs the real `graspcd` binary (GRASPCD_EXE) on small inputs and checks the command-line contract
// of docs/design.md: answers, exit codes, and the exact one-line error messages.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/envelope_check.h"
#include "support/temp_dir.h"

namespace {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Splits text into lines (without their '\n').
std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

class CliTest : public graspcd::testing::TempDirTest {
 protected:
  // Runs `graspcd ARGS` with `stdin_text` on standard input. ARGS is passed to the shell as is.
  // `cwd`: the working folder (default: the test's).
  Result run(const std::string& args, const std::string& stdin_text = "",
             const fs::path& cwd = {}) {
    const std::string in = write("stdin.txt", stdin_text);
    const fs::path out = dir_ / "stdout.txt";
    const fs::path err = dir_ / "stderr.txt";
    const std::string command = (cwd.empty() ? "" : "cd '" + cwd.string() + "' && ") + "'" +
                                GRASPCD_EXE + "' " + args + " < '" + in + "' > '" + out.string() +
                                "' 2> '" + err.string() + "'";
    const int status = std::system(command.c_str());
    Result r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_file(out);
    r.err = read_file(err);
    return r;
  }
};

// GRASPCD_TEST_SCALE < 1: the sanitizer pass, where a grasp takes ten times as long.
bool sanitizer_pass() {
  const char* scale = std::getenv("GRASPCD_TEST_SCALE");
  return scale != nullptr && std::strtod(scale, nullptr) < 1;
}

// Triangle pairs: T1 in the plane z = 0, T2 sharing its vertex at the origin / lifted by 1.
const char* const kTouching = "0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 0 1\n";
const char* const kSeparated = "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 1 0 2\n";
// Unit cubes (half-extent 1) at x = 0 and x = 2.5 / 2 (touching faces) / 1 (overlapping).
const char* const kBoxesApart = "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  2.5 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n";
const char* const kBoxesTouch = "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  2 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n";
const char* const kBoxesOverlap = "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  1 0 0 0 -1 0 1 0 0 0 0 1 1 1 1\n";

// --- tritri -------------------------------------------------------------------------------------

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

// --- errors: FILE:LINE: message, exit 2, earlier answers kept ------------------------------------

TEST_F(CliTest, MalformedNumberKeepsEarlierAnswers) {
  const std::string path =
      write("bad.txt", std::string(kTouching) + "# c\n" + kSeparated +
                           "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 1.0abc 0 2\n" + kTouching);
  const Result r = run("tritri " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "1\n0\n");
  EXPECT_EQ(r.err, path + ":4: malformed number \"1.0abc\"\n");
}

TEST_F(CliTest, NanAndInfAreErrors) {
  const std::string nan = write("nan.txt", "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 nan 0 2\n");
  Result r = run("tritri " + nan);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, nan + ":1: non-finite number \"nan\" (nan and inf are not accepted)\n");
  const std::string inf = write("inf.txt", std::string(kSeparated) +
                                               "\n0 0 0 1 0 0 0 1 0 0 0 1 "
                                               "0 0 2 1 0 -Infinity\n");
  r = run("tritri " + inf);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "0\n");
  EXPECT_EQ(r.err, inf + ":3: non-finite number \"-Infinity\" (nan and inf are not accepted)\n");
}

// Every spelling strtod reads as non-finite, and overflow, in each command's text input.
TEST_F(CliTest, NonFiniteNumbersAreErrorsInEveryCommand) {
  const std::string a = write("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  for (const std::string token : {"nan", "NaN", "-nan", "nan(0x1)", "inf", "-INF", "infinity"}) {
    const std::string expected =
        ":1: non-finite number \"" + token + "\" (nan and inf are not accepted)\n";
    Result r = run("tritri", "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 " + token + " 0 2\n");
    EXPECT_EQ(r.exit_code, 2) << token;
    EXPECT_EQ(r.err, "<stdin>" + expected);
    r = run("boxbox", "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  2 0 0 1 0 0 0 1 0 0 0 1 1 1 " + token + "\n");
    EXPECT_EQ(r.exit_code, 2) << token;
    EXPECT_EQ(r.err, "<stdin>" + expected);
    r = run("meshpair " + a + " " + a, "1 0 0 0 1 0 0 0 1  0 " + token + " 0\n");
    EXPECT_EQ(r.exit_code, 2) << token;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "<stdin>" + expected);
  }
  const std::string overflow = ":1: number \"1e999\" overflows a double\n";
  Result r = run("tritri", "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 1e999 0 2\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "<stdin>" + overflow);
  r = run("boxbox", "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  1e999 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "<stdin>" + overflow);
  r = run("meshpair " + a + " " + a, "1 0 0 0 1 0 0 0 1  1e999 0 0\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "<stdin>" + overflow);
}

// A mesh file with a non-finite coordinate: one line naming the file and the line, exit 2, and no
// answers (meshes load before any pose is read).
TEST_F(CliTest, MeshpairNonFiniteMeshCoordinatesAreErrors) {
  const std::string good = write("good.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string bad = write("bad.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  Result r = run("meshpair " + good + " " + bad, "1 0 0 0 1 0 0 0 1  0 0 0\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            bad + ":2: vertex 2: non-finite number \"nan\" (nan and inf are not accepted)\n");
  const std::string over = write("over.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n");
  r = run("meshpair " + over + " " + good, "1 0 0 0 1 0 0 0 1  0 0 0\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, over + ":3: vertex 3: number \"1e999\" overflows a double\n");
}

TEST_F(CliTest, WrongCountIsAnError) {
  const std::string path = write("count.txt", "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 1 0\n");
  const Result r = run("tritri " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, path + ":1: expected 18 numbers, got 17\n");
}

TEST_F(CliTest, OutOfRangeValueIsAnError) {
  const std::string path = write("range.txt", "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 1e51 0 2\n");
  const Result r = run("tritri " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, path +
                       ":1: number \"1e51\" is outside the exact-arithmetic range (0 or 1e-50 "
                       "<= |x| <= 1e+50)\n");
  const Result tiny = run("tritri", "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 1e-60 0 2\n");
  EXPECT_EQ(tiny.exit_code, 2);
  EXPECT_EQ(tiny.err,
            "<stdin>:1: number \"1e-60\" is outside the exact-arithmetic range (0 or "
            "1e-50 <= |x| <= 1e+50)\n");
}

TEST_F(CliTest, StdinErrorsAreNamedStdin) {
  const Result r = run("tritri", std::string(kTouching) + "1 2 x\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "1\n");
  EXPECT_EQ(r.err, "<stdin>:2: malformed number \"x\"\n");
}

TEST_F(CliTest, MissingFileIsAnError) {
  const std::string path = (dir_ / "missing.txt").string();
  const Result r = run("tritri " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, path + ": cannot open: No such file or directory\n");
}

// Usage errors: exit 2 with exactly one line on stderr.
void expect_usage_error(const Result& r) {
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("graspcd: ", 0), 0u) << r.err;
}

TEST_F(CliTest, UsageErrorsExitWithCodeTwoAndOneLine) {
  Result r = run("tritri --bogus", kTouching);
  expect_usage_error(r);
  EXPECT_NE(r.err.find("--bogus"), std::string::npos) << r.err;
  expect_usage_error(run(""));  // no subcommand
  expect_usage_error(run("frobnicate"));
  r = run("meshpair");  // the two meshes are required
  expect_usage_error(r);
  EXPECT_NE(r.err.find("A is required"), std::string::npos) << r.err;
  expect_usage_error(run("boxbox --cap", kBoxesApart));  // missing value
  expect_usage_error(run("boxbox --cap abc", kBoxesApart));
  expect_usage_error(run("boxbox --cap 0", kBoxesApart));
  expect_usage_error(run("boxbox --switch -3", kBoxesApart));
  expect_usage_error(run("tritri a b"));  // one input file at most
}

TEST_F(CliTest, UnknownMethodIsAUsageError) {
  const Result r = run("boxbox --method bogus", kBoxesApart);
  expect_usage_error(r);
  EXPECT_NE(r.err.find("bogus"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("neurosat-sticky"), std::string::npos) << r.err;  // lists the methods
}

// --- boxbox
// ---------------------------------------------------------------------------------------

TEST_F(CliTest, BoxboxSatAndExact) {
  const std::string path =
      write("boxes.txt", std::string(kBoxesApart) + kBoxesTouch + kBoxesOverlap);
  Result r = run("boxbox " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "0\n1\n1\n");
  EXPECT_EQ(run("boxbox --method sat --cap 10 --switch 5 " + path).out, "0\n1\n1\n");
  r = run("boxbox --exact " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "0\n1\n1\n");
}

// Every method answers like SAT; the perceptron methods and Neuro-SAT add the passes used: on the
// overlapping and touching pairs the perceptron runs to its cap (Neuro-SAT to its switch).
TEST_F(CliTest, BoxboxEveryMethodAndItsPasses) {
  const std::string path =
      write("boxes.txt", std::string(kBoxesApart) + kBoxesTouch + kBoxesOverlap);
  for (const std::string m : {"sat", "sat-cached"}) {
    EXPECT_EQ(run("boxbox --method " + m + " " + path).out, "0\n1\n1\n") << m;
  }
  for (const std::string m :
       {"perceptron", "perceptron-nodisp", "perceptron-scaled", "perceptron-warm"}) {
    const Result r = run("boxbox --cap 40 --method " + m + " " + path);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::string out = r.out;
    // perceptron-nodisp converges on these integer corners with one of A's corners exactly on its
    // plane (w.x + d = 0 is output 1): not a proof, so it answers 1 before its cap.
    if (m != "perceptron-nodisp") {
      EXPECT_EQ(out.substr(0, 2), "0 ") << m << ": " << out;
    }
    EXPECT_NE(out.find("\n1 40\n1 40\n"), std::string::npos) << m << ": " << out;
  }
  Result r = run("boxbox --switch 7 --method neurosat " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\n1 7\n1 7\n"), std::string::npos) << r.out;
  // Sticky: every line is the same "node pair", which switched to SAT on the second line, so the
  // third goes to SAT directly (0 passes).
  r = run("boxbox --switch 7 --method neurosat-sticky " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\n1 7\n1 0\n"), std::string::npos) << r.out;
  // The warm method carries its plane to the next line: the same pair again takes one pass.
  const std::string twice = write("twice.txt", std::string(kBoxesApart) + kBoxesApart);
  const Result warm = run("boxbox --method perceptron-warm " + twice);
  EXPECT_EQ(warm.out.substr(warm.out.find('\n') + 1), "0 1\n") << warm.out;
}

TEST_F(CliTest, BoxboxRejectsNonOrthonormalRAndNegativeExtents) {
  const std::string path = write("r.txt", std::string(kBoxesApart) +
                                              "0 0 0 1 0 0 0 1 0 0 0 1.001 1 1 1  "
                                              "2.5 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n");
  Result r = run("boxbox " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "0\n");
  EXPECT_EQ(r.err, path +
                       ":2: box A: R is not a rotation (R^T R must equal I to within 1e-09 "
                       "entrywise, and det R > 0)\n");
  r = run("boxbox", "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  2.5 0 0 1 0 0 0 1 0 0 0 1 1 -1 1\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "<stdin>:1: box B: half-extent 1 is negative (-1); half-extents must be >= 0\n");
}

// --- meshpair
// -------------------------------------------------------------------------------------

// A: one large triangle in the plane z = 0. B: a unit-high square in the plane x = 0.25 as two
// triangles, both crossing z = 0 inside A.
const char* const kMeshA = "v -1 -1 0\nv 3 -1 0\nv -1 3 0\nf 1 2 3\n";
const char* const kMeshB =
    "v 0.25 0 -1\nv 0.25 0.5 -1\nv 0.25 0.5 1\nv 0.25 0 1\n"
    "f 1 2 3\nf 1 3 4\n";
// Identity (2 pairs); lifted by 5 (none); rotated 90 degrees about z (2 pairs); lifted by 1, so
// B's lower edge touches A (2 pairs, touching counts); shifted far along x (none).
const char* const kPoses =
    "# R row-major, then t\n"
    "1 0 0 0 1 0 0 0 1  0 0 0\n"
    "1 0 0 0 1 0 0 0 1  0 0 5\n"
    "0 -1 0 1 0 0 0 0 1  0 0 0\n"
    "1 0 0 0 1 0 0 0 1  0 0 1\n"
    "1 0 0 0 1 0 0 0 1  10 0 0\n";

// The first two fields of each answer line; checks that the third is a time in ns.
std::vector<std::string> flags_and_counts(const std::string& out) {
  std::vector<std::string> result;
  const std::regex line_form("([01]) ([0-9]+) ([0-9]+)");
  for (const std::string& line : lines(out)) {
    std::smatch m;
    EXPECT_TRUE(std::regex_match(line, m, line_form)) << line;
    result.push_back(m.size() == 4 ? m[1].str() + " " + m[2].str() : line);
  }
  return result;
}

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

// --- help and version
// -----------------------------------------------------------------------------

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

// --- grasp --------------------------------------------------------------------------------------

// The shipped scenes (mjcf/ beside data/).
std::string shipped_scene(const std::string& name) {
  return (fs::path(GRASPCD_DATA_DIR).parent_path() / "mjcf" / (name + ".xml")).string();
}

TEST_F(CliTest, GraspPrintsAHeaderOneLinePerGraspStepAndASummary) {
  const Result r = run("grasp " + shipped_scene("example2") + " --max-steps 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), 1u + 8u + 3u) << r.out;
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
  EXPECT_EQ(out[10].rfind("# gripped no; held no: no segment reached the object;", 0), 0u)
      << out[10];
  EXPECT_EQ(out[10].find("(gripped)"), std::string::npos) << out[10];
  EXPECT_EQ(out[11].rfind("# detection ns ", 0), 0u) << out[11];
  EXPECT_NE(out[11].find(" 0 non-finite skips"), std::string::npos) << out[11];
}

TEST_F(CliTest, GraspJsonIsOneDocumentWithTheSameRecords) {
  const Result r = run("grasp " + shipped_scene("example1") +
                       " --max-steps 5 --json --method perceptron --cap 20");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc.at("method"), "perceptron");
  EXPECT_EQ(doc.at("native"), false);
  ASSERT_EQ(doc.at("steps").size(), 5u);
  EXPECT_EQ(doc.at("steps")[4].at("step"), 5);
  EXPECT_TRUE(doc.at("steps")[0].contains("detection_ns"));
  EXPECT_EQ(doc.at("first_contact").size(), 12u);
  EXPECT_TRUE(doc.at("first_contact").at("finger2_C").is_null());
  EXPECT_EQ(doc.at("held"), false);
  // Five steps reach nothing: the squeeze moves nothing, and nothing was gripped to drop.
  EXPECT_GE(doc.at("pushed").get<double>(), 0.0);
  EXPECT_LT(doc.at("pushed").get<double>(), 0.01);
  EXPECT_EQ(doc.at("pushed_during_squeeze"), false);
  EXPECT_TRUE(doc.at("dropped_at").is_null());
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

// --contact-reuse (registry.h, "contact_reuse"): touching pairs answered by their kept contacts,
// counted in reused_calls; 0 is the exact default; out of range, not a number, or with --native,
// one line and exit code 2.
TEST_F(CliTest, GraspContactReuseIsCountedAndCheckedOnTheCommandLine) {
  const std::string scene = shipped_scene("example1");
  const Result r = run("grasp " + scene + " --max-steps 60 --json --contact-reuse 2e-5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(nlohmann::json::parse(r.out).at("reused_calls").get<long>(), 0);
  const Result exact = run("grasp " + scene + " --max-steps 60 --json");
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  EXPECT_EQ(nlohmann::json::parse(exact.out).at("reused_calls"), 0);
  for (const std::string bad : {"--contact-reuse -1e-5", "--contact-reuse 0.01",
                                "--contact-reuse nan", "--contact-reuse 2e-5 --native"}) {
    const Result e = run("grasp " + scene + " " + bad);
    EXPECT_EQ(e.exit_code, 2) << bad;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
    EXPECT_NE(e.err.find("--contact-reuse"), std::string::npos) << bad << ": " << e.err;
  }
}

// A closed box 50 x 40 x 60 (file units: millimetres), off the origin: x 100..150, z 10..70.
const char* const kUserBox =
    "v 100 -20 10\nv 150 -20 10\nv 150 20 10\nv 100 20 10\n"
    "v 100 -20 70\nv 150 -20 70\nv 150 20 70\nv 100 20 70\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

// A new object without a scene (README, "A new object"): with --fit the box is fitted to the
// cup's place (its 60 mm height to 8 cm: scale 0.08 / 60, narrower than the 7 cm width), centred
// under the hand, and the fingers close on it from opposing sides.
TEST_F(CliTest, GraspObjectFitsANewMeshIntoTheTemplateAndTheFingersGripIt) {
  const std::string box = write("box.obj", kUserBox);
  const fs::path tmp = dir_ / "tmp";  // the command's temporary folder goes here
  fs::create_directories(tmp);
  ASSERT_EQ(setenv("TMPDIR", tmp.c_str(), 1), 0);
  const Result r = run("grasp --object " + box + " --fit --json --max-steps 150");
  unsetenv("TMPDIR");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["scene"], box);
  EXPECT_EQ(doc["object"]["file"], box);
  EXPECT_TRUE(doc["object"]["fitted"]);
  EXPECT_NEAR(doc["object"]["scale"].get<double>(), 0.08 / 60, 1e-12);
  EXPECT_EQ(doc["object"]["hand"], "project");
  EXPECT_NEAR(doc["object"]["size"][2].get<double>(), 0.08, 1e-12);
  // Gripped means two segments push from opposing sides; a failed verdict says why.
  EXPECT_TRUE(doc["gripped"]) << doc["reason"];
  EXPECT_EQ(doc["held"].get<bool>(), doc["reason"].is_null()) << doc["reason"];
  EXPECT_GT(doc["hand_travel"].get<double>(), 0.05);
  int touched = 0;
  for (const auto& [segment, step] : doc["first_contact"].items()) touched += !step.is_null();
  EXPECT_GE(touched, 2) << doc["first_contact"].dump();
  EXPECT_GT(doc["max_contacts"].get<int>(), 0);
  EXPECT_GT(doc["mean_contacts"].get<double>(), 0.0);
  EXPECT_GE(doc["max_pair_contacts"].get<int>(), 1);
  EXPECT_LE(doc["max_pair_contacts"].get<int>(), 8);  // the manifold's default budget per pair
  EXPECT_LE(doc["max_pair_contacts"].get<int>(), doc["max_contacts"].get<int>());
  EXPECT_EQ(doc["contact_buffer_full"].get<int>(), 0);
  EXPECT_GE(doc["rest"]["max_speed"].get<double>(), 0.0);
  // The temporary scene is gone.
  EXPECT_TRUE(fs::is_empty(tmp));
}

TEST_F(CliTest, GraspObjectWithAScaleWritesTheSceneWhenAsked) {
  const std::string box = write("box.obj", kUserBox);
  const fs::path out = dir_ / "scene";
  const Result r =
      run("grasp --object " + box + " --scale 0.001 --max-steps 2 --write-scene " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> text = lines(r.out);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.front(), "# object " + box +
                              " at scale 0.001 (given), 0.05 x 0.04 x 0.06 m, in the project "
                              "template");
  const std::string xml = read_file(out / "box.xml");
  EXPECT_NE(xml.find("scale=\"0.001 0.001 0.001\""), std::string::npos);
  // Centred under the hand (x 125 mm, y 0 in the file), its lowest point (10 mm) 0.5 mm above
  // the floor, not turned.
  const std::smatch pos = [&] {
    std::smatch m;
    std::regex_search(
        xml, m, std::regex(R"re(<body name="object" pos="(\S+) (\S+) (\S+)" quat="1 0 0 0">)re"));
    return m;
  }();
  ASSERT_EQ(pos.size(), 4u) << xml;
  EXPECT_NEAR(std::stod(pos[1]), -0.125, 1e-12);
  EXPECT_NEAR(std::stod(pos[2]), 0.0, 1e-12);
  EXPECT_NEAR(std::stod(pos[3]), -0.01 + 0.0005, 1e-12);
  EXPECT_TRUE(fs::exists(out / "box.pairs.json"));
  // A header that says what the scene is (not the template's), and paths relative to the folder.
  EXPECT_EQ(xml.find("generate_scenes.py"), std::string::npos);
  EXPECT_EQ(xml.find("cup: outer radius"), std::string::npos);
  EXPECT_NE(xml.find("Generated by graspcd"), std::string::npos);
  EXPECT_NE(xml.find("file axis z up, turned 0 degrees"), std::string::npos) << xml;
  std::smatch meshdir;
  ASSERT_TRUE(std::regex_search(xml, meshdir, std::regex(R"re(meshdir="([^"]*)")re")));
  EXPECT_NE(meshdir[1].str().front(), '/') << meshdir[1];
  EXPECT_TRUE(fs::exists(out / meshdir[1].str() / "finger_A.obj")) << meshdir[1];
  // It runs as a scene of its own, from another working folder (a whole grasp: Release pass only).
  if (sanitizer_pass()) return;
  const Result again = run("grasp " + (out / "box.xml").string() + " --max-steps 1");
  EXPECT_EQ(again.exit_code, 0) << again.err;
}

TEST_F(CliTest, GraspObjectErrorsAreOneLineAndExitTwo) {
  const std::string bad = write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 nan\nf 1 2 3\n");
  Result r = run("grasp --object " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(bad + ":", 0), 0u) << r.err;
  const std::string missing = (dir_ / "nowhere.obj").string();
  r = run("grasp --object " + missing);
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(missing + ":", 0), 0u) << r.err;
  // Neither SCENE nor --object, or both, or --scale without --object: usage errors.
  for (const std::string& args :
       {std::string("grasp"), "grasp " + shipped_scene("example1") + " --object " + bad,
        "grasp " + shipped_scene("example1") + " --scale 2"}) {
    r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(lines(r.err).size(), 1u) << args << ": " << r.err;
  }
}

// The box of kUserBox in metres: 5 x 4 x 6 cm, off the origin.
std::string user_box_in_metres() {
  std::istringstream in(kUserBox);
  std::ostringstream out;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      double x = 0, y = 0, z = 0;
      v >> x >> y >> z;
      out << "v " << x / 1000 << ' ' << y / 1000 << ' ' << z / 1000 << '\n';
    } else {
      out << line << '\n';
    }
  }
  return out.str();
}

// --object keeps the file's units (metres) unless told, and says so on the first line.
TEST_F(CliTest, GraspObjectKeepsTheFilesUnitsByDefault) {
  const std::string box = write("box_m.obj", user_box_in_metres());
  const Result r = run("grasp --object " + box + " --max-steps 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["object"]["scale"], 1.0);
  EXPECT_FALSE(doc["object"]["fitted"]);
  EXPECT_NEAR(doc["object"]["size"][0].get<double>(), 0.05, 1e-12);
  EXPECT_NEAR(doc["object"]["size"][1].get<double>(), 0.04, 1e-12);
  EXPECT_NEAR(doc["object"]["size"][2].get<double>(), 0.06, 1e-12);
}

// --quiet: the same run without the per-step table, so the '#' summary lines alone; with
// --object the object line stays first. With --json it changes nothing.
TEST_F(CliTest, GraspQuietPrintsOnlyTheHeaderAndTheVerdict) {
  const Result full = run("grasp " + shipped_scene("example2") + " --max-steps 8");
  const Result r = run("grasp " + shipped_scene("example2") + " --max-steps 8 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), 3u) << r.out;
  for (const std::string& line : out) EXPECT_EQ(line.rfind("# ", 0), 0u) << line;
  const std::vector<std::string> all = lines(full.out);
  ASSERT_EQ(all.size(), 1u + 8u + 3u) << full.out;
  // The verdict is the same run's (the detection times differ from run to run).
  EXPECT_EQ(out[0], all[9]);
  EXPECT_EQ(out[1], all[10]);

  const std::string box = write("box_m.obj", user_box_in_metres());
  const Result object = run("grasp --object " + box + " --max-steps 2 --quiet");
  ASSERT_EQ(object.exit_code, 0) << object.err;
  const std::vector<std::string> object_out = lines(object.out);
  ASSERT_EQ(object_out.size(), 4u) << object.out;
  EXPECT_EQ(object_out[0].rfind("# object " + box + " at scale 1 (given)", 0), 0u) << object_out[0];
  EXPECT_EQ(object_out[2].rfind("# gripped no; held no", 0), 0u) << object_out[2];

  const Result json = run("grasp " + shipped_scene("example2") + " --max-steps 8 --quiet --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["steps"].size(), 8u);
}

// `obj` with every face reversed: the same closed box turned inside out.
std::string inside_out(const std::string& obj) {
  std::istringstream in(obj);
  std::ostringstream out;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("f ", 0) == 0) {
      std::istringstream f(line.substr(2));
      std::string a, b, c;
      f >> a >> b >> c;
      out << "f " << a << ' ' << c << ' ' << b << '\n';
    } else {
      out << line << '\n';
    }
  }
  return out.str();
}

// A closed mesh whose faces all point inward is turned right way out with one warning naming the
// file: the grasp's verdict is the right-way-out box's (without the turn MuJoCo's inertia and the
// containment check read the reversed faces: the box slipped). meshpair turns it too.
TEST_F(CliTest, AnInsideOutMeshIsFlippedWithAWarningAndGraspsAsTheRightWayOutOne) {
  const std::string box = write("box_m.obj", user_box_in_metres());
  const std::string inverted = write("inverted.obj", inside_out(user_box_in_metres()));
  const Result right = run("grasp --object " + box + " --json");
  const Result turned = run("grasp --object " + inverted + " --json");
  ASSERT_EQ(right.exit_code, 0) << right.err;
  ASSERT_EQ(turned.exit_code, 0) << turned.err;
  const nlohmann::json a = nlohmann::json::parse(right.out);
  const nlohmann::json b = nlohmann::json::parse(turned.out);
  EXPECT_TRUE(a["warnings"].empty()) << a["warnings"];
  ASSERT_EQ(b["warnings"].size(), 1u) << b["warnings"];
  EXPECT_EQ(b["warnings"][0]["code"], "mesh_inside_out");
  EXPECT_EQ(b["warnings"][0]["source"], "mesh");
  EXPECT_EQ(b["warnings"][0]["message"],
            inverted + ": the faces point inward (signed volume -0.00012 m^3): flipped");
  EXPECT_EQ(turned.err, "warning: " + inverted +
                            ": the faces point inward (signed volume -0.00012 m^3): "
                            "flipped\n");
  for (const char* key : {"gripped", "held", "reason", "object_z_final", "hold_drift"}) {
    EXPECT_EQ(a[key], b[key]) << key;
  }
  EXPECT_TRUE(b["held"]) << b["reason"];

  // meshpair: the same warning, the same answers.
  const std::string poses = write("poses.txt", "1 0 0 0 1 0 0 0 1  0.03 0 0.02\n");
  const Result pair_right = run("meshpair " + box + " " + box + " --poses " + poses);
  const Result pair_turned = run("meshpair " + box + " " + inverted + " --poses " + poses);
  ASSERT_EQ(pair_turned.exit_code, 0) << pair_turned.err;
  EXPECT_EQ(pair_turned.out.substr(0, 2), pair_right.out.substr(0, 2));
  EXPECT_EQ(pair_turned.err, "warning: " + inverted +
                                 ": the faces point inward (signed volume -0.00012 m^3): "
                                 "flipped\n");
}

// An L-shaped block (6 x 3 x 7 cm, 1.5 cm thick) turned 45 degrees in the Robotiq: the pads meet
// its corner and the squeeze pushes it about 1.3 cm before the lift; the hand then lifts it. Held,
// but the verdict says it was pushed, and --require-held still passes.
TEST_F(CliTest, GraspSaysWhenTheSqueezePushedAHeldObject) {
  const fs::path models = fs::path(GRASPCD_MODELS_DIR);
  if (!fs::exists(models / "hands" / "robotiq_2f85" / "2f85.xml")) {
    GTEST_SKIP() << "real hands not found in " << models;
  }
  if (sanitizer_pass()) {
    GTEST_SKIP() << "real-hand grasps skipped at GRASPCD_TEST_SCALE < 1 (sanitizer pass)";
  }
  const std::string l_shape = write(
      "l_shape.obj",
      inside_out("v 0 0 0\nv 0.06 0 0\nv 0.06 0 0.015\nv 0.015 0 0.015\nv 0.015 0 0.07\n"
                 "v 0 0 0.07\nv 0 0.03 0\nv 0.06 0.03 0\nv 0.06 0.03 0.015\nv 0.015 0.03 0.015\n"
                 "v 0.015 0.03 0.07\nv 0 0.03 0.07\n"
                 "f 1 2 8\nf 1 8 7\nf 2 3 9\nf 2 9 8\nf 3 4 10\nf 3 10 9\nf 4 5 11\nf 4 11 10\n"
                 "f 5 6 12\nf 5 12 11\nf 6 1 7\nf 6 7 12\nf 1 3 2\nf 7 8 9\nf 1 4 3\nf 7 9 10\n"
                 "f 1 5 4\nf 7 10 11\nf 1 6 5\nf 7 11 12\n"));
  const std::string args = "grasp --object " + l_shape + " --hand robotiq --yaw 45 --require-held";
  const Result json = run(args + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json doc = nlohmann::json::parse(json.out);
  EXPECT_TRUE(doc["held"]) << doc["reason"];
  EXPECT_TRUE(doc["pushed_during_squeeze"]);
  EXPECT_GT(doc["pushed"].get<double>(), 0.01);
  EXPECT_LT(doc["pushed"].get<double>(), 0.03);
  EXPECT_TRUE(doc["dropped_at"].is_null());
  for (const nlohmann::json& w : doc["warnings"]) EXPECT_NE(w["code"], "mesh_inside_out") << w;
  const Result text = run(args + " --quiet");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::vector<std::string> out = lines(text.out);
  ASSERT_EQ(out.size(), 4u) << text.out;
  EXPECT_EQ(out[2].rfind("# gripped yes; held yes, pushed 1.", 0), 0u) << out[2];
  EXPECT_NE(out[2].find(" cm during the squeeze; object z "), std::string::npos) << out[2];
}

// The start-state check: an object that starts inside the fingers, or sunk into the
// floor, is bad input: one line naming the file, exit 2, nothing on stdout.
TEST_F(CliTest, GraspRefusesAnObjectThatStartsInsideTheHandOrTheFloor) {
  // The millimetre box at twice its size, 10 x 8 x 12 cm: wider than the open hand.
  const std::string box = write("box.obj", kUserBox);
  Result r = run("grasp --object " + box + " --scale 0.002");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(box + ": in the template scene: the start state is not valid: ", 0), 0u)
      << r.err;
  EXPECT_NE(r.err.find("penetrates"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(at most 0.5 mm allowed)"), std::string::npos) << r.err;
  // A scene of its own with the object 3.6 cm inside the floor (the issue's mug): the refused
  // run has written it (the scene is written before the grasp); at the box's true size, centred
  // under the hand (file x 100..150 mm), its lowest point (file z 10 mm) at z = -0.036.
  const fs::path out = dir_ / "scene";
  ASSERT_EQ(run("grasp --object " + box + " --scale 0.002 --write-scene " + out.string()).exit_code,
            2);
  std::string xml = read_file(out / "box.xml");
  const std::string twice = R"(scale="0.002 0.002 0.002")";
  ASSERT_NE(xml.find(twice), std::string::npos) << xml;
  xml.replace(xml.find(twice), twice.size(), R"(scale="0.001 0.001 0.001")");
  const std::regex pos(R"re(<body name="object" pos="\S+ \S+ \S+")re");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(xml, m, pos)) << xml;
  xml.replace(static_cast<std::size_t>(m.position(0)), static_cast<std::size_t>(m.length(0)),
              R"(<body name="object" pos="-0.125 0 -0.046")");
  std::ofstream(out / "box.xml", std::ios::trunc) << xml;
  const std::string scene = (out / "box.xml").string();
  r = run("grasp " + scene + " --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, scene +
                       ": the start state is not valid: geom 'object' of the object lies 36.0 mm "
                       "below the plane geom 'floor' (at most 0.5 mm allowed): put its lowest "
                       "point on the support\n");
}

// --hand FILE: any scene can be a template (docs/design.md, "Object scenes"); one that breaks the
// contract, or lacks what an option needs, is one line naming it and its line, exit 2. These are
// refused before any simulation.
TEST_F(CliTest, GraspObjectTemplateFilesAreCheckedAndNamed) {
  const std::string box = write("box.obj", kUserBox);
  // Example 1 as a file has no graspcd_fit (the built-in "project" hand supplies one).
  const std::string example1 = shipped_scene("example1");
  Result r = run("grasp --object " + box + " --hand " + example1 + " --fit");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, example1 +
                       ":1: template scene: no <numeric name=\"graspcd_fit\" data=\"WIDTH "
                       "HEIGHT\"/> for --fit\n");
  // A scene without a body "object" in its worldbody: the worldbody's line.
  const std::string bare = write("bare.xml",
                                 "<mujoco>\n  <worldbody>\n    <body name=\"cup\"/>\n  "
                                 "</worldbody>\n</mujoco>\n");
  r = run("grasp --object " + box + " --hand " + bare);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, bare + ":2: template scene: no <body name=\"object\"> in <worldbody>\n");
  // Neither a built-in hand nor a file; and a bad --up.
  r = run("grasp --object " + box + " --hand allegro");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "graspcd: grasp: --hand must be project, robotiq, shadow or a template scene file "
            "(allegro is none)\n");
  r = run("grasp --object " + box + " --up w");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "graspcd: grasp: --up must be one of x, y, z, -x, -y, -z (not 'w')\n");
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
  EXPECT_EQ(doc["reason"], "no segment reached the object");
  EXPECT_TRUE(doc["slip_time"].is_null());
  // Not a usage error: the verdict is the answer, printed in full.
  EXPECT_EQ(doc["steps"].size(), 2u);
}

// --hand robotiq and --hand shadow (../shared/models): a new object at its real size in metres and
// in millimetres, placed by --up, grasped to a verdict that agrees with its numbers.
TEST_F(CliTest, GraspObjectWithTheRealHands) {
  const fs::path models = fs::path(GRASPCD_MODELS_DIR);
  if (!fs::exists(models / "hands" / "robotiq_2f85" / "2f85.xml") ||
      !fs::exists(models / "hands" / "shadow_hand" / "right_hand.xml")) {
    GTEST_SKIP() << "real hands not found in " << models;
  }
  if (sanitizer_pass()) {
    GTEST_SKIP() << "real-hand grasps skipped at GRASPCD_TEST_SCALE < 1 (sanitizer pass)";
  }
  // A 3 x 3 x 6 cm block, in millimetres, lying on its side in the file (its long axis x).
  const std::string block = write("block.obj",
                                  "v -30 -15 -15\nv 30 -15 -15\nv -30 15 -15\nv 30 15 -15\n"
                                  "v -30 -15 15\nv 30 -15 15\nv -30 15 15\nv 30 15 15\n"
                                  "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
                                  "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n");
  // Robotiq: standing up (file x along -gravity), between the pads.
  Result r = run("grasp --object " + block + " --scale 0.001 --hand robotiq --up x --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json doc = nlohmann::json::parse(r.out);
  graspcd::testing::expect_envelope(doc, -1);
  EXPECT_EQ(doc["object"]["hand"], "robotiq");
  EXPECT_NEAR(doc["object"]["size"][2].get<double>(), 0.06, 1e-12);
  EXPECT_TRUE(doc["gripped"]) << doc["reason"];
  EXPECT_TRUE(doc["held"]) << doc["reason"];
  EXPECT_GE(doc["object_rise"].get<double>(), 0.8 * doc["hand_travel"].get<double>());
  EXPECT_LT(doc["hold_drift"].get<double>(), 0.01);
  // Shadow: lying across the fingers (file x across gravity), in metres.
  const std::string bar =
      write("bar.obj",
            "v -0.012 -0.03 -0.012\nv 0.012 -0.03 -0.012\nv -0.012 0.03 -0.012\n"
            "v 0.012 0.03 -0.012\nv -0.012 -0.03 0.012\nv 0.012 -0.03 0.012\n"
            "v -0.012 0.03 0.012\nv 0.012 0.03 0.012\n"
            "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
            "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n");
  r = run("grasp --object " + bar + " --hand shadow --up x --json --require-held");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["object"]["hand"], "shadow");
  EXPECT_TRUE(doc["gripped"]) << doc["reason"];
  EXPECT_TRUE(doc["held"]) << doc["reason"];
  EXPECT_TRUE(doc["reason"].is_null());
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

// A copy of a shipped scene in the test folder, with its meshes in DIR/meshes (the scene's
// meshdir); `skip_mesh` is left out, and `open_mesh` is written without its last face.
std::string copy_scene(const fs::path& dir, const std::string& name, const std::string& skip_mesh,
                       const std::string& open_mesh) {
  const fs::path mjcf = fs::path(GRASPCD_DATA_DIR).parent_path() / "mjcf";
  fs::create_directories(dir / "meshes");
  for (const auto& entry : fs::directory_iterator(mjcf / "meshes")) {
    const std::string file = entry.path().filename().string();
    if (file == skip_mesh) continue;
    std::string text = read_file(entry.path());
    if (file == open_mesh) {
      text.erase(text.rfind("\nf ") + 1);  // drop the last face
    }
    std::ofstream(dir / "meshes" / file, std::ios::binary) << text;
  }
  fs::copy_file(mjcf / (name + ".xml"), dir / (name + ".xml"));
  fs::copy_file(mjcf / (name + ".pairs.json"), dir / (name + ".pairs.json"));
  return (dir / (name + ".xml")).string();
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
// on one line, the start check on another (it cannot see into it either), and the grasp goes on
// with surface contacts (exit 0).
TEST_F(CliTest, GraspWithAnOpenMeshWarnsAndGoesOn) {
  const std::string scene = copy_scene(dir_ / "s", "example1", "", "cup.obj");
  const Result r = run("grasp " + scene + " --max-steps 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> err = lines(r.err);
  ASSERT_EQ(err.size(), 2u) << r.err;
  const std::string config = (dir_ / "s" / "example1.pairs.json").string();
  EXPECT_EQ(err[0].rfind("warning: " + config + ": mesh ", 0), 0u) << err[0];
  EXPECT_NE(err[0].find("'cup' is not closed: "), std::string::npos) << err[0];
  EXPECT_NE(err[0].find("boundary edges"), std::string::npos) << err[0];
  EXPECT_NE(err[0].find("containment inside it is not checked"), std::string::npos) << err[0];
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  graspcd::testing::expect_envelope(doc, 2);
  EXPECT_EQ(doc.at("warnings")[0].at("code"), "mesh_open");
  EXPECT_EQ(doc.at("warnings")[0].at("source"), "mesh");
  EXPECT_EQ(doc.at("warnings")[0].at("count"), 1);
  EXPECT_EQ("warning: " + doc.at("warnings")[0].at("message").get<std::string>(), err[0]);
  EXPECT_EQ(err[1],
            "warning: start check: geom 'object' is not a closed mesh: what lies inside it is not "
            "checked");
  EXPECT_EQ(doc.at("warnings")[1].at("source"), "scene");
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

// --- Hostile input at the seams between graspcd, MuJoCo and the files ----------------------------

// A unit cube (12 faces) in an OBJ, 8 vertices; `first` replaces the first vertex line.
std::string cube_obj(const std::string& first = "v 0 0 0") {
  return first +
         "\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\n"
         "f 3 8 7\nf 4 1 5\nf 4 5 8\n";
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

// Item 4: answers that could not be written are an error, not a success; a closed pipe stays
// quiet (SIGPIPE).
TEST_F(CliTest, StdoutThatCannotBeWrittenIsAnErrorAndAClosedPipeIsQuiet) {
  const std::string cases = write("t.txt", std::string(kTouching) + kSeparated);
  const std::string exe = std::string("'") + GRASPCD_EXE + "' ";
  const fs::path err = dir_ / "err.txt";
  const auto status_of = [&](const std::string& command) {
    const int status = std::system((command + " 2> '" + err.string() + "'").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  };
  EXPECT_EQ(status_of(exe + "tritri " + cases + " > /dev/full"), 2);
  EXPECT_EQ(read_file(err), "<stdout>: cannot write: No space left on device\n");
  EXPECT_EQ(status_of(exe + "boxbox " + write("b.txt", kBoxesApart) + " > /dev/full"), 2);
  EXPECT_EQ(read_file(err), "<stdout>: cannot write: No space left on device\n");
  EXPECT_EQ(status_of(exe + "tritri --help > /dev/full"), 2);
  EXPECT_EQ(read_file(err), "<stdout>: cannot write: No space left on device\n");
  EXPECT_EQ(status_of(exe + "tritri " + cases + " >&-"), 2);
  EXPECT_EQ(read_file(err), "<stdout>: cannot write: Bad file descriptor\n");
  // 200,000 answers into `head -1`: the pipe closes early, graspcd ends by SIGPIPE, silently.
  std::string many;
  for (int i = 0; i < 200000; ++i) many += kTouching;
  const std::string big = write("big.txt", many);
  const fs::path status = dir_ / "status.txt";
  fs::remove(err);
  EXPECT_EQ(std::system(("{ " + exe + "tritri " + big + " 2> '" + err.string() + "'; echo $? > '" +
                         status.string() + "'; } | head -1 > /dev/null")
                            .c_str()),
            0);
  EXPECT_EQ(read_file(status), std::to_string(128 + SIGPIPE) + "\n");
  EXPECT_EQ(read_file(err), "");
}

// Item 3: a byte-order mark hid the first vertex and shifted every face (meshpair answered "1 11"
// where the same file without it answers "0 0"); refused the same way by every reader.
TEST_F(CliTest, AnObjWithAByteOrderMarkIsRefusedEverywhere) {
  const std::string bom = write("bom.obj", "\xEF\xBB\xBF" + cube_obj());
  const std::string plain = write("plain.obj", cube_obj());
  const std::string poses = write("p.txt", "1 0 0 0 1 0 0 0 1  5 0 0\n");
  Result r = run("meshpair " + plain + " " + plain + " --poses " + poses);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, 4), "0 0 ");
  r = run("meshpair " + bom + " " + plain + " --poses " + poses);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, bom + ":1: UTF-8 byte-order mark\n");
  r = run("grasp --object " + bom);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, bom + ":1: UTF-8 byte-order mark\n");
  // In a scene: graspcd checks the meshes it names before MuJoCo reads them.
  const std::string scene = copy_scene(dir_ / "s", "example1", "", "");
  const std::string cup = (dir_ / "s" / "meshes" / "cup.obj").string();
  const std::string text = read_file(cup);
  std::ofstream(cup, std::ios::binary | std::ios::trunc) << "\xEF\xBB\xBF" << text;
  r = run("grasp " + scene + " --max-steps 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, cup + ":1: UTF-8 byte-order mark\n");
}

// Items 1 and 5: a non-finite number in a scene is refused at load by every command that loads
// one (validate and trajectory used to spin in the exact predicates on it, grasp ran it).
TEST_F(CliTest, ASceneWithANonFiniteNumberIsRefusedByEveryCommand) {
  const std::string scene = copy_scene(dir_ / "s", "example1", "", "");
  std::string xml = read_file(scene);
  const std::string object = "<geom name=\"object\" type=\"mesh\"";
  ASSERT_NE(xml.find(object), std::string::npos);
  xml.replace(xml.find(object), object.size(),
              "<geom name=\"object\" pos=\"nan 0 0\" type=\"mesh\"");
  std::ofstream(scene, std::ios::trunc) << xml;
  const std::string line =
      std::to_string(1 + std::count(xml.begin(), xml.begin() + xml.find("pos=\"nan"), '\n'));
  const std::string expected =
      scene + ":" + line + ": <geom name=\"object\"> pos=\"nan 0 0\": non-finite number \"nan\"\n";
  for (const std::string& command :
       {"grasp " + scene, "validate " + scene + " --steps 1",
        "trajectory " + scene + " --out " + (dir_ / "t.json").string()}) {
    const Result r = run(command);
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_EQ(r.out, "") << command;
    EXPECT_EQ(r.err, expected) << command;
  }
  // The palm's size, and an overflowing literal.
  xml = read_file(shipped_scene("example1"));
  const std::string palm = "<geom name=\"palm\" type=\"box\" size=\"0.045000";
  ASSERT_NE(xml.find(palm), std::string::npos);
  xml.replace(xml.find(palm), palm.size(), "<geom name=\"palm\" type=\"box\" size=\"1e999");
  std::ofstream(scene, std::ios::trunc) << xml;
  Result r = run("grasp " + scene);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(": <geom name=\"palm\"> size=\"1e999 "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("non-finite number \"1e999\""), std::string::npos) << r.err;
  // A NaN vertex in the scene's OBJ, which MuJoCo reads as 0.
  std::ofstream(scene, std::ios::trunc) << read_file(shipped_scene("example1"));
  const std::string cup = (dir_ / "s" / "meshes" / "cup.obj").string();
  std::string obj = read_file(cup);
  obj.replace(obj.find("\nv ") + 1, 0, "v nan 1 1\n");
  std::ofstream(cup, std::ios::binary | std::ios::trunc) << obj;
  r = run("validate " + scene + " --steps 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(cup + ":", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(": vertex 1: non-finite number \"nan\""), std::string::npos) << r.err;
}

// Item 2: qhull inside MuJoCo (a mesh fitted to about 1e-21 m has no 3D hull) used to end the
// process with exit 41 through libqhullcpp's print hook, naming nothing, leaving the temporary
// folder. Now: the user's file named, exit 2, the folder removed.
TEST_F(CliTest, GraspObjectThatMujocoCannotCompileNamesTheFileAndCleansUp) {
  const std::string huge = write("huge.obj", cube_obj("v 1e20 0 0"));
  const fs::path tmp = dir_ / "tmp";
  fs::create_directories(tmp);
  ASSERT_EQ(setenv("TMPDIR", tmp.c_str(), 1), 0);
  const Result r = run("grasp --object " + huge + " --fit");
  unsetenv("TMPDIR");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  ASSERT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind(huge + ": in the template scene: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("qhull"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(tmp));
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

// Item 7: an OBJ with two objects is warned about in grasp --object as in meshpair (MuJoCo keeps
// the first, the fit sees both).
TEST_F(CliTest, GraspObjectWarnsAboutSeveralObjectsAsMeshpairDoes) {
  const std::string two = write("two.obj", "o first\n" + cube_obj() +
                                               "o second\nv 3 0 0\nv 4 0 0\nv 3 1 0\nv 3 0 1\n"
                                               "f 9 11 10\nf 9 10 12\nf 9 12 11\nf 10 11 12\n");
  const std::string warning = "warning: " + two +
                              ": 2 objects ('first', 'second'): graspcd reads them all, but "
                              "MuJoCo 2.2 keeps only the first ('first'); merge them into one "
                              "object for a scene\n";
  const Result m = run("meshpair " + two + " " + write("cube.obj", cube_obj()) + " --poses " +
                       write("p.txt", "1 0 0 0 1 0 0 0 1  9 0 0\n"));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(m.err, warning);
  const Result g = run("grasp --object " + two + " --fit --max-steps 1");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  EXPECT_NE(g.err.find(warning), std::string::npos) << g.err;
}

// The messages: option values, a misspelled subcommand, a config's bad JSON named once with its
// line.
TEST_F(CliTest, OptionAndSubcommandErrorsAreShortAndRight) {
  Result r = run("grasp --object x.obj --scale nan");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "graspcd: --scale: Value nan is not a finite number (run with --help for usage)\n");
  r = run("grasp " + shipped_scene("example1") + " --max-steps 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "graspcd: --max-steps: Value 0 is not > 0 (run with --help for usage)\n");
  r = run("tritr x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "graspcd: unknown subcommand 'tritr' (expected one of: tritri, boxbox, meshpair, "
            "grasp, study, stress, validate, trajectory, decompose)\n");
  const std::string scene = copy_scene(dir_ / "s", "example1", "", "");
  const std::string config = (dir_ / "s" / "example1.pairs.json").string();
  std::ofstream(config, std::ios::trunc) << "{\n  \"pairs\": [\n  }\n";
  for (const std::string& command : {"validate " + scene, "grasp " + scene}) {
    r = run(command);
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_EQ(r.err, config +
                         ":3: bad JSON: syntax error while parsing value - unexpected '}'; "
                         "expected '[', '{', or a literal\n")
        << command;
  }
}

}  // namespace
