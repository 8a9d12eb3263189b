// MuJoCo's warnings into graspcd's one warning sink (graspcd/core/warnings.h).
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
// behind) and names no file. route_mujoco_errors() makes them a MujocoError exception instead,
// thrown out of the MuJoCo call (mj_step, mj_makeData, ...), whose state is then not to be used
// again: the caller reports it naming its scene and gives up that model.
#pragma once

#include <stdexcept>

#include "graspcd/core/warnings.h"

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
  explicit ScopedMujocoWarnings(WarningSink& sink);
  ~ScopedMujocoWarnings();
  ScopedMujocoWarnings(const ScopedMujocoWarnings&) = delete;
  ScopedMujocoWarnings& operator=(const ScopedMujocoWarnings&) = delete;

 private:
  WarningSink* previous_;
};

}  // namespace graspcd::mujoco
