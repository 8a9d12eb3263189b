// Containment (containment.h): closedness by welding and edge counting, the exact ray-parity
// point query on the OBB tree, and the mesh-in-mesh check built from them.
#include "graspcd/core/containment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "graspcd/core/predicates.h"
#include "graspcd/core/tolerances.h"
#include "graspcd/core/tree_query.h"

namespace graspcd {
namespace {

// ---- Welding and edges --------------------------------------------------------------------------

bool lexicographic_less(const Vec3& x, const Vec3& y) {
  if (x[0] != y[0]) return x[0] < y[0];
  if (x[1] != y[1]) return x[1] < y[1];
  return x[2] < y[2];
}

// Welded vertex ids of a triangle soup: ids[3 f + k] for vertex k of face f, equal exactly when
// the coordinates compare equal. Returns the number of distinct vertices.
std::size_t weld(const std::vector<Triangle>& triangles, std::vector<std::int32_t>& ids) {
  const std::size_t n = 3 * triangles.size();
  const auto point = [&](std::size_t i) -> const Vec3& { return triangles[i / 3].v[i % 3]; };
  std::vector<std::int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t x, std::int32_t y) {
    return lexicographic_less(point(static_cast<std::size_t>(x)),
                              point(static_cast<std::size_t>(y)));
  });
  ids.assign(n, 0);
  std::int32_t next = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const auto cur = static_cast<std::size_t>(order[i]);
    if (i == 0 || point(static_cast<std::size_t>(order[i - 1])) != point(cur)) ++next;
    ids[cur] = next;
  }
  return static_cast<std::size_t>(next + 1);
}

// Union-find with path halving.
std::int32_t find_root(std::vector<std::int32_t>& parent, std::int32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// ---- Exact point and segment tests --------------------------------------------------------------

// p on the closed segment [a, b] (a == b allowed: then p == a). Exact: collinearity from the
// three components of (b - a) x (p - a), betweenness by coordinate comparisons.
bool on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  for (int k = 0; k < 3; ++k) {
    if (p[k] < std::min(a[k], b[k]) || p[k] > std::max(a[k], b[k])) return false;
  }
  for (int k = 0; k < 3; ++k) {
    if (predicates::orient2d(a, b, p, k) != 0) return false;
  }
  return true;
}

// p in the closed triangle abc, given that p lies in its plane (orient3d(a, b, c, p) == 0).
// A non-degenerate triangle is tested in a projection where it keeps a non-zero area; a triangle
// spanning a segment or a point is the union of its three edges.
bool on_triangle_in_plane(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  for (int k = 0; k < 3; ++k) {
    const int area = predicates::orient2d(a, b, c, k);
    if (area == 0) continue;
    return predicates::orient2d(a, b, p, k) != -area && predicates::orient2d(b, c, p, k) != -area &&
           predicates::orient2d(c, a, p, k) != -area;
  }
  return on_segment(p, a, b) || on_segment(p, b, c) || on_segment(p, c, a);
}

// The sign of component k of (b - a) x (q - a) for q = p + eps e_u + eps^2 e_v, (u, v) = (k + 1,
// k + 2) mod 3, eps > 0 infinitesimal (Simulation of Simplicity). The component is
//   orient2d(a, b, p, k) - (b_v - a_v) eps + (b_u - a_u) eps^2,
// so its sign is that of the first non-zero term; 0 only when a and b project to the same point.
// Antisymmetric in (a, b), like the exact predicate.
int perturbed_orient2d(const Vec3& a, const Vec3& b, const Vec3& p, int k) {
  const int s = predicates::orient2d(a, b, p, k);
  if (s != 0) return s;
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  if (b[v] != a[v]) return b[v] < a[v] ? 1 : -1;
  if (b[u] != a[u]) return b[u] > a[u] ? 1 : -1;
  return 0;
}

