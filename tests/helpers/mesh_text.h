// A mesh written as the text formats graspcd reads (ASCII STL, OFF, ASCII PLY), for tests that
// need the same mesh in each format. Default stream precision (6 digits).
#pragma once

#include <sstream>
#include <string>

#include "graspcd/core/geometry.h"

namespace graspcd::testing {

inline std::string ascii_stl(const TriangleMesh& m) {
  std::ostringstream out;
  out << "solid box\n";
  for (const auto& f : m.faces) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = m.vertices[f[k]];
      out << "      vertex " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid box\n";
  return out.str();
}

// With a comment line after the header (OFF allows them).
inline std::string off_of(const TriangleMesh& m) {
  std::ostringstream out;
  out << "OFF\n# a box\n" << m.vertices.size() << ' ' << m.faces.size() << " 0\n";
  for (const Vec3& v : m.vertices) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& f : m.faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
  return out.str();
}

inline std::string ascii_ply(const TriangleMesh& m) {
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\nelement vertex " << m.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.faces.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& v : m.vertices) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& f : m.faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
  return out.str();
}

}  // namespace graspcd::testing
