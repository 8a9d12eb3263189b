// V-HACD 4 (Mamou, Game Engine Gems 3, 2016) through node and the npm package vhacd-js: see
// vhacd.h.
#include "graspcd/decompose/vhacd.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "graspcd/core/clock.h"

extern char** environ;

namespace graspcd::decompose {

namespace {

namespace fs = std::filesystem;

// node on PATH (an executable file named node in one of its folders); empty when there is none.
std::string find_node() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return {};
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    const fs::path candidate = fs::path(folder) / "node";
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate.string();
    }
  }
  return {};
}

std::string script_of(const VhacdOptions& o) {
  return o.script.empty() ? default_vhacd_script() : o.script;
}

// A temporary folder, removed with everything in it when the object goes.
class TempFolder {
 public:
  TempFolder() {
    std::string pattern = (fs::temp_directory_path() / "graspcd_vhacd_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("V-HACD: cannot create a temporary folder in " +
                               fs::temp_directory_path().string());
    }
    path_ = pattern;
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string last_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

// Runs `node script in out` with stdin from /dev/null and stdout, stderr into files of `tmp`;
// kills it after `timeout` s. Throws std::runtime_error when it cannot start, is killed or exits
// other than 0.
void run_node(const std::string& node, const std::string& script, const fs::path& in,
              const fs::path& out, const fs::path& tmp, double timeout) {
  const std::string out_file = (tmp / "stdout.txt").string();
  const std::string err_file = (tmp / "stderr.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  posix_spawn_file_actions_addopen(&actions, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  std::vector<std::string> args = {node, script, in.string(), out.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, node.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error("V-HACD: cannot start " + node);

  const Clock::time_point start = Clock::now();
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0) throw std::runtime_error("V-HACD: lost the node process");
    if (seconds_since(start) > timeout) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      std::ostringstream msg;
      msg << "V-HACD: node ran past the timeout of " << timeout << " s and was stopped";
      throw std::runtime_error(msg.str());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string why = last_line(err_file);
    if (why.empty()) {
      why = WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                              : "killed by signal " + std::to_string(WTERMSIG(status));
    }
    throw std::runtime_error("V-HACD failed: " + why);
  }
}

}  // namespace

std::string default_vhacd_script() {
  if (const char* env = std::getenv("GRASPCD_VHACD_SCRIPT"); env != nullptr && *env != '\0') {
    return env;
  }
  return GRASPCD_VHACD_SCRIPT;
}

std::string vhacd_missing(const VhacdOptions& options) {
  if (find_node().empty()) return "node is not on PATH";
  const fs::path script = script_of(options);
  std::error_code ec;
  if (!fs::is_regular_file(script, ec)) return "no script " + script.string();
  const fs::path package = script.parent_path() / "node_modules" / "vhacd-js" / "lib" / "vhacd.js";
  if (!fs::is_regular_file(package, ec)) {
    return "no vhacd-js in " + (script.parent_path() / "node_modules").string();
  }
  return {};
}

Decomposition vhacd_decompose(const TriangleMesh& mesh, const VhacdOptions& options) {
  if (mesh.faces.empty()) throw std::runtime_error("V-HACD: the mesh has no faces");
  if (options.max_hulls < 1) throw std::runtime_error("V-HACD: at least one piece");
  if (const std::string missing = vhacd_missing(options); !missing.empty()) {
    throw VhacdUnavailable(missing);
  }
  const TempFolder tmp;
  const fs::path in = tmp.path() / "mesh.json";
  const fs::path out = tmp.path() / "hulls.json";
  {
    nlohmann::json positions = nlohmann::json::array();
    for (const Vec3& v : mesh.vertices) {
      positions.insert(positions.end(), {v.x(), v.y(), v.z()});
    }
    nlohmann::json indices = nlohmann::json::array();
    for (const auto& f : mesh.faces) indices.insert(indices.end(), {f[0], f[1], f[2]});
    const nlohmann::json doc = {{"positions", std::move(positions)},
                                {"indices", std::move(indices)},
                                {"options",
                                 {{"maxHulls", options.max_hulls},
                                  {"voxelResolution", options.voxel_resolution},
                                  {"maxVerticesPerHull", options.max_vertices_per_hull},
                                  {"minVolumePercentError", 1},
                                  {"maxRecursionDepth", 10},
                                  {"shrinkWrap", true},
                                  {"fillMode", "flood"}}}};
    std::ofstream file(in, std::ios::binary);
    file << doc.dump();
    if (!file) throw std::runtime_error("V-HACD: cannot write " + in.string());
  }
  run_node(find_node(), script_of(options), in, out, tmp.path(), options.timeout_seconds);

  nlohmann::json result;
  try {
    std::ifstream file(out);
    result = nlohmann::json::parse(file);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("V-HACD: unreadable hulls: ") + e.what());
  }
  Decomposition d;
  try {
    for (const auto& h : result.at("hulls")) {
      const auto coords = h.at("positions").get<std::vector<double>>();
      std::vector<Vec3> points;
      for (std::size_t k = 0; k + 2 < coords.size(); k += 3) {
        points.emplace_back(coords[k], coords[k + 1], coords[k + 2]);
      }
      TriangleMesh hull = convex_hull(points);
      if (hull.faces.empty()) {
        ++d.flat_clusters;
        continue;
      }
      d.pieces.push_back(ConvexPiece{std::move(hull)});
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("V-HACD: unreadable hulls: ") + e.what());
  }
  if (d.pieces.empty()) throw std::runtime_error("V-HACD: no hull has a volume (a flat mesh?)");
  return d;
}

}  // namespace graspcd::decompose
