#include "graspcd/core/triangle_contact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "graspcd/core/tolerances.h"

namespace graspcd {
namespace {

// A triangle clipped by three planes: 6 vertices in exact arithmetic, room for rounding.
struct Polygon {
  std::array<Vec3, 24> v;  // each clip at most doubles the count: 3, 6, 12, 24
  int n = 0;
};

// One side of a plane through `o` with normal `m`: keeps m.(p - o) >= 0 (Sutherland-Hodgman),
// from the polygon `in` (n vertices) into `out` (two buffers in turn: no polygon is copied). Each
// vertex's signed distance is computed once, by the same expression for both edges it ends.
// Returns false, leaving `out` untouched, when every vertex is kept: the clipped polygon is `in`
// itself. kFixedN > 0 is n known when compiling (a triangle: the loops unroll), 0 any n.
template <int kFixedN>
bool clip_polygon(const Vec3* in, int n_any, const Vec3& o, const Vec3& m, Polygon& out) {
  const int n = kFixedN > 0 ? kFixedN : n_any;
  std::array<double, 25> s;  // and s[n] = s[0]
  bool all_kept = true;
  for (int i = 0; i < n; ++i) {
    const double si = m.dot(in[i] - o);
    s[static_cast<std::size_t>(i)] = si;
    all_kept &= si >= 0;
  }
  if (all_kept) return false;
  s[static_cast<std::size_t>(n)] = s[0];
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3& p = in[i];
    const double sp = s[static_cast<std::size_t>(i)], sq = s[static_cast<std::size_t>(i + 1)];
    if (sp >= 0) out.v[static_cast<std::size_t>(count++)] = p;
    if ((sp >= 0) != (sq >= 0)) {
      const Vec3& q = in[i + 1 == n ? 0 : i + 1];
      out.v[static_cast<std::size_t>(count++)] = p + (sp / (sp - sq)) * (q - p);
    }
  }
  out.n = count;
  return true;
}

bool clip(const Vec3* in, int n, const Vec3& o, const Vec3& m, Polygon& out) {
  switch (n) {
    case 3:
      return clip_polygon<3>(in, n, o, m, out);
    case 4:
      return clip_polygon<4>(in, n, o, m, out);
    case 5:
      return clip_polygon<5>(in, n, o, m, out);
    default:
      return clip_polygon<0>(in, n, o, m, out);
  }
}

struct Direction {
  bool valid = false;
  double depth = 0;  // deepest point below the reference plane, >= 0
  Vec3 deepest = Vec3::Zero();
  Vec3 crossing_sum =
      Vec3::Zero();  // sum of the points where the clipped polygon crosses the plane
  int crossings = 0;
};

// Whether two triangles have the same coordinates bit for bit.
bool same_bits(const Triangle& x, const Triangle& y) {
  for (std::size_t k = 0; k < 3; ++k) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      std::uint64_t bx, by;
      std::memcpy(&bx, &x.v[k][c], sizeof bx);
      std::memcpy(&by, &y.v[k][c], sizeof by);
      if (bx != by) return false;
    }
  }
  return true;
}

// A triangle's unit normal and the inward normals n x (edge) of its edge planes, kept for the
// calls that follow with the same triangle (the MuJoCo layer passes candidates sorted by pair,
// so geom1's triangle repeats): set(t) computes them unless t has the bits of the last triangle.
struct Face {
  Triangle t{{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}};  // with what set() gives for it
  bool flat = false;
  Vec3 unit = Vec3::Zero();
  std::array<Vec3, 3> inward{{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}};

  void set(const Triangle& tri) {
    if (same_bits(tri, t)) return;
    t = tri;
    const Vec3 nrm = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    const double len = nrm.norm();
    // A zero or non-finite normal gives no direction (the triangle is a segment or a point).
    flat = len > 0 && std::isfinite(len);
    unit = flat ? Vec3(nrm / len) : Vec3::Zero();
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3 edge = t.v[(k + 1) % 3] - t.v[k];
      inward[k] = unit.cross(edge);
    }
  }
};

// measure's second half: the clipped polygon (count vertices; kFixedN as in clip_polygon)
// measured below ref's plane.
template <int kFixedN>
void measure_polygon(const Triangle& ref, const Vec3& n, const Vec3* poly, int count_any,
                     bool position, Direction& d) {
  const int count = kFixedN > 0 ? kFixedN : count_any;
  d.valid = true;
  std::array<double, 25> s;  // and s[count] = s[0]
  double best = -std::numeric_limits<double>::infinity();
  int deepest = 0;
  for (int i = 0; i < count; ++i) {
    const double si = n.dot(poly[i] - ref.v[0]);
    s[static_cast<std::size_t>(i)] = si;
    if (-si > best) {
      best = -si;
      deepest = i;
    }
  }
  d.depth = std::max(best, 0.0);
  if (!position) return;
  d.deepest = poly[deepest];
  s[static_cast<std::size_t>(count)] = s[0];
  for (int i = 0; i < count; ++i) {
    const double sp = s[static_cast<std::size_t>(i)], sq = s[static_cast<std::size_t>(i + 1)];
    if ((sp <= 0) != (sq <= 0)) {
      const Vec3& p = poly[i];
      const Vec3& q = poly[i + 1 == count ? 0 : i + 1];
      d.crossing_sum += p + (sp / (sp - sq)) * (q - p);
      ++d.crossings;
    }
  }
}

