#include "graspcd/version/data_dirs.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#if !defined(GRASPCD_MJCF_FROM_EXE) || !defined(GRASPCD_MJCF_BUILD_DIR) || \
    !defined(GRASPCD_MODELS_BUILD_DIR)
#error "src/CMakeLists.txt defines where graspcd_version finds the templates and the models"
#endif

namespace graspcd {

namespace fs = std::filesystem;

namespace {

// The folder with no link in its path: a scene written from a template names the template's files
// by paths relative to the scene, which lead elsewhere through a link's "..".
std::string without_links(const fs::path& dir) {
  std::error_code ec;
  const fs::path real = fs::canonical(dir, ec);
  return ec ? dir.string() : real.string();
}

}  // namespace

std::string mjcf_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path() / GRASPCD_MJCF_FROM_EXE;
    if (fs::is_directory(installed, ec)) return without_links(installed);
  }
  return without_links(GRASPCD_MJCF_BUILD_DIR);
}

std::string models_dir() {
  const char* env = std::getenv("GRASPCD_MODELS_DIR");
  if (env != nullptr && *env != '\0') return env;
  return GRASPCD_MODELS_BUILD_DIR;
}

}  // namespace graspcd
