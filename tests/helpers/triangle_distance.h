// The distance between two triangles, computed independently of the code under test (long double,
// Ericson's closest points), for tests of lower bounds on it (tritri.h's gap, a front's leaf gaps).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>

#include "graspcd/core/geometry.h"
#include "graspcd/core/penetration.h"

namespace graspcd::testing {

// The distance between closed segments [p1, q1] and [p2, q2] (Ericson, Real-Time Collision
// Detection, 5.1.9), in long double.
inline long double segment_distance(const Vec3& p1d, const Vec3& q1d, const Vec3& p2d,
                                    const Vec3& q2d) {
  using V = Eigen::Matrix<long double, 3, 1>;
  const V p1 = p1d.cast<long double>(), p2 = p2d.cast<long double>();
  const V d1 = q1d.cast<long double>() - p1, d2 = q2d.cast<long double>() - p2, r = p1 - p2;
  const long double a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
  long double s = 0, t = 0;
  if (a <= 0 && e <= 0) return r.norm();
  if (a <= 0) {
    t = std::clamp(f / e, 0.0L, 1.0L);
  } else {
    const long double c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0L, 1.0L);
    } else {
      const long double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0L, 1.0L) : 0.0L;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0L, 1.0L);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0L, 1.0L);
      }
    }
  }
  return (p1 + d1 * s - (p2 + d2 * t)).norm();
}

// The distance between two triangles that do not intersect: the least of the six vertex-triangle
// and nine edge-edge distances.
inline long double triangle_distance(const Triangle& t, const Triangle& u) {
  long double best = std::numeric_limits<long double>::infinity();
  for (const Vec3& v : t.v) best = std::min<long double>(best, point_triangle_distance(v, u));
  for (const Vec3& v : u.v) best = std::min<long double>(best, point_triangle_distance(v, t));
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      best = std::min(best, segment_distance(t.v[i], t.v[(i + 1) % 3], u.v[j], u.v[(j + 1) % 3]));
    }
  }
  return best;
}

}  // namespace graspcd::testing
