// A careless or hostile user's input to every subcommand (docs/bad-input.md): no hang, nothing
// silent, the error naming the file or the option at fault, one line and exit 2. Each test runs
// the graspcd executable; ctest gives each a timeout (tests/CMakeLists.txt), so a hang fails.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers/command_test.h"

namespace fs = std::filesystem;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif
#else
constexpr bool kAsan = false;
#endif

std::string cube_obj() {
  return "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\n"
         "f 3 8 7\nf 4 1 5\nf 4 5 8\n";
}

#if GRASPCD_HAS_HACD  // only the decomposition test below uses it
// A torus of 16 x 8 quads: concave, so its pieces' hulls lie off its surface, and the farthest
// point lies inside a face, where the distance is refined rather than found at a vertex.
std::string torus_obj() {
  constexpr int kAround = 16;
  constexpr int kAcross = 8;
  std::ostringstream out;
  for (int i = 0; i < kAround; ++i) {
    const double a = 2 * M_PI * i / kAround;
    for (int j = 0; j < kAcross; ++j) {
      const double b = 2 * M_PI * j / kAcross;
      const double r = 2 + 0.7 * std::cos(b);
      out << "v " << r * std::cos(a) << ' ' << r * std::sin(a) << ' ' << 0.7 * std::sin(b) << '\n';
    }
  }
  const auto v = [](int i, int j) { return 1 + (i % kAround) * kAcross + (j % kAcross); };
  for (int i = 0; i < kAround; ++i) {
    for (int j = 0; j < kAcross; ++j) {
      out << "f " << v(i, j) << ' ' << v(i + 1, j) << ' ' << v(i + 1, j + 1) << '\n';
      out << "f " << v(i, j) << ' ' << v(i + 1, j + 1) << ' ' << v(i, j + 1) << '\n';
    }
  }
  return out.str();
}
#endif

std::string shipped_scene(const std::string& name) {
  return (fs::path(GRASPCD_DATA_DIR).parent_path() / "mjcf" / (name + ".xml")).string();
}

// A scene of one box that needs no mesh, and its pair config.
const char* const kBoxScene =
    "<mujoco>\n  <worldbody>\n    <geom name=\"a\" type=\"box\" size=\"1 1 1\"/>\n"
    "  </worldbody>\n</mujoco>\n";
const char* const kPairs = R"({"pairs": [{"a": "a", "b": "a"}]})";

class HostileInputTest : public graspcd::testing::CommandTest {
 protected:
  // The one line of stderr, checked to be one line.
  static std::string one_line(const graspcd::testing::Outcome& r) {
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
    return r.err;
  }
  std::string big_line_file(const std::string& name, const std::string& before) {
    const std::string path = (dir_ / name).string();
    std::ofstream out(path, std::ios::binary);
    out << before << std::string((std::size_t{17} << 20), '1') << "\n";
    return path;
  }
};

// --- Hangs ---

// The decomposition is an optional part of the build (GRASPCD_WITH_HACD): this test exists only
// in a build that has it.
#if GRASPCD_HAS_HACD
TEST_F(HostileInputTest, DecomposeRefusesAHausdorffBoundFinerThanItCanReach) {
  const std::string mesh = write("torus.obj", torus_obj());
  const auto r = graspcd("decompose " + mesh + " --out " + (dir_ / "dec").string() +
                         " --pieces 16 --hausdorff-bound 1e-300");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r).rfind("graspcd: --hausdorff-bound: the bound 1e-300 m is finer", 0), 0u)
      << r.err;
}
#endif

