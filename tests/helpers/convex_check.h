// A convex piece's check: every vertex on the inner side of every face's plane.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "graspcd/core/geometry.h"

namespace graspcd::testing {

// Every vertex of `hull` on the inner side of every face's plane, within `tol` metres.
inline void expect_convex(const TriangleMesh& hull, double tol, const std::string& name) {
  ASSERT_GE(hull.faces.size(), 4u) << name;
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const Triangle t = hull.triangle(f);
    const Vec3 n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    if (n.norm() == 0) continue;
    for (const Vec3& v : hull.vertices) {
      ASSERT_LE(n.normalized().dot(v - t.v[0]), tol) << name << " face " << f;
    }
  }
}

}  // namespace graspcd::testing