// The ray p + t * sign * e_axis against one closed triangle. Returns kOnSurface when p lies on
// the triangle, kInside when the perturbed ray crosses it at t > 0 (one crossing), else kOutside.
PointSide ray_triangle(const Triangle& t, const Vec3& p, int axis, int sign) {
  const Vec3& a = t.v[0];
  const Vec3& b = t.v[1];
  const Vec3& c = t.v[2];
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  // Exact bounding-box filter: the perturbed ray's line meets the triangle's projection only if
  // p's projection lies in the closed box of the projected vertices; a triangle containing p
  // passes too.
  const auto lo = [&](int i) { return std::min(a[i], std::min(b[i], c[i])); };
  const auto hi = [&](int i) { return std::max(a[i], std::max(b[i], c[i])); };
  if (p[u] < lo(u) || p[u] > hi(u) || p[v] < lo(v) || p[v] > hi(v)) return PointSide::kOutside;
  if (sign > 0 ? hi(axis) < p[axis] : lo(axis) > p[axis]) return PointSide::kOutside;

  const int side = predicates::orient3d(a, b, c, p);
  // The perturbed line crosses the open projected triangle iff the three edge signs agree; their
  // sum is the projected area's sign (the perturbation terms cancel around the cycle), so then
  // sigma = sign of the normal's component `axis`, which is non-zero.
  const int s1 = perturbed_orient2d(a, b, p, axis);
  const int s2 = perturbed_orient2d(b, c, p, axis);
  const int s3 = perturbed_orient2d(c, a, p, axis);
  const bool crosses_line = s1 != 0 && s1 == s2 && s2 == s3;
  if (side == 0) {
    // p in the plane. If the perturbed line crossed the triangle, p's projection lies in the
    // closed projected triangle, which the plane maps one-to-one onto the triangle: p is on it.
    if (crosses_line || on_triangle_in_plane(p, a, b, c)) return PointSide::kOnSurface;
    return PointSide::kOutside;
  }
  if (!crosses_line) return PointSide::kOutside;
  // With n = (b - a) x (c - a), the ray meets the plane at t = -n.(p - a) / (sign n_axis): ahead
  // of p iff orient3d and sign * sigma have opposite signs.
  return side * sign * s1 < 0 ? PointSide::kInside : PointSide::kOutside;
}

// The half-line p + t d, d = sign * e_axis, t >= 0, against the closed box c + sum e_i u_i a_i,
// |u_i| <= 1 (the axes as given, orthonormal or not). True when some axis provably separates them
// beyond `slack`: L = a_i (the ray's projection is a half-line starting at p.L) and L = d x a_i
// (the ray projects to the point p.L). The box projects to c.L +- sum_j e_j |a_j.L|.
bool ray_misses_box(const Obb& box, const Vec3& p, int axis, int sign, double slack) {
  const Vec3 w = p - box.center;
  const Mat3& A = box.axes;
  const Vec3& e = box.half;
  const auto radius = [&](const Vec3& L) {
    return e[0] * std::fabs(A.col(0).dot(L)) + e[1] * std::fabs(A.col(1).dot(L)) +
           e[2] * std::fabs(A.col(2).dot(L));
  };
  for (int i = 0; i < 3; ++i) {
    const Vec3 L = A.col(i);
    const double along = static_cast<double>(sign) * L[axis];  // exact
    const double offset = w.dot(L);
    const double r = radius(L) + slack;
    if (along >= 0 && offset > r) return true;
    if (along <= 0 && offset < -r) return true;
  }
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  for (int i = 0; i < 3; ++i) {
    // e_axis x a_i (exact: components moved and negated); the sign of d does not matter here.
    Vec3 L = Vec3::Zero();
    L[u] = -A(v, i);
    L[v] = A(u, i);
    if (std::fabs(w.dot(L)) > radius(L) + slack) return true;
  }
  return false;
}

bool is_identity(const Pose& pose) { return pose.R == Mat3::Identity() && pose.t == Vec3::Zero(); }

RayDirection choose_ray(const Obb& root, const Vec3& p, const RayDirection& ray) {
  if (ray.axis >= 0) {
    if (ray.axis > 2 || (ray.sign != 1 && ray.sign != -1)) {
      throw std::invalid_argument("point_side: ray axis must be 0-2 (or -1) and sign +-1");
    }
    return ray;
  }
  const Vec3 d = p - root.center;
  const int axis = argmax_abs(d);
  return RayDirection{axis, d[axis] < 0 ? -1 : 1};
}

}  // namespace

