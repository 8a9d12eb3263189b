// Scenes for the MuJoCo layer's tests: closed, outward-oriented meshes generated here, written as
// OBJ files beside an MJCF string in a fresh temporary folder, and loaded with mj_loadXML.
#pragma once

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/mujoco/mujoco_ptr.h"
#include "graspcd/support/meshes.h"

namespace graspcd::testing {

inline void write_obj(const TriangleMesh& m, const std::filesystem::path& path) {
  std::ofstream out(path);
  out.precision(17);
  for (const Vec3& v : m.vertices) out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  for (const auto& f : m.faces)
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
}

// A fresh folder under the system's temporary directory, removed on destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("graspcd_bridge_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

using mujoco::DataPtr;
using mujoco::ModelPtr;

// Writes `meshes` (name -> mesh, as NAME.obj) and `xml` (as scene.xml) into `dir`, loads the
// scene. Fails the test with MuJoCo's message on a load error.
inline ModelPtr load_scene(const TempDir& dir, const std::string& xml,
                           const std::vector<std::pair<std::string, TriangleMesh>>& meshes) {
  for (const auto& [name, mesh] : meshes) write_obj(mesh, dir.path() / (name + ".obj"));
  const std::filesystem::path file = dir.path() / "scene.xml";
  std::ofstream(file) << xml;
  char error[1024] = "";
  ModelPtr m(mj_loadXML(file.c_str(), nullptr, error, sizeof(error)));
  EXPECT_TRUE(m) << "mj_loadXML: " << error;
  return m;
}

// The contacts of d between geoms a and b (either order).
inline std::vector<const mjContact*> contacts_between(const mjData* d, int a, int b) {
  std::vector<const mjContact*> out;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if ((c.geom1 == a && c.geom2 == b) || (c.geom1 == b && c.geom2 == a)) out.push_back(&c);
  }
  return out;
}

}  // namespace graspcd::testing
