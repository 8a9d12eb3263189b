// V-HACD 4 (Mamou, Game Engine Gems 3, 2016) through node and the npm package vhacd-js: see
// vhacd.h.
#include "graspcd/decompose/vhacd.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "graspcd/core/clock.h"
#include "graspcd/io/output_files.h"

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

// The lines of `file`, blank ones left out.
std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) out.push_back(line);
  }
  return out;
}

// What went wrong, from node's stderr: the line vhacd.mjs wrote ("vhacd.mjs: ..."), else the
// error line of an exception node reports itself ("SyntaxError: ...", "Error [ERR_...]: ..."),
// never its version banner ("Node.js v20...") or a stack frame; empty when there is none.
std::string node_error(const std::vector<std::string>& lines) {
  static const std::regex script_line(R"(^vhacd\.mjs: (.*)$)");
  static const std::regex error_line(R"(^([A-Za-z]*Error|Error)( \[[A-Z0-9_]+\])?: .*$)");
  static const std::regex noise(R"(^(Node\.js v[0-9].*|\s+at .*|\s*\^+\s*|\s*\}\s*)$)");
  std::smatch m;
  for (const std::string& line : lines) {
    if (std::regex_match(line, m, script_line)) return m[1].str();
  }
  for (const std::string& line : lines) {
    if (std::regex_match(line, error_line))
      return "node could not run the V-HACD script (" + line + ")";
  }
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
    if (!std::regex_match(*it, noise)) return *it;
  }
  return {};
}

// nlohmann's message without its "[json.exception.parse_error.101] " tag.
std::string json_reason(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const std::size_t end = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2)
                                                                            : what;
}

// Runs `node script in out` with stdin from /dev/null and stdout, stderr into files of `tmp`, as a
// child tied to the run (io::ChildProcess: killed with graspcd on INT, TERM and HUP, and by the
// kernel when graspcd dies); kills it after `timeout` s. Throws std::runtime_error when it cannot
// start, is killed or exits other than 0.
void run_node(const std::string& node, const std::string& script, const fs::path& in,
              const fs::path& out, const fs::path& tmp, double timeout) {
  const std::string out_file = (tmp / "stdout.txt").string();
  const std::string err_file = (tmp / "stderr.txt").string();
  std::vector<std::string> args = {node, script, in.string(), out.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  io::ChildProcess child;
  if (child.pid() == 0) {
    // The child: only async-signal-safe calls until execve.
    const int null = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    const int o = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    const int e = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (null < 0 || o < 0 || e < 0 || ::dup2(null, 0) < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0) {
      ::_exit(126);
    }
    ::execve(node.c_str(), argv.data(), environ);
    ::_exit(127);
  }
  if (child.pid() < 0) throw std::runtime_error("V-HACD: cannot start " + node);

  const Clock::time_point start = Clock::now();
  int status = 0;
  while (!child.wait(&status, false)) {
    if (seconds_since(start) > timeout) {
      child.kill();
      child.wait(&status, true);
      std::ostringstream msg;
      msg << "V-HACD: node ran past the timeout of " << timeout << " s and was stopped";
      throw std::runtime_error(msg.str());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string why = node_error(lines_of(err_file));
    if (why.empty() && WIFEXITED(status) && WEXITSTATUS(status) == 127) {
      why = "node could not be started (" + node + ")";
    }
    if (why.empty()) {
      why = WIFEXITED(status) ? "node ended with exit code " + std::to_string(WEXITSTATUS(status))
                              : "node was killed by signal " + std::to_string(WTERMSIG(status));
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
  // The mesh and the hulls cross through a folder of the run (removed on INT, TERM and HUP too).
  const fs::path temporary = io::temporary_folder();
  const io::CleanupGuard tmp =
      io::make_private_folder(temporary, "graspcd-vhacd", temporary.string());
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

  const std::string unreadable = "V-HACD: node's answer is not hulls graspcd can read (";
  nlohmann::json result;
  try {
    std::ifstream file(out);
    result = nlohmann::json::parse(file);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(unreadable + "not JSON: " + json_reason(e) + ")");
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
    throw std::runtime_error(unreadable + json_reason(e) + ")");
  }
  if (d.pieces.empty()) throw std::runtime_error("V-HACD: no hull has a volume (a flat mesh?)");
  return d;
}

}  // namespace graspcd::decompose
