// Real meshes from ../shared/models (models/README.md), read by path, never copied in. Tests that
// use them skip with a message when the folder is absent.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "graspcd/core/geometry.h"
#include "graspcd/io/mesh_io.h"

namespace graspcd::testing {

// cube_cup_hi (14,876 faces, metres) and the mug (24,544 faces, scaled by 0.01 to metres as the
// models' README says).
struct CupAndMug {
  TriangleMesh cup;
  TriangleMesh mug;
};

// The two meshes, or nullopt with `why_not` saying what is missing.
inline std::optional<CupAndMug> load_cup_and_mug(std::string& why_not) {
  const std::filesystem::path dir = std::filesystem::path(GRASPCD_MODELS_DIR) / "objects/mujoco";
  if (!std::filesystem::exists(dir / "mug.obj") ||
      !std::filesystem::exists(dir / "cube_cup_hi.obj")) {
    why_not = "real models not found at " + dir.string() + " (../shared/models is absent)";
    return std::nullopt;
  }
  CupAndMug meshes{io::load_mesh((dir / "cube_cup_hi.obj").string()),
                   io::load_mesh((dir / "mug.obj").string())};
  for (Vec3& v : meshes.mug.vertices) v *= 0.01;
  return meshes;
}

}  // namespace graspcd::testing
