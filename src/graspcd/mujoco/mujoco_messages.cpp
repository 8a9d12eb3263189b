#include "graspcd/mujoco/mujoco_messages.h"

#include <mujoco/mujoco.h>

#include <string>

#include "graspcd/io/input_error.h"

namespace graspcd::mujoco {
namespace {

thread_local graspcd::WarningSink* t_capture = nullptr;
// The scene this thread simulates (ScopedMujocoErrors), or null.
thread_local const ScopedMujocoErrors* t_scene = nullptr;

// The sink keeps one line of each message (io::one_line).
void on_mujoco_warning(const char* message) {
  const std::string line = "MuJoCo: " + io::one_line(message != nullptr ? message : "");
  warnings().add("mujoco_warning", line);
  if (t_capture != nullptr) t_capture->add("mujoco_warning", line);
}

[[noreturn]] void on_mujoco_error(const char* message) {
  const std::string line = "MuJoCo error: " + io::one_line(message != nullptr ? message : "");
  if (t_scene != nullptr) throw io::InputError(t_scene->file(), 0, line + t_scene->note());
  throw MujocoError(line);
}

}  // namespace

void route_mujoco_warnings() { mju_user_warning = on_mujoco_warning; }

void route_mujoco_errors() { mju_user_error = on_mujoco_error; }

ScopedMujocoWarnings::ScopedMujocoWarnings(graspcd::WarningSink& sink) : previous_(t_capture) {
  t_capture = &sink;
}

ScopedMujocoWarnings::~ScopedMujocoWarnings() { t_capture = previous_; }

ScopedMujocoErrors::ScopedMujocoErrors(const std::string& scene, const SceneNames& names)
    : file_(names.file(scene)),
      note_(scene == names.written_scene ? names.note : ""),
      previous_(t_scene) {
  t_scene = this;
}

ScopedMujocoErrors::~ScopedMujocoErrors() { t_scene = previous_; }

}  // namespace graspcd::mujoco
