#include "graspcd/version/machine.h"

#include <sys/utsname.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <thread>

#include "graspcd/version.h"

namespace graspcd {

namespace {

using json = nlohmann::json;

std::string read_first(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) {
      const auto colon = line.find(':');
      if (colon == std::string::npos) continue;
      std::string v = line.substr(colon + 1);
      const auto first = v.find_first_not_of(" \t");
      return first == std::string::npos ? "" : v.substr(first);
    }
  }
  return "unknown";
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(' ') - first + 1);
}

// PRETTY_NAME="Debian GNU/Linux 12 (bookworm)" of os-release(5).
std::string os_pretty_name() {
  std::ifstream in("/etc/os-release");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("PRETTY_NAME=", 0) != 0) continue;
    std::string pretty = line.substr(12);
    pretty.erase(std::remove(pretty.begin(), pretty.end(), '"'), pretty.end());
    return pretty;
  }
  return "unknown";
}

}  // namespace

json machine_info() {
  utsname u{};
  uname(&u);
  return {{"cpu", read_first("/proc/cpuinfo", "model name")},
          {"cores", std::thread::hardware_concurrency()},
          {"memory", read_first("/proc/meminfo", "MemTotal")},
          {"kernel", std::string(u.sysname) + " " + u.release},
          {"os", os_pretty_name()}};
}

json build_info() {
  return {{"graspcd", GRASPCD_VERSION},       {"build_type", GRASPCD_BUILD_TYPE},
          {"compiler", GRASPCD_CXX_COMPILER}, {"flags", trimmed(GRASPCD_BUILD_FLAGS)},
          {"mujoco", GRASPCD_MUJOCO_VERSION}, {"eigen", GRASPCD_EIGEN_VERSION},
          {"cgal", GRASPCD_CGAL_VERSION}};
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace graspcd
