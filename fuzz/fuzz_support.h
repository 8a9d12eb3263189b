// Helpers shared by the libFuzzer targets of fuzz/ (docs/fuzzing.md).
#pragma once

#include <stdlib.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace graspcd::fuzz {

// A file that holds the current fuzz input, for the parsers that read files by name (the text
// grammar and the mesh loader choose by path). One private temporary folder per process, removed
// at a normal exit; the file is rewritten for every input.
class InputFile {
 public:
  // `name` is the file's name inside the folder, e.g. "input.obj" (the extension matters to
  // load_mesh).
  explicit InputFile(const std::string& name) {
    char pattern[] = "/tmp/graspcd-fuzz-XXXXXX";
    const char* dir = ::mkdtemp(pattern);
    if (dir == nullptr) {
      std::perror("graspcd fuzz: mkdtemp");
      std::abort();
    }
    dir_ = dir;
    path_ = dir_ + "/" + name;
  }
  ~InputFile() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // Writes the bytes and returns the path.
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
      std::fprintf(stderr, "graspcd fuzz: cannot write %s\n", path_.c_str());
      std::abort();
    }
    return path_;
  }
  const std::string& path() const { return path_; }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::string path_;
};

// Reports a wrong answer found by an oracle and aborts (libFuzzer saves the input).
[[noreturn]] inline void disagreement(const char* what) {
  std::fprintf(stderr, "graspcd fuzz: %s\n", what);
  std::abort();
}

}  // namespace graspcd::fuzz
