#include "graspcd/mujoco/scene_names.h"

namespace graspcd::mujoco {

std::string SceneNames::file(const std::string& path) const {
  if (!written_scene.empty() && path == written_scene) return scene;
  for (const auto& [written, known] : files) {
    if (path == written) return known;
  }
  return path;
}

io::InputError SceneNames::refusal(const std::string& path, std::size_t line,
                                   const std::string& message) const {
  if (!written_scene.empty() && path == written_scene) {
    return io::InputError(scene, 0, scene_context + message + note);
  }
  return io::InputError(file(path), line, message);
}

std::string SceneNames::mesh_owner(const std::string& mesh_name) const {
  return mesh_name.empty() || mesh_name == object_mesh ? "" : hand;
}

}  // namespace graspcd::mujoco
