// The process's one warning sink: what a user should know without the run failing (a mesh with
// degenerate faces, a served geom with a margin, MuJoCo's own warnings). Each layer adds to it;
// the command line prints each warning once on stderr at the end ("warning: MESSAGE", with
// " (N times)"), and every JSON document carries the list in its envelope (version/envelope.h).
// The same code and message added again only raise the count. Thread-safe.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace graspcd {

struct Warning {
  std::string code;     // stable snake_case, for scripts, e.g. "mesh_zero_area_faces"
  std::string message;  // one line, naming the file (and line) or the pair it concerns
  std::int64_t count = 1;
  std::string source;  // "mujoco", "mesh", "config" (the pair config, the registry), "scene"
};

class WarningSink {
 public:
  // Records a warning, or raises the count of an equal (code, message) one.
  void add(const std::string& code, const std::string& message, const std::string& source);
  // The same with the source read from the code: "mujoco_*" -> "mujoco", "mesh_*" -> "mesh",
  // "served_*" -> "config", "start_*" -> "scene", anything else "graspcd".
  void add(const std::string& code, const std::string& message);
  // The warnings in the order they were first added.
  std::vector<Warning> list() const;
  bool empty() const;
  void clear();

 private:
  mutable std::mutex mutex_;
  std::vector<Warning> warnings_;
};

// The process's sink.
WarningSink& warnings();

// A warning as one line (io::one_line): "MESSAGE" or "MESSAGE (N times)".
std::string warning_line(const Warning& w);

}  // namespace graspcd
