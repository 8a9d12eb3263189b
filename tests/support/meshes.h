// Generated test meshes (closed, consistently oriented), so that tests do not depend on files.
#pragma once

#include <cmath>

#include "core/geometry.h"

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

}  // namespace graspcd::testing