// ---- Closedness ---------------------------------------------------------------------------------

std::string Closedness::describe() const {
  const auto plural = [](std::size_t n, const char* what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
  };
  if (closed()) {
    return "closed (" + plural(faces, "face") + ", " +
           (vertices == 1 ? "1 vertex" : std::to_string(vertices) + " vertices") + ", " +
           plural(edges, "edge") + ", " + plural(component_faces.size(), "component") +
           (collapsed_faces > 0 ? ", " + std::to_string(collapsed_faces) + " collapsed faces"
                                : "") +
           ")";
  }
  std::string why;
  const auto add = [&](std::size_t n, const char* what) {
    if (n == 0) return;
    why += (why.empty() ? "" : ", ") + plural(n, what);
  };
  if (faces == collapsed_faces) why = faces == 0 ? "no faces" : "no face with three vertices";
  add(boundary_edges, "boundary edge");
  add(non_manifold_edges, "non-manifold edge");
  add(misoriented_edges, "misoriented edge");
  return "not closed: " + why + " (" + plural(faces, "face") +
         (collapsed_faces > 0 ? ", " + std::to_string(collapsed_faces) + " collapsed" : "") + ")";
}

// Welding by sorting the 3n vertices lexicographically (equal coordinates become one vertex),
// then the directed edges of the non-collapsed faces sorted by undirected edge: each group's size
// and directions classify it. Components by union-find over the welded vertices of every face.
Closedness closedness(const std::vector<Triangle>& triangles) {
  Closedness c;
  c.faces = triangles.size();
  if (triangles.empty()) return c;
  std::vector<std::int32_t> ids;
  c.vertices = weld(triangles, ids);

  struct Edge {
    std::int32_t lo, hi;
    bool forward;  // traversed lo -> hi
  };
  std::vector<Edge> edges;
  edges.reserve(ids.size());
  std::vector<std::int32_t> parent(c.vertices);
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const std::array<std::int32_t, 3> w{ids[3 * f], ids[3 * f + 1], ids[3 * f + 2]};
    for (int k = 1; k < 3; ++k) parent[find_root(parent, w[k])] = find_root(parent, w[0]);
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) {
      ++c.collapsed_faces;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const std::int32_t from = w[k], to = w[(k + 1) % 3];
      edges.push_back({std::min(from, to), std::max(from, to), from < to});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& x, const Edge& y) { return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi; });
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i, forward = 0;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) {
      forward += edges[j].forward;
      ++j;
    }
    ++c.edges;
    const std::size_t uses = j - i;
    if (uses == 1) {
      ++c.boundary_edges;
    } else if (uses > 2) {
      ++c.non_manifold_edges;
    } else if (forward != 1) {
      ++c.misoriented_edges;
    }
    i = j;
  }

  // The first face of each component, in face order.
  std::vector<bool> seen(c.vertices, false);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const std::int32_t root = find_root(parent, ids[3 * f]);
    if (seen[root]) continue;
    seen[root] = true;
    c.component_faces.push_back(static_cast<std::int32_t>(f));
  }
  return c;
}

Closedness closedness(const TriangleMesh& mesh) {
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) triangles.push_back(mesh.triangle(f));
  return closedness(triangles);
}

Closedness closedness(const ObbTree& tree) { return closedness(tree.triangles()); }

// ---- Point queries ------------------------------------------------------------------------------

const char* point_side_name(PointSide side) {
  switch (side) {
    case PointSide::kOutside:
      return "outside";
    case PointSide::kOnSurface:
      return "on surface";
    case PointSide::kInside:
      return "inside";
  }
  return "?";
}

PointQueryStats& PointQueryStats::operator+=(const PointQueryStats& o) {
  queries += o.queries;
  nodes_visited += o.nodes_visited;
  triangle_tests += o.triangle_tests;
  return *this;
}

