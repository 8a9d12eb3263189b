// The files graspcd writes (docs/bad-input.md, "Output files"): grasp --write-scene never replaces
// the run's own template or a file graspcd did not write (unless --force), two runs writing one
// stem into one folder each simulate their own object, a written scene folder loads after it was
// moved, INT, TERM and HUP leave no temporary file or partial output (exit 128 + signal), and an
// output that cannot be written is one line naming it, exit code 2, before the work.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "helpers/command_test.h"
#include "helpers/processes.h"
#include "helpers/test_scale.h"

namespace safe_files_test {
namespace {

namespace fs = std::filesystem;
using graspcd::testing::Outcome;
using graspcd::testing::read_file;

// A 50 x 40 x `height` mm box (file units mm), its lowest point at z = 10 mm.
std::string box_obj(int height) {
  const std::string top = std::to_string(10 + height);
  return "v 100 -20 10\nv 150 -20 10\nv 150 20 10\nv 100 20 10\n"
         "v 100 -20 " +
         top + "\nv 150 -20 " + top + "\nv 150 20 " + top + "\nv 100 20 " + top +
         "\nf 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
         "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
}

const std::string kMjcf = GRASPCD_MJCF_DIR;

class SafeFilesTest : public graspcd::testing::CommandTest {
 protected:
  // Runs graspcd with stdout kept.
  struct Result {
    int exit_code = -1;
    std::string out;
    std::string err;
  };
  Result run_out(const std::string& args, const std::string& env = "") {
    const fs::path out = dir_ / "stdout.txt";
    const Outcome r =
        run("{ " + env + " '" + GRASPCD_EXE + "' " + args + " > '" + out.string() + "'; }");
    return {r.exit_code, read_file(out), r.err};
  }

  static std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  }

  // The names in `dir` that start with `prefix`.
  static std::vector<std::string> entries(const fs::path& dir, const std::string& prefix = "") {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      if (name.rfind(prefix, 0) == 0) out.push_back(name);
    }
    return out;
  }

  // Exit code 2 and one line on stderr that starts with "FILE: ".
  void expect_refused(const Outcome& r, const std::string& file, const std::string& what) {
    EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
    EXPECT_EQ(lines(r.err).size(), 1u) << what << ": " << r.err;
    EXPECT_EQ(r.err.rfind(file + ": ", 0), 0u) << what << ": " << r.err;
  }

  // Starts graspcd with `args` (TMPDIR = `tmpdir`), waits until `appears` has an entry starting
  // with `prefix`, sends `sig` and returns the exit status (-1 when the entry never appeared).
  int interrupt(const std::vector<std::string>& args, const fs::path& tmpdir,
                const fs::path& appears, const std::string& prefix, int sig) {
    const pid_t pid = fork();
    if (pid == 0) {
      setenv("TMPDIR", tmpdir.c_str(), 1);
      const int null = open("/dev/null", O_WRONLY);
      dup2(null, 1);
      dup2(null, 2);
      std::vector<char*> argv{const_cast<char*>(GRASPCD_EXE)};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(GRASPCD_EXE, argv.data());
      _exit(127);
    }
    bool seen = false;
    for (int i = 0; i < 4000 && !seen; ++i) {
      seen = !entries(appears, prefix).empty();
      if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (seen) kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    if (!seen) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  }
};

// --write-scene into the template's folder, the object named as the template (the file it reads).
// The template and its pair config are left as they were, with or without --force.
TEST_F(SafeFilesTest, WriteSceneNeverReplacesTheTemplateItReads) {
  const fs::path hand = dir_ / "hand";
  fs::create_directories(hand);
  fs::copy_file(kMjcf + "/example1.xml", hand / "example1.xml");
  fs::copy_file(kMjcf + "/example1.pairs.json", hand / "example1.pairs.json");
  fs::create_directory_symlink(kMjcf + "/meshes", hand / "meshes");
  const std::string object = write("example1.obj", box_obj(60));
  const std::string xml = read_file(hand / "example1.xml");
  const std::string pairs = read_file(hand / "example1.pairs.json");
  for (const std::string force : {"", " --force"}) {
    const Outcome r = graspcd("grasp --object " + object + " --scale 0.001 --hand " +
                              (hand / "example1.xml").string() + " --write-scene " + hand.string() +
                              " --max-steps 1" + force);
    expect_refused(r, (hand / "example1.xml").string(), "the template" + force);
    EXPECT_NE(r.err.find("template"), std::string::npos) << r.err;
    EXPECT_EQ(read_file(hand / "example1.xml"), xml);
    EXPECT_EQ(read_file(hand / "example1.pairs.json"), pairs);
    EXPECT_TRUE(entries(hand, ".graspcd").empty());
  }
}

// A scene graspcd did not write is replaced with --force only; its own (the marker) always.
TEST_F(SafeFilesTest, WriteSceneReplacesAForeignSceneOnlyWithForce) {
  const std::string box = write("box.obj", box_obj(60));
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  const std::string mine = "<mujoco model=\"mine\"/>\n";
  std::ofstream(out / "box.xml") << mine;
  const std::string args =
      "grasp --object " + box + " --scale 0.001 --write-scene " + out.string() + " --max-steps 1";
  Outcome r = graspcd(args);
  expect_refused(r, (out / "box.xml").string(), "a foreign scene");
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(out / "box.xml"), mine);
  EXPECT_FALSE(fs::exists(out / "box.pairs.json"));
  // A pair config alone, without graspcd's scene beside it, is not graspcd's either.
  fs::remove(out / "box.xml");
  std::ofstream(out / "box.pairs.json") << "{}\n";
  expect_refused(graspcd(args), (out / "box.pairs.json").string(), "a foreign pair config");
  std::ofstream(out / "box.xml") << mine;

