// Inputs that would make graspcd wait without a word (docs/bad-input.md): a FIFO wherever a scene
// names a file is refused at once, a large object is announced before MuJoCo compiles it and
// stopped at its time limit, and a FIFO among a folder of objects gets its row. ctest gives each
// test a timeout (tests/CMakeLists.txt), so a hang fails rather than stalls the pass.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "graspcd/grasp/object_run.h"
#include "helpers/command_test.h"

namespace {

namespace fs = std::filesystem;
using graspcd::testing::Outcome;
using graspcd::testing::read_file;

const fs::path kMjcf = GRASPCD_MJCF_DIR;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A 50 x 40 x 60 mm box, file units mm.
std::string box_obj() {
  return "v 100 -20 10\nv 150 -20 10\nv 150 20 10\nv 100 20 10\n"
         "v 100 -20 70\nv 150 -20 70\nv 150 20 70\nv 100 20 70\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
         "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
}

// A closed sphere of radius `r` m as a binary STL of at least `faces` triangles (a UV sphere).
std::string sphere_stl(double r, std::size_t faces) {
  const int rings = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(faces) / 4.0))) + 1;
  const int segments = 2 * rings;
  const auto point = [&](int i, int j) {
    const double theta = M_PI * i / rings;
    const double phi = 2 * M_PI * j / segments;
    return std::array<float, 3>{static_cast<float>(r * std::sin(theta) * std::cos(phi)),
                                static_cast<float>(r * std::sin(theta) * std::sin(phi)),
                                static_cast<float>(r * std::cos(theta))};
  };
  std::vector<std::array<std::array<float, 3>, 3>> triangles;
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const auto a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      if (i > 0) triangles.push_back({a, b, d});
      if (i + 1 < rings) triangles.push_back({d, b, c});
    }
  }
  std::string out(80, '\0');
  const auto put = [&out](const void* p, std::size_t n) {
    out.append(static_cast<const char*>(p), n);
  };
  const std::uint32_t count = static_cast<std::uint32_t>(triangles.size());
  put(&count, 4);
  const float normal[3] = {0, 0, 0};
  const std::uint16_t attributes = 0;
  for (const auto& t : triangles) {
    put(normal, 12);
    for (const auto& v : t) put(v.data(), 12);
    put(&attributes, 2);
  }
  return out;
}

class LongWaits : public graspcd::testing::CommandTest {
 protected:
  // A copy of example 1 in `folder` (its meshes by a link) whose worldbody is preceded by `extra`.
  fs::path scene_with(const fs::path& folder, const std::string& extra) {
    fs::create_directories(folder);
    std::string xml = read_file(kMjcf / "example1.xml");
    const std::size_t at = xml.find("<worldbody>");
    xml.insert(at, extra + "\n  ");
    std::ofstream(folder / "scene.xml") << xml;
    fs::copy_file(kMjcf / "example1.pairs.json", folder / "scene.pairs.json");
    fs::create_directory_symlink(kMjcf / "meshes", folder / "meshes");
    return folder / "scene.xml";
  }

  // Exit code 2 and one line that starts with `start` and holds `words`.
  static void expect_refused(const Outcome& r, const std::string& start,
                             const std::vector<std::string>& words, const std::string& what) {
    EXPECT_EQ(r.exit_code, 2) << what << ": " << r.err;
    EXPECT_EQ(lines(r.err).size(), 1u) << what << ": " << r.err;
    EXPECT_EQ(r.err.rfind(start, 0), 0u) << what << ": " << r.err;
    for (const std::string& w : words)
      EXPECT_NE(r.err.find(w), std::string::npos) << what << ": " << r.err;
  }
};

// An <include> naming a FIFO, and a texture whose file is one: refused at the element's line
// before anything opens them, by every command that loads a scene.
TEST_F(LongWaits, AFifoTheSceneNamesIsRefusedAtOnce) {
  const fs::path include = scene_with(dir_ / "include", "<include file=\"p.xml\"/>");
  ASSERT_EQ(mkfifo((dir_ / "include" / "p.xml").c_str(), 0600), 0);
  const std::string at = include.string() + ":";
  const std::vector<std::string> words = {"<include file=\"p.xml\">",
                                          (dir_ / "include" / "p.xml").string(), "a FIFO"};
  expect_refused(graspcd("grasp " + include.string() + " --max-steps 1"), at, words, "grasp");
  expect_refused(graspcd("validate " + include.string() + " --max-steps 1"), at, words, "validate");
  expect_refused(graspcd("trajectory " + include.string() + " --out " + (dir_ / "t.json").string() +
                         " --max-steps 1"),
                 at, words, "trajectory");
  EXPECT_FALSE(fs::exists(dir_ / "t.json"));

  const fs::path texture = scene_with(
      dir_ / "texture", "<asset><texture name=\"t\" type=\"2d\" file=\"t.png\"/></asset>");
  ASSERT_EQ(mkfifo((dir_ / "texture" / "t.png").c_str(), 0600), 0);
  expect_refused(graspcd("grasp " + texture.string() + " --max-steps 1"), texture.string() + ":",
                 {"<texture file=\"t.png\">", "a FIFO"}, "a texture");
}