// Crossing-number parity along an axis-parallel ray with exact predicates and Simulation of
// Simplicity (Edelsbrunner and Mucke 1990; see containment.h), the tree descended only where the
// ray may hit a box.
//
// Why culling is safe: a node's box contains its triangles (obb.h: the fit pads every extent), so a
// ray that misses the box misses them, and the perturbed ray is infinitesimally close to it. The
// floating-point separation test has a rounding error of a few units of roundoff times
// (|p - c|_1 + sum of half-extents) for axes of norm about 1 (|a_i| <= 1 + 1e-9 by
// kOrthonormalTol); a posed box's centre and the placed vertices differ from their exact images by
// a few ulps of
// (|c|_1 + |t|_1 + extents). The slack below, SAT's (tolerances.h) with the ray origin as a point
// box and |t| added, exceeds both by a factor of about 1e6.
PointSide point_side(const ObbTree& tree, const Pose& tree_pose, const Vec3& p,
                     const RayDirection& ray, PointQueryStats* stats) {
  PointQueryStats local;
  ++local.queries;
  PointSide answer = PointSide::kOutside;
  if (!tree.nodes().empty()) {
    const bool posed = !is_identity(tree_pose);
    const auto placed_box = [&](const ObbNode& node) {
      return posed ? transform(tree_pose, node.box) : node.box;
    };
    const RayDirection dir = choose_ray(placed_box(tree.root()), p, ray);
    const double t_magnitude = posed ? tree_pose.t.lpNorm<1>() : 0.0;
    const double p_magnitude = p.lpNorm<1>();

    bool odd = false;
    std::vector<std::int32_t> stack;
    stack.reserve(64);
    stack.push_back(0);
    while (!stack.empty() && answer != PointSide::kOnSurface) {
      const std::int32_t index = stack.back();
      stack.pop_back();
      const ObbNode& node = tree.nodes()[index];
      const Obb box = placed_box(node);
      ++local.nodes_visited;
      const double slack =
          tol::kSatRelativeSlack * (box.half.sum() + (p - box.center).lpNorm<1>()) +
          tol::kSatRoundoffFactor * (box.center.lpNorm<1>() + p_magnitude + t_magnitude);
      if (ray_misses_box(box, p, dir.axis, dir.sign, slack)) continue;
      if (!node.is_leaf()) {
        stack.push_back(node.right);
        stack.push_back(index + 1);
        continue;
      }
      for (std::int32_t i = node.first; i < node.first + node.count; ++i) {
        const Triangle& stored = tree.triangles()[i];
        const Triangle t = posed ? apply_pose(tree_pose, stored) : stored;
        ++local.triangle_tests;
        const PointSide hit = ray_triangle(t, p, dir.axis, dir.sign);
        if (hit == PointSide::kOnSurface) {
          answer = PointSide::kOnSurface;
          break;
        }
        odd ^= hit == PointSide::kInside;
      }
    }
    if (answer != PointSide::kOnSurface) answer = odd ? PointSide::kInside : PointSide::kOutside;
  }
  if (stats) *stats += local;
  return answer;
}

PointSide point_side(const ObbTree& tree, const Vec3& p, PointQueryStats* stats) {
  return point_side(tree, Pose{}, p, RayDirection{}, stats);
}

// The same parity over every face: automatic direction +x.
PointSide point_side(const std::vector<Triangle>& triangles, const Vec3& p,
                     const RayDirection& ray) {
  const RayDirection dir = ray.axis < 0 ? RayDirection{0, 1} : ray;
  if (dir.axis > 2 || (dir.sign != 1 && dir.sign != -1)) {
    throw std::invalid_argument("point_side: ray axis must be 0-2 (or -1) and sign +-1");
  }
  bool odd = false;
  for (const Triangle& t : triangles) {
    const PointSide hit = ray_triangle(t, p, dir.axis, dir.sign);
    if (hit == PointSide::kOnSurface) return hit;
    odd ^= hit == PointSide::kInside;
  }
  return odd ? PointSide::kInside : PointSide::kOutside;
}

