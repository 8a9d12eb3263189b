#include "graspcd/mujoco/scene_names.h"

#include <algorithm>
#include <filesystem>

namespace graspcd::mujoco {

namespace {

// A path as the checks and MuJoCo spell it: "a/./b/../c" and "a/c" are the same file.
std::string normal(const std::string& path) {
  return std::filesystem::path(path).lexically_normal().string();
}

}  // namespace

std::string SceneNames::file(const std::string& path) const {
  if (!written_scene.empty() && normal(path) == normal(written_scene)) return scene;
  for (const auto& [written, known] : files) {
    if (normal(path) == normal(written)) return known;
  }
  return path;
}

std::string SceneNames::named(const std::string& message) const {
  std::vector<std::pair<std::string, std::string>> renames = files;
  if (!written_scene.empty()) renames.emplace_back(written_scene, scene);
  // The longest first, so that no written path is replaced inside a longer one.
  std::sort(renames.begin(), renames.end(),
            [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
  std::string out = message;
  for (const auto& [written, known] : renames) {
    if (written.empty()) continue;
    for (std::size_t at = out.find(written); at != std::string::npos;
         at = out.find(written, at + known.size())) {
      out.replace(at, written.size(), known);
    }
  }
  return out;
}

io::InputError SceneNames::refusal(const std::string& path, std::size_t line,
                                   const std::string& message) const {
  if (!written_scene.empty() && normal(path) == normal(written_scene)) {
    return io::InputError(scene, 0, scene_context + named(message) + note);
  }
  return io::InputError(file(path), line, named(message));
}

std::string SceneNames::mesh_owner(const std::string& mesh_name) const {
  return mesh_name.empty() || mesh_name == object_mesh ? "" : hand;
}

}  // namespace graspcd::mujoco