  r = graspcd(args + " --force");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string written = read_file(out / "box.xml");
  EXPECT_NE(written.find("graspcd-generated"), std::string::npos) << written;
  EXPECT_NE(read_file(out / "box.pairs.json"), "{}\n");
  // graspcd's own scene is replaced without --force; no private folder is left.
  r = graspcd(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(entries(out, ".graspcd").empty());
  EXPECT_EQ(entries(out).size(), 3u);  // box.xml, box.pairs.json, box.meshes
}

// Two runs writing an object of one stem into one folder at the same time: each simulates its
// own object (its first line and its heights are those of the same run alone).
TEST_F(SafeFilesTest, ConcurrentRunsWithOneStemEachSimulateTheirOwnObject) {
  fs::create_directories(dir_ / "a");
  fs::create_directories(dir_ / "b");
  const std::string a = write("a/box.obj", box_obj(60));
  const std::string b = write("b/box.obj", box_obj(30));
  const fs::path out = dir_ / "out";
  const auto args = [&](const std::string& box, const std::string& write_scene) {
    return std::string("'") + GRASPCD_EXE + "' grasp --object " + box +
           " --scale 0.001 --max-steps 2 --json" + write_scene;
  };
  const std::string scene = " --write-scene " + out.string();
  const Outcome both = run("{ " + args(a, scene) + " > '" + (dir_ / "a.json").string() + "' & " +
                           args(b, scene) + " > '" + (dir_ / "b.json").string() + "'; wait; }");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  const nlohmann::json together_a = load(dir_ / "a.json");
  const nlohmann::json together_b = load(dir_ / "b.json");
  const Outcome alone = run("{ " + args(a, "") + " > '" + (dir_ / "a1.json").string() + "' && " +
                            args(b, "") + " > '" + (dir_ / "b1.json").string() + "'; }");
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  const nlohmann::json alone_a = load(dir_ / "a1.json");
  const nlohmann::json alone_b = load(dir_ / "b1.json");
  EXPECT_NEAR(together_a["object"]["size"][2].get<double>(), 0.06, 1e-12);
  EXPECT_NEAR(together_b["object"]["size"][2].get<double>(), 0.03, 1e-12);
  for (const char* key : {"object_z_initial", "object_z_gripped", "object_z_final"}) {
    EXPECT_EQ(together_a[key], alone_a[key]) << key;
    EXPECT_EQ(together_b[key], alone_b[key]) << key;
  }
  EXPECT_NE(alone_a["object_z_final"], alone_b["object_z_final"]);
  EXPECT_EQ(together_a["object"]["scene"], (out / "box.xml").string());
  // One run's scene is left, whole, and no private folder.
  EXPECT_TRUE(entries(out, ".graspcd").empty());
  EXPECT_EQ(entries(out).size(), 3u);
}

// A written scene folder moved elsewhere (its object's mesh gone from where it was) loads and
// runs the same grasp.
TEST_F(SafeFilesTest, AMovedSceneFolderLoads) {
  const std::string box = write("box.obj", box_obj(60));
  const fs::path out = dir_ / "scene";
  const Result first = run_out("grasp --object " + box + " --scale 0.001 --max-steps 2 --json " +
                               "--write-scene " + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  fs::create_directories(dir_ / "far/away");
  fs::rename(out, dir_ / "far/away/scene");
  fs::remove(box);
  const Result moved =
      run_out("grasp " + (dir_ / "far/away/scene/box.xml").string() + " --max-steps 2 --json");
  ASSERT_EQ(moved.exit_code, 0) << moved.err;
  const nlohmann::json a = nlohmann::json::parse(first.out);
  const nlohmann::json b = nlohmann::json::parse(moved.out);
  EXPECT_EQ(a["object_z_initial"], b["object_z_initial"]);
  EXPECT_EQ(a["object_z_final"], b["object_z_final"]);
  // The object is named relative to the scene's folder; no file the scene reads is named under
  // the folder it was written in.
  const std::string xml = read_file(dir_ / "far/away/scene/box.xml");
  EXPECT_NE(xml.find("file=\"object/box.obj\""), std::string::npos) << xml;
  const std::regex file_attribute(R"re(file="([^"]*)")re");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), file_attribute);
       it != std::sregex_iterator(); ++it) {
    const std::string named = (*it)[1].str();
    EXPECT_EQ(named.find(out.string()), std::string::npos) << named;
    EXPECT_EQ(named.find(".."), std::string::npos) << named;
  }
}

// INT, TERM and HUP in the middle of a grasp: exit code 128 + the signal, the temporary folder
// (and, with --write-scene, the private folder) removed.
TEST_F(SafeFilesTest, AnInterruptedGraspLeavesNoTemporaryFiles) {
  const std::string box = write("box.obj", box_obj(60));
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const fs::path tmp = dir_ / ("tmp" + std::to_string(sig));
    fs::create_directories(tmp);
    EXPECT_EQ(
        interrupt({"grasp", "--object", box, "--scale", "0.001"}, tmp, tmp, "graspcd-object-", sig),
        128 + sig)
        << sig;
    EXPECT_TRUE(fs::is_empty(tmp)) << sig;
    const fs::path out = dir_ / ("out" + std::to_string(sig));
    fs::create_directories(out);
    EXPECT_EQ(
        interrupt({"grasp", "--object", box, "--scale", "0.001", "--write-scene", out.string()},
                  tmp, out, ".graspcd-box-", sig),
        128 + sig)
        << sig;
    EXPECT_TRUE(fs::is_empty(out)) << sig;
    EXPECT_TRUE(fs::is_empty(tmp)) << sig;
  }
}

#if GRASPCD_HAS_HACD  // graspcd decompose is built only with the decomposition
// An interrupted decompose leaves neither --out nor its hidden folder; an existing --out keeps
// its earlier decomposition.
TEST_F(SafeFilesTest, AnInterruptedDecomposeLeavesNoPartialOutput) {
  const std::string cup = kMjcf + "/meshes/cup.obj";
  const fs::path out = dir_ / "cup32";
  EXPECT_EQ(interrupt({"decompose", cup, "--out", out.string(), "--pieces", "32"}, dir_, dir_,
                      ".cup32.graspcd", SIGTERM),
            128 + SIGTERM);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(entries(dir_, ".cup32").empty());
}

// `n` separate unit cubes along x, 2 units apart: HACD gives one piece each, at once.
std::string cubes_obj(int n) {
  std::string out;
  for (int k = 0; k < n; ++k) {
    const int x = 2 * k;
    for (int c = 0; c < 8; ++c) {
      out += "v " + std::to_string(x + (c & 1)) + " " + std::to_string((c >> 1) & 1) + " " +
             std::to_string((c >> 2) & 1) + "\n";
    }
    const int b = 8 * k + 1;
    const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                              {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& f : faces) {
      out += "f " + std::to_string(b + f[0]) + " " + std::to_string(b + f[1]) + " " +
             std::to_string(b + f[2]) + "\n";
    }
  }
  return out;
}

// A reused --out holds the new decomposition only (no stale piece); a file its manifest does not
// list, or a folder graspcd did not write, is refused before the work.
TEST_F(SafeFilesTest, AReusedDecomposeOutDropsStalePieces) {
  const std::string cubes = write("cubes.obj", cubes_obj(3));
  const fs::path out = dir_ / "cubes";
  Outcome r = graspcd("decompose " + cubes + " --pieces 3 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(out / "cubes_piece_2.obj"));
  std::ofstream(out / "cubes_piece_99.obj") << "v 0 0 0\n";
  write("cubes.obj", cubes_obj(2));
  const std::string again = "decompose " + cubes + " --pieces 2 --out " + out.string();
  expect_refused(graspcd(again), out.string(), "a file the manifest does not list");
  EXPECT_TRUE(fs::exists(out / "cubes_piece_99.obj"));
  fs::remove(out / "cubes_piece_99.obj");
  r = graspcd(again);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(out / "cubes_piece_2.obj"));
  EXPECT_TRUE(fs::exists(out / "cubes_piece_1.obj"));
  EXPECT_EQ(load(out / "decomposition.json")["piece_count"], 2);
  EXPECT_TRUE(entries(dir_, ".cubes").empty());
  // Not a decomposition: refused, left as it was.
  const fs::path other = dir_ / "other";
  fs::create_directories(other);
  std::ofstream(other / "notes.txt") << "mine\n";
  expect_refused(graspcd("decompose " + cubes + " --pieces 2 --out " + other.string()),
                 other.string(), "a foreign folder");
  EXPECT_EQ(entries(other).size(), 1u);
}
// decompose never deletes the mesh it reads nor a file graspcd did not write, whatever --out
// names: a folder with an earlier decomposition that also holds the input (or is its folder's
// parent), or a user's notes, is refused before the work and left as it was.
TEST_F(SafeFilesTest, DecomposeNeverDeletesItsInputOrAUsersFile) {
  const fs::path out = dir_ / "d";
  const std::string cubes = write("cubes.obj", cubes_obj(2));
  ASSERT_EQ(graspcd("decompose " + cubes + " --pieces 2 --out " + out.string()).exit_code, 0);
  const std::string mine = write("d/mine.obj", cubes_obj(2));
  const auto refused = [&](const std::string& mesh, const std::string& why) {
    const std::vector<std::string> before = entries(out);
    const Outcome r = graspcd("decompose " + mesh + " --pieces 2 --out " + out.string());
    expect_refused(r, out.string(), why);
    EXPECT_EQ(entries(out), before) << why;
    return r.err;
  };
  EXPECT_NE(refused(mine, "the input in --out").find("holds the mesh this run reads (mine.obj)"),
            std::string::npos);
  EXPECT_NE(refused((out / "cubes_piece_0.obj").string(), "a piece as the input")
                .find("holds the mesh this run reads (cubes_piece_0.obj)"),
            std::string::npos);
  fs::create_directories(out / "sub");
  fs::rename(mine, out / "sub" / "mine.obj");
  EXPECT_NE(refused((out / "sub" / "mine.obj").string(), "the input under --out")
                .find("holds the mesh this run reads (sub/mine.obj)"),
            std::string::npos);
  fs::remove_all(out / "sub");
  std::ofstream(out / "notes.txt") << "mine\n";
  EXPECT_NE(refused(cubes, "a user's notes")
                .find("holds notes.txt, which graspcd decompose did "
                      "not write"),
            std::string::npos);
  EXPECT_EQ(read_file(out / "notes.txt"), "mine\n");
  EXPECT_TRUE(entries(dir_, ".d.").empty());
}

#endif

// A folder whose mode grants no write permission (0555) is refused as an output, also for root,
// to whom any mode is writable, and left as it was: decompose --out, --write-scene, a trajectory
// file in it.
TEST_F(SafeFilesTest, AReadOnlyFolderIsRefusedAlsoForRoot) {
  const fs::path ro = dir_ / "ro";
  fs::create_directories(ro);
  const fs::perms read_only = fs::perms::owner_read | fs::perms::owner_exec |
                              fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec;
  fs::permissions(ro, read_only);
  const std::string box = write("box.obj", box_obj(60));
  std::vector<std::pair<std::string, std::string>> cases = {
      {"grasp --object " + box + " --scale 0.001 --max-steps 1 --write-scene " + ro.string(),
       ro.string()},
      {"trajectory " + kMjcf + "/example1.xml --max-steps 1 --out " + (ro / "t.json").string(),
       (ro / "t.json").string()}};
#if GRASPCD_HAS_HACD
  cases.emplace_back(
      "decompose " + write("cubes.obj", cubes_obj(2)) + " --pieces 2 --out " + ro.string(),
      ro.string());
#endif
  for (const auto& [args, named] : cases) {
    const Outcome r = graspcd(args);
    expect_refused(r, named, args);
    EXPECT_NE(r.err.find("read-only (mode 0555)"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_empty(ro)) << args;
    EXPECT_EQ(fs::status(ro).permissions() & fs::perms::all, read_only) << args;
  }
  fs::permissions(ro, fs::perms::owner_all);
}

// trajectory --out never replaces a file the run reads (the scene, its pair config, its meshes),
// even with --force, and replaces a file graspcd did not write only with --force; an earlier
// trajectory is replaced.
TEST_F(SafeFilesTest, TrajectoryNeverOverwritesWhatItReadsNorAUsersFile) {
  const fs::path hand = dir_ / "hand";
  fs::create_directories(hand / "meshes");
  fs::copy_file(kMjcf + "/example1.xml", hand / "example1.xml");
  fs::copy_file(kMjcf + "/example1.pairs.json", hand / "example1.pairs.json");
  for (const char* mesh : {"finger_A.obj", "finger_B.obj", "finger_C.obj", "cup.obj"}) {
    fs::copy_file(kMjcf + "/meshes/" + mesh, hand / "meshes" / mesh);
  }
  const std::string scene = (hand / "example1.xml").string();
  const std::string args = "trajectory " + scene + " --max-steps 2 --methods sat --out ";
  for (const fs::path& input :
       {hand / "example1.xml", hand / "example1.pairs.json", hand / "meshes" / "cup.obj"}) {
    const std::string before = read_file(input);
    for (const std::string force : {"", " --force"}) {
      const Outcome r = graspcd(args + input.string() + force);
      expect_refused(r, input.string(), input.string() + force);
      EXPECT_NE(r.err.find("this run reads"), std::string::npos) << r.err;
      EXPECT_EQ(read_file(input), before) << input;
    }
  }
  // Another name of the scene (a link) is the scene.
  fs::create_symlink(hand / "example1.xml", dir_ / "link.xml");
  expect_refused(graspcd(args + (dir_ / "link.xml").string()), (dir_ / "link.xml").string(),
                 "a link to the scene");
  const std::string notes = write("notes.txt", "mine\n");
  const Outcome r = graspcd(args + notes);
  expect_refused(r, notes, "a user's file");
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(notes), "mine\n");
  EXPECT_EQ(graspcd(args + notes + " --force").exit_code, 0);
  EXPECT_NE(read_file(notes), "mine\n");
  const Outcome again = graspcd(args + notes);  // now a trajectory graspcd wrote
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(entries(dir_, ".notes").empty());
}

// The mesh reader's child (Assimp reads PLY in a child process, and loops on a PLY whose header
// ends early) dies with graspcd: after INT, TERM or HUP to graspcd no reader is left running.
TEST_F(SafeFilesTest, TheMeshReaderDiesWithGraspcd) {
  const std::string ply = write("loop.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const pid_t pid =
        graspcd::testing::spawn(GRASPCD_EXE, {"grasp", "--object", ply}, {},
                                (dir_ / "out.txt").string(), (dir_ / "err.txt").string());
    pid_t reader = 0;
    const bool forked = graspcd::testing::wait_for(
        [&] {
          const auto children = graspcd::testing::children_of(pid);
          if (!children.empty()) reader = children.front().first;
          return reader != 0;
        },
        60);
    kill(pid, sig);
    EXPECT_EQ(graspcd::testing::finish(pid, 60), 128 + sig) << read_file(dir_ / "err.txt");
    ASSERT_TRUE(forked) << "no reader started: " << read_file(dir_ / "err.txt");
    EXPECT_TRUE(
        graspcd::testing::wait_for([&] { return !graspcd::testing::process_runs(reader); }, 10))
        << "the reader runs on after graspcd ended (signal " << sig << ")";
    if (graspcd::testing::process_runs(reader)) kill(reader, SIGKILL);
  }
}

// TERM during `study --out DIR` after its first table was written: DIR is as it was (an earlier
// study's files untouched, none of the new run's), since the run writes into a private folder
// and moves its files in together at the end. A study of example 1 cut to 10 grasp steps; skipped
// in the sanitizer pass (its point is the files, which the Release pass checks).
TEST_F(SafeFilesTest, AnInterruptedStudyLeavesNoHalfStudy) {
  if (graspcd::testing::test_scale() < 1) {
    GTEST_SKIP() << "a study's run skipped at GRASPCD_TEST_SCALE < 1 (sanitizer pass)";
  }
  const fs::path out = dir_ / "study";
  fs::create_directories(out);
  std::ofstream(out / "study.json") << "earlier\n";
  std::ofstream(out / "sweep.json") << "earlier\n";
  const pid_t pid = graspcd::testing::spawn(
      GRASPCD_EXE,
      {"study", "--quick", "--repeats", "1", "--max-steps", "10", "--out", out.string()}, {},
      (dir_ / "out.txt").string(), (dir_ / "err.txt").string());
  // The first table written, wherever the run writes it (DIR or a folder of its own in DIR).
  const bool table = graspcd::testing::wait_for(
      [&] {
        std::error_code ec;
        for (const auto& e : fs::recursive_directory_iterator(out, ec)) {
          if (e.path().filename() == "table1.csv") return true;
        }
        return false;
      },
      300);
  kill(pid, SIGTERM);
  EXPECT_EQ(graspcd::testing::finish(pid, 60), 128 + SIGTERM) << read_file(dir_ / "err.txt");
  ASSERT_TRUE(table) << "no table was written: " << read_file(dir_ / "err.txt");
  std::vector<std::string> left = entries(out);
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"study.json", "sweep.json"}));
  EXPECT_EQ(read_file(out / "study.json"), "earlier\n");
  EXPECT_EQ(read_file(out / "sweep.json"), "earlier\n");
}

