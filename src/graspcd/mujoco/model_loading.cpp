#include "graspcd/mujoco/model_loading.h"

#include <mujoco/mujoco.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <string>
#include <system_error>

#include "graspcd/mujoco/model_check.h"
#include "graspcd/mujoco/scene_check.h"

namespace graspcd::mujoco {

namespace {

// MuJoCo's mesh compiler runs qhull with stderr as qhull's error file: a mesh without a 3D hull
// (e.g. one scaled to 1e-21 m) prints a page of qhull's diagnostics there before mj_loadXML
// returns its own one-line error. While a model loads, file descriptor 2 goes to a temporary file
// (serialised: the descriptor is the process's); what was written is passed on to stderr after a
// load that succeeded, and the first qhull line ("QH6154 Qhull precision error: ...") joins the
// error of one that failed.
class CapturedStderr {
 public:
  CapturedStderr() : lock_(mutex()), file_(std::tmpfile()) {
    std::fflush(stderr);
    if (file_ != nullptr) saved_ = ::dup(STDERR_FILENO);
    if (saved_ >= 0) ::dup2(::fileno(file_), STDERR_FILENO);
  }
  ~CapturedStderr() {
    restore();
    if (file_ != nullptr) std::fclose(file_);
  }
  CapturedStderr(const CapturedStderr&) = delete;
  CapturedStderr& operator=(const CapturedStderr&) = delete;

  // Restores stderr and returns what was written meanwhile.
  std::string release() {
    restore();
    std::string text;
    if (file_ == nullptr) return text;
    std::rewind(file_);
    char chunk[4096];
    for (std::size_t n; (n = std::fread(chunk, 1, sizeof(chunk), file_)) > 0;)
      text.append(chunk, n);
    return text;
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
  }

  std::lock_guard<std::mutex> lock_;
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

// The first line of `text` that starts with "QH" (a qhull message code), or "".
std::string qhull_line(const std::string& text) {
  std::size_t at = text.rfind("QH", 0) == 0 ? 0 : text.find("\nQH");
  if (at == std::string::npos) return "";
  if (at > 0) ++at;
  return text.substr(at, text.find('\n', at) - at);
}

}  // namespace

ModelPtr load_model(const std::string& path, const SceneNames& names) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path).good())
    throw names.refusal(path, 0, "cannot open the scene file");
  // What MuJoCo would accept with a warning or misread (scene_check.h), then MuJoCo's own checks,
  // then the compiled numbers (model_check.h: the same rule for what the checks cannot see).
  check_scene_file(path, names);
  char error[2048] = "";
  ModelPtr m;
  std::string qhull;
  {
    CapturedStderr captured;
    m.reset(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
    const std::string text = captured.release();
    if (m) {
      std::cerr << text;
    } else {
      qhull = qhull_line(text);
    }
  }
  if (!m) {
    std::string message = io::one_line(error);
    if (message.empty()) message = "MuJoCo could not load it";
    if (!qhull.empty()) message += "; " + qhull;
    throw names.refusal(path, 0, message);
  }
  const std::string non_finite = find_non_finite(m.get());
  if (!non_finite.empty()) throw names.refusal(path, 0, non_finite);
  return m;
}

}  // namespace graspcd::mujoco