TEST_F(HostileInputTest, ObjectFolderWalkKeepsInsideTheFolderAndReadsEachFolderOnce) {
  const fs::path objects = dir_ / "objects";
  fs::create_directories(objects / "sub");
  write("objects/bad.obj", "v nan 0 0\n");  // refused at once: its row is quick
  write("outside.obj", "v nan 0 0\n");      // beside the folder, not in it
  fs::create_directory_symlink("..", objects / "up");
  fs::create_directory_symlink("..", objects / "sub" / "loop");
  fs::create_directory_symlink(".", objects / "self");
  const auto r = graspcd("validate --objects " + objects.string() + " --max-steps 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // One object, one refusal warning.
  std::size_t refused = 0;
  for (std::size_t at = r.err.find("warning:"); at != std::string::npos;
       at = r.err.find("warning:", at + 1)) {
    ++refused;
  }
  EXPECT_EQ(refused, 1u) << r.err;
  EXPECT_EQ(r.err.find("outside.obj"), std::string::npos) << r.err;
}

TEST_F(HostileInputTest, AnEndlessLineIsRefusedAtItsLine) {
  for (const char* command : {"tritri", "boxbox"}) {
    const auto r = graspcd(std::string(command) + " /dev/zero");
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_EQ(one_line(r), "/dev/zero:1: line longer than 16777216 bytes\n") << command;
  }
  const std::string cases = big_line_file("cases.txt", "# a comment\n");
  const auto t = graspcd("tritri " + cases);
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_EQ(one_line(t), cases + ":2: line longer than 16777216 bytes\n");
  const std::string obj = big_line_file("long.obj", "v 0 0 0\n# ");
  const auto m = graspcd("meshpair " + obj + " " + obj + " --poses - < /dev/null");
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_EQ(one_line(m), obj + ":2: line longer than 16777216 bytes\n");
}

// Under a memory limit an endless line is still one line naming the file, never exit 0. ASan
// cannot run under a memory limit: the sanitizer pass skips this test.
TEST_F(HostileInputTest, UnderAMemoryLimitAnEndlessLineIsAnErrorNamingTheFile) {
  if (kAsan) GTEST_SKIP() << "AddressSanitizer cannot run under a memory limit";
  const std::string cases = big_line_file("cases.txt", "");
  for (const std::string& args :
       std::vector<std::string>{"tritri /dev/zero", "boxbox /dev/zero", "boxbox " + cases}) {
    const auto r = run("ulimit -v 400000; '" + std::string(GRASPCD_EXE) + "' " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    const std::string file = args.substr(args.find(' ') + 1);
    EXPECT_EQ(r.err.rfind(file + ":1: ", 0), 0u) << args << ": " << r.err;
  }
}

TEST_F(HostileInputTest, AFifoOrAFolderAsAMeshSceneOrConfigIsRefusedAtOnce) {
  const std::string fifo = (dir_ / "fifo.obj").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string cube = write("cube.obj", cube_obj());
  auto r = graspcd("grasp --object " + fifo);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), fifo + ": not a regular file (a FIFO)\n");
  r = graspcd("meshpair " + fifo + " " + cube + " --poses - < /dev/null");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), fifo + ": not a regular file (a FIFO)\n");
  const std::string config = (dir_ / "fifo.json").string();
  ASSERT_EQ(::mkfifo(config.c_str(), 0600), 0);
  r = graspcd("grasp " + shipped_scene("example1") + " --config " + config);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(one_line(r).find(config + ": "), std::string::npos) << r.err;
  fs::create_directory(dir_ / "folder.obj");
  r = graspcd("meshpair " + (dir_ / "folder.obj").string() + " " + cube + " --poses - < /dev/null");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), (dir_ / "folder.obj").string() + ": not a regular file (a folder)\n");
}

// A named FIFO as text input: read when something writes to it, refused when nothing does.
TEST_F(HostileInputTest, AFifoAsTextInputIsReadOrRefusedNeverWaitedOnForever) {
  const std::string fifo = (dir_ / "cases.fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string tri = "0 0 0  1 0 0  0 1 0   0 0 0  1 0 0  0 1 0";
  auto r = run("(sleep 0.2; echo '" + tri + "') > '" + fifo + "' & '" + GRASPCD_EXE + "' tritri '" +
               fifo + "'; wait");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = graspcd("tritri " + fifo);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), fifo +
                             ": a FIFO that nothing wrote to in 10 s (give the input on standard "
                             "input, -, instead)\n");
}

// --- Nothing silent ---

TEST_F(HostileInputTest, AnEmptyPairListIsAnError) {
  const std::string config = write("empty.json", R"({"method": "sat", "pairs": []})");
  const auto r = graspcd("grasp " + shipped_scene("example1") + " --config " + config);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), config + ": 'pairs' is empty: the config would serve no pair\n");
}

