#include "graspcd/core/proximity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "graspcd/core/penetration.h"
#include "graspcd/core/sat.h"
#include "graspcd/core/tritri.h"

namespace graspcd {

namespace {

// The closest point of triangle t to p (Ericson, 5.1.5), for the point of a vertex-triangle
// distance; the distance itself is point_triangle_distance's.
Vec3 closest_on_triangle(const Vec3& p, const Triangle& t) {
  const Vec3 &a = t.v[0], &b = t.v[1], &c = t.v[2];
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double sum = va + vb + vc;
  if (sum > 0) return a + ab * (vb / sum) + ac * (vc / sum);
  // A zero-area triangle: the nearest of its edges.
  Vec3 best = a;
  double best_d = (p - a).norm();
  for (std::size_t i = 0; i < 3; ++i) {
    const SegmentDistance s = segment_distance(p, p, t.v[i], t.v[(i + 1) % 3]);
    if (s.distance < best_d) {
      best_d = s.distance;
      best = s.on_second;
    }
  }
  return best;
}

// Where the edges of `e` cross triangle `t` (its plane, inside its edges by barycentric
// coordinates in floating point): summed into `sum`, counted in `n`.
void add_crossings(const Triangle& e, const Triangle& t, Vec3& sum, int& n) {
  const Vec3 normal = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
  const double area2 = normal.squaredNorm();
  if (area2 <= 0) return;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec3& p = e.v[i];
    const Vec3& q = e.v[(i + 1) % 3];
    const double sp = normal.dot(p - t.v[0]);
    const double sq = normal.dot(q - t.v[0]);
    if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || sp == sq) continue;
    const Vec3 x = p + (q - p) * (sp / (sp - sq));
    const double u = normal.dot((t.v[1] - x).cross(t.v[2] - x)) / area2;
    const double v = normal.dot((t.v[2] - x).cross(t.v[0] - x)) / area2;
    if (u < 0 || v < 0 || u + v > 1) continue;
    sum += x;
    ++n;
  }
}

// One node pair of the descent: node indices into a's and b's trees.
struct NodePair {
  std::int32_t a = 0, b = 0;
};

// The depth-first descent shared by tree_distance and triangles_within: `radius()` is how far
// apart a node pair may be and still matter; `leaf(i, j, ta, tb)` sees each triangle pair of two
// leaves whose boxes pass, tb placed in a's frame, and returns false to stop.
template <class Radius, class Leaf>
void descend(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, Radius radius, Leaf leaf) {
  const std::vector<ObbNode>& na = a.nodes();
  const std::vector<ObbNode>& nb = b.nodes();
  if (na.empty() || nb.empty()) return;
  std::vector<NodePair> stack{{0, 0}};
  std::vector<Triangle> placed;  // b's triangles of the current leaf, in a's frame
  while (!stack.empty()) {
    const NodePair pair = stack.back();
    stack.pop_back();
    const ObbNode& x = na[static_cast<std::size_t>(pair.a)];
    const ObbNode& y = nb[static_cast<std::size_t>(pair.b)];
    Obb grown = x.box;
    grown.half += Vec3::Constant(radius());
    if (sat_disjoint(grown, transform(b_in_a, y.box))) continue;
    if (x.is_leaf() && y.is_leaf()) {
      placed.clear();
      for (std::int32_t j = 0; j < y.count; ++j) {
        placed.push_back(apply_pose(b_in_a, b.triangles()[static_cast<std::size_t>(y.first + j)]));
      }
      for (std::int32_t i = 0; i < x.count; ++i) {
        for (std::int32_t j = 0; j < y.count; ++j) {
          if (!leaf(x.first + i, y.first + j, a.triangles()[static_cast<std::size_t>(x.first + i)],
                    placed[static_cast<std::size_t>(j)])) {
            return;
          }
        }
      }
      continue;
    }
    // Split the larger box (by its half-extents' sum), or the one that is not a leaf.
    const bool split_a = y.is_leaf() || (!x.is_leaf() && x.box.half.sum() >= y.box.half.sum());
    if (split_a) {
      stack.push_back({x.right, pair.b});
      stack.push_back({pair.a + 1, pair.b});
    } else {
      stack.push_back({pair.a, y.right});
      stack.push_back({pair.a, pair.b + 1});
    }
  }
}

}  // namespace

// Ericson, Real-Time Collision Detection, 5.1.9.
SegmentDistance segment_distance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) {
    // Both points.
  } else if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  SegmentDistance out;
  out.on_first = p1 + d1 * s;
  out.on_second = p2 + d2 * t;
  out.distance = (out.on_first - out.on_second).norm();
  return out;
}

TriangleDistance triangle_distance(const Triangle& a, const Triangle& b) {
  TriangleDistance out;
  if (tri_tri_intersect(a, b)) {
    Vec3 sum = Vec3::Zero();
    int n = 0;
    add_crossings(a, b, sum, n);
    add_crossings(b, a, sum, n);
    if (n == 0) {
      for (const Vec3& v : a.v) sum += v;
      for (const Vec3& v : b.v) sum += v;
      n = 6;
    }
    out.point = sum / n;
    return out;
  }
  out.distance = std::numeric_limits<double>::infinity();
  const auto consider = [&out](double d, const Vec3& p, const Vec3& q) {
    if (d < out.distance) {
      out.distance = d;
      out.point = 0.5 * (p + q);
    }
  };
  for (const Vec3& v : a.v) {
    const double d = point_triangle_distance(v, b);
    if (d < out.distance) consider(d, v, closest_on_triangle(v, b));
  }
  for (const Vec3& v : b.v) {
    const double d = point_triangle_distance(v, a);
    if (d < out.distance) consider(d, v, closest_on_triangle(v, a));
  }
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      const SegmentDistance s =
          segment_distance(a.v[i], a.v[(i + 1) % 3], b.v[j], b.v[(j + 1) % 3]);
      consider(s.distance, s.on_first, s.on_second);
    }
  }
  return out;
}

double tree_distance(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, double cap,
                     double stop_at) {
  double best = cap;
  descend(
      a, b, b_in_a, [&best] { return best; },
      [&best, stop_at](std::int32_t, std::int32_t, const Triangle& ta, const Triangle& tb) {
        const double d = triangle_distance(ta, tb).distance;
        if (d < best) best = d;
        return !(stop_at >= 0 && best <= stop_at);
      });
  return best;
}

void triangles_within(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, double within,
                      std::vector<NearTriangles>& out) {
  descend(
      a, b, b_in_a, [within] { return within; },
      [&out, within](std::int32_t i, std::int32_t j, const Triangle& ta, const Triangle& tb) {
        const TriangleDistance d = triangle_distance(ta, tb);
        if (d.distance <= within) out.push_back({i, j, d.distance, d.point});
        return true;
      });
}

}  // namespace graspcd
