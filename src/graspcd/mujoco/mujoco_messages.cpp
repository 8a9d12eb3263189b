#include "graspcd/mujoco/mujoco_messages.h"

#include <mujoco/mujoco.h>

#include <string>

namespace graspcd::mujoco {
namespace {

thread_local WarningSink* t_capture = nullptr;

// MuJoCo's messages end with no newline but may hold several lines (e.g. "Pre-allocated contact
// buffer is full. Increase nconmax above 1. Time = 0.0020."); the sink keeps one line.
void on_mujoco_warning(const char* message) {
  std::string line = message != nullptr ? message : "";
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  line = "MuJoCo: " + line;
  warnings().add("mujoco_warning", line);
  if (t_capture != nullptr) t_capture->add("mujoco_warning", line);
}

[[noreturn]] void on_mujoco_error(const char* message) {
  std::string line = message != nullptr ? message : "";
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  throw MujocoError("MuJoCo error: " + line);
}

}  // namespace

void route_mujoco_warnings() { mju_user_warning = on_mujoco_warning; }

void route_mujoco_errors() { mju_user_error = on_mujoco_error; }

ScopedMujocoWarnings::ScopedMujocoWarnings(WarningSink& sink) : previous_(t_capture) {
  t_capture = &sink;
}

ScopedMujocoWarnings::~ScopedMujocoWarnings() { t_capture = previous_; }

}  // namespace graspcd::mujoco