TEST_F(HostileInputTest, ADuplicateKeyIsAnErrorNamingItAndItsLines) {
  const std::string config =
      write("dup.json",
            "{\n  \"method\": \"sat\",\n  \"pairs\": [{\"a\": \"x\", \"b\": \"y\"}],\n"
            "  \"method\": \"perceptron\"\n}\n");
  const auto r = graspcd("grasp " + shipped_scene("example1") + " --config " + config);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), config + ":4: duplicate key 'method' (lines 2 and 4)\n");
  // In a pair entry, and an escaped spelling of the same key.
  const std::string inner =
      write("inner.json", R"({"pairs": [{"a": "x", "b": "y", "\u0061": "z"}]})");
  const auto i = graspcd("grasp " + shipped_scene("example1") + " --config " + inner);
  EXPECT_EQ(i.exit_code, 2);
  EXPECT_EQ(one_line(i), inner + ":1: duplicate key 'a' (lines 1 and 1)\n");
}

TEST_F(HostileInputTest, ContentAfterTheXmlRootIsAnError) {
  const std::string scene = write("two.xml", std::string(kBoxScene) + "<mujoco/>\n");
  write("two.pairs.json", kPairs);
  const auto r = graspcd("validate " + scene);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r).rfind(scene + ":6: a second root element <mujoco> after <mujoco>", 0), 0u)
      << r.err;
}

TEST_F(HostileInputTest, AWordAfterVersionIsAnError) {
  const auto r = graspcd("--version foo");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r).rfind("graspcd: --version: unexpected argument 'foo'", 0), 0u) << r.err;
}

// --- Errors that name the right thing ---

TEST_F(HostileInputTest, PlacementOptionsAreNamedWhenTheirNumbersMeanNothing) {
  const std::string box = write("box.obj", cube_obj());
  const struct {
    const char* args;
    const char* error;
  } cases[] = {
      {"--yaw nan", "graspcd: --yaw: Value nan is not a finite number"},
      {"--pose inf 0 0 0", "graspcd: --pose: Value inf is not a finite number"},
      {"--pose nan 0 0 0", "graspcd: --pose: Value nan is not a finite number"},
      {"--pose 0 0 0 0", "graspcd: --pose: not a finite unit quaternion"},
      {"--scale 1e308", "graspcd: --scale: Value 1e308 is not in [1e-06, 1000]"},
  };
  for (const auto& c : cases) {
    const auto r = graspcd("grasp --object " + box + " " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_EQ(one_line(r).rfind(c.error, 0), 0u) << c.args << ": " << r.err;
  }
  // A tiny quaternion is normalised, not taken for zero.
  const auto r = graspcd("grasp --object " + box + " --scale 0.01 --pose 1e-300 0 0 0 " +
                         "--max-steps 1 --write-scene " + (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("quaternion"), std::string::npos) << r.err;
}

TEST_F(HostileInputTest, ValidateNamesABadSceneBeforeItsMissingConfig) {
  const std::string scene = write("garbage.xml", "this is no scene\n");
  const auto r = graspcd("validate " + scene);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r).rfind(scene + ": ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("pairs.json"), std::string::npos) << r.err;
}

TEST_F(HostileInputTest, AMeshThatIsAFolderOrGarbageIsNamed) {
  fs::create_directory(dir_ / "folder.obj");
  write("garbage.obj", "hello\n");
  for (const char* mesh : {"folder.obj", "garbage.obj"}) {
    const std::string scene =
        write("s.xml", std::string("<mujoco>\n  <asset>\n    <mesh name=\"m\" file=\"") + mesh +
                           "\"/>\n  </asset>\n  <worldbody>\n    <geom type=\"mesh\" mesh=\"m\"/>\n"
                           "  </worldbody>\n</mujoco>\n");
    write("s.pairs.json", kPairs);
    const auto r = graspcd("validate " + scene);
    EXPECT_EQ(r.exit_code, 2) << mesh;
    EXPECT_EQ(one_line(r).rfind((dir_ / mesh).string() + ": ", 0), 0u) << r.err;
  }
}

// --- One error form ---

TEST_F(HostileInputTest, MergeWithoutShardFilesNamesWhatIsWrong) {
  auto r = graspcd("validate --merge --out " + (dir_ / "m").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r),
            "--merge: '--out' is no shard file (give the shard files after --merge)\n");
  fs::create_directory(dir_ / "shard.json");
  r = graspcd("validate --merge " + (dir_ / "shard.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), (dir_ / "shard.json").string() + ": not a regular file (a folder)\n");
  r = graspcd("study --merge " + (dir_ / "missing.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(one_line(r), (dir_ / "missing.json").string() + ": cannot open the shard file\n");
}

}  // namespace