// Outputs that cannot be written: one line naming the file, exit code 2, before the work.
TEST_F(SafeFilesTest, AnOutputThatCannotBeWrittenIsOneLineNamingIt) {
  const std::string box = write("box.obj", box_obj(60));
  const std::string file = write("file.txt", "a file\n");
  const std::string scene = kMjcf + "/example1.xml";
  const std::string grasp = "grasp --object " + box + " --scale 0.001 --max-steps 1";
  expect_refused(graspcd(grasp + " --write-scene " + file + "/scene"), file + "/scene",
                 "--write-scene under a file");
  expect_refused(graspcd(grasp + " --write-scene " + file), file, "--write-scene onto a file");
  // A read-only folder (root writes into a mode 555 folder: sysfs refuses even root).
  const fs::path read_only = geteuid() == 0 ? fs::path("/sys/kernel") : dir_ / "ro";
  if (geteuid() != 0) {
    fs::create_directories(read_only);
    fs::permissions(read_only, fs::perms::owner_read | fs::perms::owner_exec);
  }
  if (fs::is_directory(read_only)) {
    expect_refused(graspcd(grasp + " --write-scene " + read_only.string()), read_only.string(),
                   "--write-scene into a read-only folder");
  }
  const Outcome no_tmp =
      run("TMPDIR='" + (dir_ / "missing").string() + "' '" + GRASPCD_EXE + "' " + grasp);
  expect_refused(no_tmp, (dir_ / "missing").string(), "a missing TMPDIR");
  expect_refused(graspcd("validate " + scene + " --max-steps 1 --out /dev/full"), "/dev/full",
                 "validate --out /dev/full");
  expect_refused(graspcd("validate " + scene + " --max-steps 1 --out " + file), file,
                 "validate --out FILE");
  const std::string nowhere = file + "/t.json";
  expect_refused(graspcd("trajectory " + scene + " --out " + nowhere), nowhere,
                 "trajectory --out under a file");
  expect_refused(graspcd("trajectory " + scene + " --out " + dir_.string()), dir_.string(),
                 "trajectory --out onto a folder");
  if (fs::is_directory(read_only)) {
    const std::string locked = (read_only / "t.json").string();
    expect_refused(graspcd("trajectory " + scene + " --out " + locked), locked,
                   "trajectory --out in a read-only folder");
  }
#if GRASPCD_HAS_HACD
  expect_refused(graspcd("decompose " + kMjcf + "/meshes/cup.obj --out " + file), file,
                 "decompose --out FILE");
#endif
  EXPECT_TRUE(entries(dir_, ".").empty());
}

// Messages and JSON name the user's files: without --write-scene the document names no scene
// (the temporary one is gone) and stderr no temporary path.
TEST_F(SafeFilesTest, TheOutputNamesNoTemporaryFile) {
  const std::string box = write("box.obj", box_obj(60));
  const fs::path tmp = dir_ / "tmp";
  fs::create_directories(tmp);
  const Result r = run_out("grasp --object " + box + " --scale 0.001 --max-steps 1 --json",
                           "TMPDIR='" + tmp.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_TRUE(doc["object"]["scene"].is_null());
  EXPECT_EQ(doc["scene"], box);
  EXPECT_EQ(r.out.find(tmp.string()), std::string::npos);
  EXPECT_EQ(r.err.find(tmp.string()), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(tmp));
}

}  // namespace
}  // namespace safe_files_test
