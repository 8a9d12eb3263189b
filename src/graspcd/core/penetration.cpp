#include "graspcd/core/penetration.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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

namespace {

// The distance from p to the closed box b: the length of what the clamp to its extents leaves in
// its frame. Algorithm: Ericson (2005), 5.1.4 "Closest point on OBB to point".
double point_box_distance(const Vec3& p, const Obb& b) {
  const Vec3 local = b.axes.transpose() * (p - b.center);
  return (local.cwiseAbs() - b.half).cwiseMax(0.0).norm();
}

}  // namespace

// Why the bound is safe: a box holds its triangles, so a triangle is no nearer than its boxes (the
// comparison leaves a margin for the box's rounding): the triangles the bound keeps are those the
// linear scan would find nearest.
double nearest_surface_distance(const ObbTree& tree, const Vec3& p, double enough,
                                std::vector<std::int32_t>& stack) {
  const std::vector<ObbNode>& nodes = tree.nodes();
  const std::vector<Triangle>& triangles = tree.triangles();
  if (nodes.empty()) return std::numeric_limits<double>::infinity();
  const double slack = 1e-9 * (1 + nodes.front().box.half.maxCoeff());
  double nearest = std::numeric_limits<double>::infinity();
  stack.assign(1, 0);
  while (!stack.empty()) {
    const ObbNode& node = nodes[static_cast<std::size_t>(stack.back())];
    const std::int32_t index = stack.back();
    stack.pop_back();
    if (point_box_distance(p, node.box) - slack > nearest) continue;
    if (node.is_leaf()) {
      for (std::int32_t k = 0; k < node.count; ++k) {
        nearest = std::min(nearest, point_triangle_distance(
                                        p, triangles[static_cast<std::size_t>(node.first + k)]));
      }
      if (nearest <= enough) return nearest;
      continue;
    }
    const std::int32_t left = index + 1;
    const std::int32_t right = node.right;
    const double dl = point_box_distance(p, nodes[static_cast<std::size_t>(left)].box);
    const double dr = point_box_distance(p, nodes[static_cast<std::size_t>(right)].box);
    // The nearer child on top of the stack.
    if (dl <= dr) {
      stack.push_back(right);
      stack.push_back(left);
    } else {
      stack.push_back(left);
      stack.push_back(right);
    }
  }
  return nearest;
}

VertexPenetration deepest_point_inside(const ObbTree& solid, const std::vector<Vec3>& points,
                                       double stop_above) {
  VertexPenetration out;
  if (solid.nodes().empty()) return out;
  std::vector<std::int32_t> stack;
  const Obb& root = solid.root().box;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    // Outside the root box (which contains every triangle): outside the solid.
    const Vec3 local = root.axes.transpose() * (p - root.center);
    if ((local.cwiseAbs() - root.half).maxCoeff() > 0) continue;
    if (point_side(solid, p) == PointSide::kOutside) continue;
    ++out.inside;
    // The distance to the surface, abandoned once it cannot exceed the deepest so far.
    const double nearest = nearest_surface_distance(solid, p, out.depth, stack);
    if (nearest > out.depth || out.point == std::numeric_limits<std::size_t>::max()) {
      out.depth = std::max(out.depth, nearest);
      out.point = i;
    }
    if (out.depth > stop_above) break;
  }
  return out;
}

}  // namespace graspcd