// `moving` clipped to the prism over `ref` and measured below `ref`'s plane (unit normal n).
// Without `position`, only `valid` and `depth` are set (deepest, crossing_sum and crossings stay
// zero).
Direction measure(const Face& face, const Triangle& moving, bool position) {
  const Triangle& ref = face.t;
  const Vec3& n = face.unit;
  Direction d;
  Polygon buffers[2];
  const Vec3* poly = moving.v.data();
  int count = 3;
  int next = 0;  // the buffer the next clip writes
  // The three edge planes of `ref`.
  for (std::size_t k = 0; k < 3 && count > 0; ++k) {
    if (clip(poly, count, ref.v[k], face.inward[k], buffers[next])) {
      poly = buffers[next].v.data();
      count = buffers[next].n;
      next = 1 - next;
    }
  }
  switch (count) {
    case 0:
      return d;
    case 3:
      measure_polygon<3>(ref, n, poly, count, position, d);
      break;
    case 4:
      measure_polygon<4>(ref, n, poly, count, position, d);
      break;
    case 5:
      measure_polygon<5>(ref, n, poly, count, position, d);
      break;
    default:
      measure_polygon<0>(ref, n, poly, count, position, d);
  }
  return d;
}

// The smallest overlap of the triangles' projections on the edge-edge axes ea_i x eb_j of their
// sharp edges (the SAT axes of gim_tri_collision). The sign comes from the solids where their
// faces say something: the normal N = +-L must point out of A and into B, so N.(n_a - n_b) >= 0
// (unit outward face normals, zero for a degenerate face), and the push is one-sided:
// max(A.N) - min(B.N). When L is nearly perpendicular to n_a - n_b (|L.(n_a - n_b)| <=
// tol::kContactSignCosine), the faces do not decide and the smaller of the two sides does. Returns
// false when no sharp edge pair has a cross-product axis.
bool min_edge_axis(const Triangle& a, const Triangle& b, const Vec3& na, const Vec3& nb,
                   std::uint8_t sharp_a, std::uint8_t sharp_b, Vec3& normal, double& depth) {
  const Vec3 out_of_a = na - nb;
  bool found = false;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!(sharp_a >> i & 1u)) continue;
    const Vec3 ea = a.v[(i + 1) % 3] - a.v[i];
    for (std::size_t j = 0; j < 3; ++j) {
      if (!(sharp_b >> j & 1u)) continue;
      const Vec3 eb = b.v[(j + 1) % 3] - b.v[j];
      Vec3 axis = ea.cross(eb);
      const double len = axis.norm();
      if (!(len > tol::kContactParallelEdgeSine * ea.norm() * eb.norm())) continue;
      axis /= len;
      double amin = axis.dot(a.v[0]), amax = amin, bmin = axis.dot(b.v[0]), bmax = bmin;
      for (std::size_t k = 1; k < 3; ++k) {
        const double pa = axis.dot(a.v[k]), pb = axis.dot(b.v[k]);
        amin = std::min(amin, pa);
        amax = std::max(amax, pa);
        bmin = std::min(bmin, pb);
        bmax = std::max(bmax, pb);
      }
      const double up = amax - bmin, down = bmax - amin;  // push B along +L, along -L
      const double w = axis.dot(out_of_a);
      const bool plus = std::abs(w) > tol::kContactSignCosine ? w > 0 : up <= down;
      const double d = std::max(plus ? up : down, 0.0);
      if (!found || d < depth) {
        found = true;
        depth = d;
        normal = plus ? axis : Vec3(-axis);
      }
    }
  }
  return found;
}

}  // namespace

TriContact triangle_pair_contact(const Triangle& a, const Triangle& b, double max_depth,
                                 const Vec3& fallback_normal, std::uint8_t sharp_a,
                                 std::uint8_t sharp_b) {
  thread_local Face face_a, face_b;
  face_a.set(a);
  face_b.set(b);
  const Vec3 &ua = face_a.unit, &ub = face_b.unit;
  const Direction da = face_a.flat ? measure(face_a, b, true) : Direction{};
  // b's crossings and deepest point place the contact only when a's clipped b has no crossing.
  const Direction db = face_b.flat ? measure(face_b, a, da.crossings == 0) : Direction{};
  TriContact c;
  // The smallest push among the face directions (one-sided, measured inside the prism)...
  double depth = std::numeric_limits<double>::infinity();
  if (da.valid) {
    depth = da.depth;
    c.normal = ua;
  }
  if (db.valid && db.depth < depth) {
    depth = db.depth;
    c.normal = -ub;
  }
  // ...and the edge-edge directions of sharp edges, which catch pairs where two faces cross along
  // edges of the solids and neither face normal is the direction of penetration.
  Vec3 edge_normal;
  double edge_depth = 0;
  if (sharp_a != 0 && sharp_b != 0 &&
      min_edge_axis(a, b, ua, ub, sharp_a, sharp_b, edge_normal, edge_depth) &&
      edge_depth < depth) {
    depth = edge_depth;
    c.normal = edge_normal;
  }
  if (!std::isfinite(depth)) {
    // No direction: both triangles degenerate, no sharp non-parallel edge pair.
    c.normal = fallback_normal;
    depth = 0;
  }
  c.depth = std::min(depth, max_depth);
  // Position: the midpoint of the intersection segment, on both surfaces.
  if (da.crossings > 0) {
    c.pos = da.crossing_sum / da.crossings;
  } else if (db.crossings > 0) {
    c.pos = db.crossing_sum / db.crossings;
  } else if (da.valid) {
    c.pos = da.deepest + (0.5 * c.depth) * c.normal;
  } else if (db.valid) {
    c.pos = db.deepest - (0.5 * c.depth) * c.normal;
  } else {
    c.pos = (a.v[0] + a.v[1] + a.v[2] + b.v[0] + b.v[1] + b.v[2]) / 6.0;
  }
  return c;
}

}  // namespace graspcd
