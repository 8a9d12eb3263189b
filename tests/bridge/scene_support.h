// Scenes for the bridge tests: closed, outward-oriented meshes generated here, written as OBJ
// files beside an MJCF string in a fresh temporary folder, and loaded with mj_loadXML.
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

#include "bridge/mujoco_ptr.h"
#include "core/geometry.h"
#include "support/meshes.h"

namespace graspcd::testing {

// A prism: the polygon `profile` (counter-clockwise in the xy-plane), triangulated by `caps`
// (counter-clockwise index triples), extruded over z in [-half_depth, half_depth]. Outward normals.
inline TriangleMesh make_prism(const std::vector<std::pair<double, double>>& profile,
                               const std::vector<std::array<int, 3>>& caps, double half_depth) {
  TriangleMesh m;
  const int n = static_cast<int>(profile.size());
  for (double z : {-half_depth, half_depth}) {
    for (const auto& [x, y] : profile) m.vertices.emplace_back(x, y, z);
  }
  for (const auto& c : caps) {
    m.faces.push_back({n + c[0], n + c[1], n + c[2]});  // top, seen from +z
    m.faces.push_back({c[0], c[2], c[1]});              // bottom, seen from -z
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.faces.push_back({i, j, n + j});
    m.faces.push_back({i, n + j, n + i});
  }
  return m;
}

inline TriangleMesh make_box_mesh(double hx, double hy, double hz) {
  return make_prism({{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}}, {{0, 1, 2}, {0, 2, 3}}, hz);
}

// A U-shape opening toward +y: outer half-width w, height h (y from 0), wall thickness t,
// extruded over z in [-half_depth, half_depth]. Cavity: |x| < w - t, y > t.
inline TriangleMesh make_u_mesh(double w, double h, double t, double half_depth) {
  return make_prism(
      {{-w, 0}, {w, 0}, {w, h}, {w - t, h}, {w - t, t}, {-w + t, t}, {-w + t, h}, {-w, h}},
      {{0, 1, 4}, {0, 4, 5}, {1, 2, 3}, {1, 3, 4}, {0, 5, 6}, {0, 6, 7}}, half_depth);
}

// Six times the signed volume (divergence theorem): positive for a closed outward mesh.
inline double signed_volume6(const TriangleMesh& m) {
  double v = 0;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const Triangle t = m.triangle(f);
    v += t.v[0].dot(t.v[1].cross(t.v[2]));
  }
  return v;
}

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

using bridge::DataPtr;
using bridge::ModelPtr;

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