bool point_inside(const ObbTree& tree, const Vec3& p) {
  return point_side(tree, p) != PointSide::kOutside;
}

bool point_inside(const ObbTree& tree, const Pose& tree_pose, const Vec3& p) {
  return point_side(tree, tree_pose, p) != PointSide::kOutside;
}

bool point_inside(const std::vector<Triangle>& triangles, const Vec3& p) {
  return point_side(triangles, p) != PointSide::kOutside;
}

// ---- Mesh in mesh -------------------------------------------------------------------------------

namespace {

void check_matches(const ObbTree& tree, const Closedness& c, const char* which) {
  bool ok = c.faces == tree.triangles().size();
  for (std::int32_t f : c.component_faces) {
    ok = ok && f >= 0 && static_cast<std::size_t>(f) < tree.triangles().size();
  }
  if (!ok) {
    throw std::invalid_argument(std::string("mesh_inside: ") + which +
                                "'s closedness was not computed from its tree (closedness(tree))");
  }
}

// Every component of `inner` (its vertices placed by inner_pose) inside `outer` (placed by
// outer_pose); the caller has checked closedness and the surface query.
bool components_inside(const ObbTree& outer, const Pose& outer_pose, const ObbTree& inner,
                       const Closedness& inner_closedness, const Pose& inner_pose) {
  if (inner_closedness.component_faces.empty()) return false;
  for (std::int32_t f : inner_closedness.component_faces) {
    const Vec3 vertex = apply_pose(inner_pose, inner.triangles()[f].v[0]);
    if (point_side(outer, outer_pose, vertex) == PointSide::kOutside) return false;
  }
  return true;
}

bool surfaces_meet(const ObbTree& a, const Pose& b_in_a, const ObbTree& b) {
  SatSeparator sat;
  QueryCounters counters;
  return collide(a, b, b_in_a, QueryMode::kFirstContact, sat, counters).intersect;
}

}  // namespace

bool mesh_inside(const ObbTree& a, const Closedness& a_closedness, const Pose& b_in_a,
                 const ObbTree& b, const Closedness& b_closedness, bool surfaces_intersect) {
  check_matches(a, a_closedness, "A");
  check_matches(b, b_closedness, "B");
  if (!a_closedness.closed() || surfaces_intersect) return false;
  return components_inside(a, Pose{}, b, b_closedness, b_in_a);
}

bool mesh_inside(const ObbTree& a, const Closedness& a_closedness, const Pose& b_in_a,
                 const ObbTree& b, const Closedness& b_closedness) {
  check_matches(a, a_closedness, "A");
  check_matches(b, b_closedness, "B");
  if (!a_closedness.closed() || b.nodes().empty() || a.nodes().empty()) return false;
  return mesh_inside(a, a_closedness, b_in_a, b, b_closedness, surfaces_meet(a, b_in_a, b));
}

MeshContainment mesh_containment(const ObbTree& a, const Closedness& a_closedness,
                                 const Pose& b_in_a, const ObbTree& b,
                                 const Closedness& b_closedness, bool surfaces_intersect) {
  check_matches(a, a_closedness, "A");
  check_matches(b, b_closedness, "B");
  MeshContainment r;
  r.surfaces_intersect = surfaces_intersect;
  if (surfaces_intersect) return r;
  r.b_inside_a = a_closedness.closed() && components_inside(a, Pose{}, b, b_closedness, b_in_a);
  r.a_inside_b = b_closedness.closed() && components_inside(b, b_in_a, a, a_closedness, Pose{});
  return r;
}

MeshContainment mesh_containment(const ObbTree& a, const Closedness& a_closedness,
                                 const Pose& b_in_a, const ObbTree& b,
                                 const Closedness& b_closedness) {
  check_matches(a, a_closedness, "A");
  check_matches(b, b_closedness, "B");
  const bool meet = !a.nodes().empty() && !b.nodes().empty() && surfaces_meet(a, b_in_a, b);
  return mesh_containment(a, a_closedness, b_in_a, b, b_closedness, meet);
}

}  // namespace graspcd
