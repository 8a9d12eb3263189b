// Errors every command shares: FILE:LINE: message, exit 2, earlier answers kept; usage
// errors in one line; hostile input at the seams between graspcd, MuJoCo and the files.
// Runs the real `graspcd` binary (GRASPCD_EXE); helpers in cli_helpers.h.
#include "app/cli_helpers.h"

namespace {

using namespace graspcd::cli_testing;

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

// Answers that could not be written are an error, not a success; a closed pipe stays
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

// A byte-order mark hid the first vertex and shifted every face (meshpair answered "1 11"
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

// A non-finite number in a scene is refused at load by every command that loads
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
            "grasp, study, stress, validate, trajectory, decompose, hand, judge)\n");
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
