// Helpers of the command-line tests (tests/app/cli_*_test.cpp): CliTest runs the real `graspcd`
// binary (GRASPCD_EXE) on small inputs; shared inputs and readers of its output.
#pragma once

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

#include "helpers/envelope_check.h"
#include "helpers/temp_dir.h"

namespace graspcd::cli_testing {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Splits text into lines (without their '\n').
inline std::vector<std::string> lines(const std::string& text) {
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
inline bool sanitizer_pass() {
  const char* scale = std::getenv("GRASPCD_TEST_SCALE");
  return scale != nullptr && std::strtod(scale, nullptr) < 1;
}

// Why a test that grasps with real hands (their files below GRASPCD_MODELS_DIR/hands, e.g.
// "robotiq_2f85/2f85.xml") cannot run here: a hand missing, or the sanitizer pass, where such a
// grasp takes ten times as long; empty when it can (SKIP_UNLESS_REAL_HAND_GRASPS).
inline std::string real_hand_skip(const std::vector<std::string>& hands) {
  const fs::path models = fs::path(GRASPCD_MODELS_DIR);
  for (const std::string& hand : hands) {
    if (!fs::exists(models / "hands" / hand)) return "real hands not found in " + models.string();
  }
  if (sanitizer_pass()) {
    return "real-hand grasps skipped at GRASPCD_TEST_SCALE < 1 (sanitizer pass)";
  }
  return "";
}

// Triangle pairs: T1 in the plane z = 0, T2 sharing its vertex at the origin / lifted by 1.
const char* const kTouching = "0 0 0 1 0 0 0 1 0  0 0 0 0 0 1 1 0 1\n";
const char* const kSeparated = "0 0 0 1 0 0 0 1 0  0 0 1 0 0 2 1 0 2\n";
// Unit cubes (half-extent 1) at x = 0 and x = 2.5 / 2 (touching faces) / 1 (overlapping).
const char* const kBoxesApart = "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  2.5 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n";
const char* const kBoxesTouch = "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  2 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n";
const char* const kBoxesOverlap = "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1  1 0 0 0 -1 0 1 0 0 0 0 1 1 1 1\n";

// Usage errors: exit 2 with exactly one line on stderr.
inline void expect_usage_error(const Result& r) {
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("graspcd: ", 0), 0u) << r.err;
}

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
inline std::vector<std::string> flags_and_counts(const std::string& out) {
  std::vector<std::string> result;
  const std::regex line_form("([01]) ([0-9]+) ([0-9]+)");
  for (const std::string& line : lines(out)) {
    std::smatch m;
    EXPECT_TRUE(std::regex_match(line, m, line_form)) << line;
    result.push_back(m.size() == 4 ? m[1].str() + " " + m[2].str() : line);
  }
  return result;
}

// The shipped scenes (mjcf/ beside data/).
inline std::string shipped_scene(const std::string& name) {
  return (fs::path(GRASPCD_DATA_DIR).parent_path() / "mjcf" / (name + ".xml")).string();
}

// A closed box 50 x 40 x 60 (file units: millimetres), off the origin: x 100..150, z 10..70.
const char* const kUserBox =
    "v 100 -20 10\nv 150 -20 10\nv 150 20 10\nv 100 20 10\n"
    "v 100 -20 70\nv 150 -20 70\nv 150 20 70\nv 100 20 70\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

// The box of kUserBox in metres: 5 x 4 x 6 cm, off the origin.
inline std::string user_box_in_metres() {
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

// `obj` with every face reversed: the same closed box turned inside out.
inline std::string inside_out(const std::string& obj) {
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

// A copy of a shipped scene in the test folder, with its meshes in DIR/meshes (the scene's
// meshdir); `skip_mesh` is left out, and `open_mesh` is written without its last face.
inline std::string copy_scene(const fs::path& dir, const std::string& name,
                              const std::string& skip_mesh, const std::string& open_mesh) {
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

// A unit cube (12 faces) in an OBJ, 8 vertices; `first` replaces the first vertex line.
inline std::string cube_obj(const std::string& first = "v 0 0 0") {
  return first +
         "\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\n"
         "f 3 8 7\nf 4 1 5\nf 4 5 8\n";
}
}  // namespace graspcd::cli_testing

// Skips the test, saying why, unless it can grasp with the real hands named (real_hand_skip).
#define SKIP_UNLESS_REAL_HAND_GRASPS(...)                                                    \
  if (const std::string why_skipped = ::graspcd::cli_testing::real_hand_skip({__VA_ARGS__}); \
      !why_skipped.empty())                                                                  \
  GTEST_SKIP() << why_skipped
