// MuJoCo's warnings into graspcd's one warning sink (graspcd/io/warnings.h).
//
// MuJoCo 2.2 prints a warning (a full contact buffer, a bad number in the state, "XML contains a
// 'NaN'") on stdout and appends it to MUJOCO_LOG.TXT in the working folder, unless the process sets
// the hook mju_user_warning (mujoco.h). Printed on stdout it would corrupt a command's JSON; the
// command line therefore routes them here: each message becomes a warning of code
// "mujoco_warning" in the process's sink, printed on stderr and carried in the JSON envelope.
// mju_warning is raised once per mjData and warning type; the counters d->warning[i].number count
// every occurrence and are what a caller checks after each step.
//
// The hook is one process-wide pointer. A thread that wants the warnings of its own simulation (the
// study replays grasps on several threads) opens a ScopedMujocoWarnings: while it lives, the
// messages raised on that thread also go to its sink. A library user's own hook is replaced only
// when route_mujoco_warnings() is called; NonconvexContacts never calls it.
//
// MuJoCo's errors (mju_error: e.g. its stack or arena is too small for the model) print, append to
// MUJOCO_LOG.TXT and exit(1) by default, which skips every destructor (a temporary folder stays
// behind) and names no file. route_mujoco_errors() makes them an exception instead, thrown out of
// the MuJoCo call (mj_step, mj_makeData, ...), whose state is then not to be used again: an
// io::InputError naming the scene while a ScopedMujocoErrors lives on the thread, else a
// MujocoError.
#pragma once

#include <stdexcept>
#include <string>

#include "graspcd/io/warnings.h"
#include "graspcd/mujoco/scene_names.h"

namespace graspcd::mujoco {

// Sets mju_user_warning to graspcd's handler. Idempotent.
void route_mujoco_warnings();

// MuJoCo's error, one line: "MuJoCo error: MESSAGE".
class MujocoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Sets mju_user_error to a handler that throws MujocoError. Idempotent.
void route_mujoco_errors();

// While alive, MuJoCo warnings raised on this thread are also added to `sink`.
class ScopedMujocoWarnings {
 public:
  explicit ScopedMujocoWarnings(graspcd::WarningSink& sink);
  ~ScopedMujocoWarnings();
  ScopedMujocoWarnings(const ScopedMujocoWarnings&) = delete;
  ScopedMujocoWarnings& operator=(const ScopedMujocoWarnings&) = delete;

 private:
  graspcd::WarningSink* previous_;
};

// While alive, a MuJoCo error raised on this thread (with route_mujoco_errors()) is an
// io::InputError naming the scene being simulated as `names` has it: "SCENE: MuJoCo error:
// MESSAGE", with the names' note for a scene graspcd wrote.
class ScopedMujocoErrors {
 public:
  explicit ScopedMujocoErrors(const std::string& scene, const SceneNames& names = {});
  ~ScopedMujocoErrors();
  ScopedMujocoErrors(const ScopedMujocoErrors&) = delete;
  ScopedMujocoErrors& operator=(const ScopedMujocoErrors&) = delete;

  const std::string& file() const { return file_; }
  const std::string& note() const { return note_; }

 private:
  std::string file_;
  std::string note_;
  const ScopedMujocoErrors* previous_;
};

}  // namespace graspcd::mujoco
