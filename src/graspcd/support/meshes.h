// Generated test meshes (closed, consistently oriented), so that tests do not depend on files.
#pragma once

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd::testing {

// A UV sphere of `rings` latitude bands and `segments` longitudes: 2 * segments * (rings - 1)
// triangles.
inline TriangleMesh make_uv_sphere(double radius, int rings, int segments,
                                   const Vec3& center = Vec3::Zero()) {
  TriangleMesh m;
  const double pi = std::acos(-1.0);
  m.vertices.push_back(center + Vec3(0, 0, radius));
  for (int r = 1; r < rings; ++r) {
    const double theta = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * pi * s / segments;
      m.vertices.push_back(center + radius * Vec3(std::sin(theta) * std::cos(phi),
                                                  std::sin(theta) * std::sin(phi),
                                                  std::cos(theta)));
    }
  }
  m.vertices.push_back(center + Vec3(0, 0, -radius));
  const auto ring = [segments](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  const int south = static_cast<int>(m.vertices.size()) - 1;
  for (int s = 0; s < segments; ++s) {
    m.faces.push_back({0, ring(1, s), ring(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r) {
      m.faces.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      m.faces.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
    m.faces.push_back({ring(rings - 1, s), south, ring(rings - 1, s + 1)});
  }
  return m;
}

// A torus (genus 1, non-convex) around the z axis: 2 * n_major * n_minor triangles.
inline TriangleMesh make_torus(double major, double minor, int n_major, int n_minor) {
  TriangleMesh m;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n_major; ++i) {
    const double u = 2 * pi * i / n_major;
    for (int j = 0; j < n_minor; ++j) {
      const double v = 2 * pi * j / n_minor;
      m.vertices.emplace_back((major + minor * std::cos(v)) * std::cos(u),
                              (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v));
    }
  }
  const auto at = [&](int i, int j) { return (i % n_major) * n_minor + (j % n_minor); };
  for (int i = 0; i < n_major; ++i) {
    for (int j = 0; j < n_minor; ++j) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return m;
}

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

}  // namespace graspcd::testing
