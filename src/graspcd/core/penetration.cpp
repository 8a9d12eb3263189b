#include "graspcd/core/penetration.h"

#include <algorithm>
#include <cmath>

#include "graspcd/core/containment.h"

namespace graspcd {

namespace {

// The distance from p to the segment [a, b] (Ericson 5.1.2; a point when a == b).
double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

double point_triangle_distance(const Vec3& p, const Triangle& t) {
  const Vec3& a = t.v[0];
  const Vec3& b = t.v[1];
  const Vec3& c = t.v[2];
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  // A zero-area triangle: the closest of its three edges (the segment or point it spans).
  if (ab.cross(ac).squaredNorm() == 0) {
    return std::min({point_segment_distance(p, a, b), point_segment_distance(p, b, c),
                     point_segment_distance(p, c, a)});
  }
  // Vertex region of a.
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  // Vertex region of b.
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  // Edge region of ab.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  // Vertex region of c.
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  // Edge region of ac.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  // Edge region of bc.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  // Face region: barycentric (u, v, w) = (va, vb, vc) / (va + vb + vc).
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

VertexPenetration deepest_point_inside(const ObbTree& solid, const std::vector<Vec3>& points,
                                       double stop_above) {
  VertexPenetration out;
  if (solid.nodes().empty()) return out;
  const Obb& root = solid.root().box;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    // Outside the root box (which contains every triangle): outside the solid.
    const Vec3 local = root.axes.transpose() * (p - root.center);
    if ((local.cwiseAbs() - root.half).maxCoeff() > 0) continue;
    if (point_side(solid, p) == PointSide::kOutside) continue;
    ++out.inside;
    // The distance to the surface, abandoned once it cannot exceed the deepest so far.
    double nearest = std::numeric_limits<double>::infinity();
    for (const Triangle& t : solid.triangles()) {
      nearest = std::min(nearest, point_triangle_distance(p, t));
      if (nearest <= out.depth) break;
    }
    if (nearest > out.depth || out.point == std::numeric_limits<std::size_t>::max()) {
      out.depth = std::max(out.depth, nearest);
      out.point = i;
    }
    if (out.depth > stop_above) break;
  }
  return out;
}

}  // namespace graspcd
