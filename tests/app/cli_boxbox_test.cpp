// `graspcd boxbox`: box pairs by every method, their passes, the checks on each box.
// Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

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
}  // namespace