// An object of kLargeObjectFaces triangles: one line says before the wait that MuJoCo compiles it
// slowly and when the run stops; past --load-timeout the run stops with one line naming the
// object, exit code 2, its temporary folder removed.
TEST_F(LongWaits, ALargeObjectIsAnnouncedAndStoppedAtItsTimeLimit) {
  const std::string big = write("big.stl", sphere_stl(0.02, graspcd::grasp::kLargeObjectFaces));
  const fs::path tmp = dir_ / "tmp";
  fs::create_directories(tmp);
  const Outcome r = run("TMPDIR='" + tmp.string() + "' '" + GRASPCD_EXE + "' grasp --object " +
                        big + " --load-timeout 0.2");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const std::vector<std::string> out = lines(r.err);
  ASSERT_EQ(out.size(), 2u) << r.err;
  EXPECT_EQ(out[0].rfind("[grasp] " + big + ": ", 0), 0u) << out[0];
  EXPECT_NE(out[0].find(" triangles: MuJoCo compiles a mesh this large slowly"), std::string::npos)
      << out[0];
  EXPECT_NE(out[0].find("stopped if it has not started in 0.2 s (--load-timeout)"),
            std::string::npos)
      << out[0];
  EXPECT_EQ(out[1].rfind(big + ": the grasp did not start within 0.2 s", 0), 0u) << out[1];
  EXPECT_NE(out[1].find("--load-timeout raises the limit"), std::string::npos) << out[1];
  EXPECT_TRUE(fs::is_empty(tmp));
  // A small object says nothing of a wait.
  const std::string box = write("box.obj", box_obj());
  const Outcome small = graspcd("grasp --object " + box + " --scale 0.001 --max-steps 1");
  EXPECT_EQ(small.exit_code, 0) << small.err;
  EXPECT_EQ(small.err.find("[grasp]"), std::string::npos) << small.err;
}

// A FIFO with a mesh's name in a folder of objects is a refused row, not left out; a link of a
// mesh's name that leads out of the folder is named as skipped.
TEST_F(LongWaits, AFifoAmongObjectsIsARefusedRow) {
  const fs::path set = dir_ / "set";
  fs::create_directories(set);
  write("set/box.obj", box_obj());
  ASSERT_EQ(mkfifo((set / "p.obj").c_str(), 0600), 0);
  write("elsewhere.obj", box_obj());
  fs::create_symlink(dir_ / "elsewhere.obj", set / "out.obj");
  const fs::path json = dir_ / "set.json";
  const Outcome r =
      run(std::string("{ '") + GRASPCD_EXE + "' validate --objects " + set.string() +
          " --scale 0.001 --max-steps 1 --method sat --json > '" + json.string() + "'; }");
  EXPECT_EQ(r.exit_code, 2) << r.err;  // a refused object
  const nlohmann::json doc = load(json);
  ASSERT_EQ(doc["rows"].size(), 2u) << doc.dump(1);
  EXPECT_EQ(doc["rows"][0]["object"], "box.obj");
  EXPECT_EQ(doc["rows"][1]["object"], "p.obj");
  EXPECT_EQ(doc["rows"][1]["status"], "refused");
  EXPECT_NE(doc["rows"][1]["error"].get<std::string>().find("not a regular file (a FIFO)"),
            std::string::npos)
      << doc["rows"][1];
  bool skipped = false;
  for (const nlohmann::json& w : doc["warnings"]) {
    if (w["code"] == "object_skipped") {
      skipped = true;
      EXPECT_NE(w["message"].get<std::string>().find((set / "out.obj").string()), std::string::npos)
          << w;
    }
  }
  EXPECT_TRUE(skipped) << doc["warnings"];
}

}  // namespace
