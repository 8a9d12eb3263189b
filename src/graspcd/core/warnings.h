// The one warning sink of a graspcd process. Every layer that notices something a user should
// know without failing the run (a mesh with degenerate faces, a served geom outside the config's
// reach, a pair whose contacts were cut to the solver's budget) adds it here; the command line
// prints each warning once on stderr at the end of the run ("warning: MESSAGE", with " (N times)"
// when it recurred) and every JSON document carries the list in its envelope's "warnings" array
// (graspcd/version/envelope.h; docs/design.md, "The command line").
//
// A warning is a stable code (snake_case, for scripts), a one-line message (for people) and the
// source that raised it: "mujoco" (MuJoCo's own warnings), "mesh" (a mesh file's hygiene), "config"
// (the pair config and the registry's findings), "scene" (the scene and its start state).
// The same code and message added again only raise the count, so a warning met at every physics
// step is one line, not thousands. Thread-safe: the study replays grasps on several threads.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace graspcd {

struct Warning {
  std::string code;     // e.g. "mesh_degenerate_faces"; stable across releases
  std::string message;  // one line, naming the file (and line) or the pair it concerns
  std::int64_t count = 1;
  std::string source;  // "mujoco", "mesh", "config", "scene" (see above)
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
  // Changes every warning in place (e.g. a temporary file's name replaced by the user's).
  void edit(const std::function<void(Warning&)>& change);

 private:
  mutable std::mutex mutex_;
  std::vector<Warning> warnings_;
};

// The process's sink. Libraries add to it; the command line reads it once at the end.
WarningSink& warnings();

// A warning as one line: "MESSAGE" or "MESSAGE (N times)".
std::string warning_line(const Warning& w);

}  // namespace graspcd
