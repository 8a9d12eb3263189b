// A googletest fixture that runs command lines (graspcd, python scripts) in a fresh temporary
// folder and keeps their exit code and stderr; with helpers to read what they wrote.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "helpers/temp_dir.h"

namespace graspcd::testing {

struct Outcome {
  int exit_code = -1;
  std::string err;
};

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

class CommandTest : public TempDirTest {
 protected:
  // Runs `command_line` through the shell, stdout discarded.
  Outcome run(const std::string& command_line) {
    const std::filesystem::path err = dir_ / "stderr.txt";
    const int status =
        std::system((command_line + " > /dev/null 2> '" + err.string() + "'").c_str());
    Outcome r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.err = read_file(err);
    return r;
  }
  Outcome graspcd(const std::string& args) {
    return run(std::string("'") + GRASPCD_EXE + "' " + args);
  }
  static nlohmann::json load(const std::filesystem::path& p) {
    std::ifstream in(p);
    nlohmann::json j;
    in >> j;
    return j;
  }
};

}  // namespace graspcd::testing
