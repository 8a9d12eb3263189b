#include "graspcd/core/tritri.h"

#include <algorithm>
#include <cmath>

#include "graspcd/core/predicates.h"
#include "graspcd/core/tolerances.h"

namespace graspcd {
namespace {

using predicates::orient2d;
using predicates::orient3d;

constexpr double kU = tol::kUnitRoundoff;

// ================================================================================================
// Exact test from orientation predicates (every decision an exact sign).
// ================================================================================================

// The drop axis k for which the projection of non-degenerate triangle abc onto the other two
// coordinates is non-degenerate (component k of its normal is exactly non-zero). Such a
// projection is a bijection of the triangle's plane, so it preserves every incidence in it.
int projection_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  // Prefer the largest normal component (best conditioned), but decide non-zero exactly.
  const Vec3 n = (b - a).cross(c - a);
  const int k = argmax_abs(n);
  if (orient2d(a, b, c, k) != 0) return k;
  for (int m = 0; m < 3; ++m) {
    if (orient2d(a, b, c, m) != 0) return m;
  }
  return -1;  // degenerate: callers never ask for one
}

// Is p on closed segment [a, b], given that p, a, b are collinear? Coordinatewise betweenness.
bool between(const Vec3& a, const Vec3& b, const Vec3& p) {
  for (int k = 0; k < 3; ++k) {
    if (p[k] < std::min(a[k], b[k]) || p[k] > std::max(a[k], b[k])) return false;
  }
  return true;
}

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  return orient2d(a, b, c, 0) == 0 && orient2d(a, b, c, 1) == 0 && orient2d(a, b, c, 2) == 0;
}

// Closed segments [p1, p2] and [q1, q2] in the projection dropping axis k.
bool segments_meet_2d(const Vec3& p1, const Vec3& p2, const Vec3& q1, const Vec3& q2, int k) {
  const int o1 = orient2d(p1, p2, q1, k), o2 = orient2d(p1, p2, q2, k);
  const int o3 = orient2d(q1, q2, p1, k), o4 = orient2d(q1, q2, p2, k);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
  // Touching or collinear: an endpoint on the other segment. In the projection, betweenness is
  // checked on the two kept coordinates only.
  const auto on = [k](const Vec3& a, const Vec3& b, const Vec3& p) {
    for (int m = 0; m < 3; ++m) {
      if (m == k) continue;
      if (p[m] < std::min(a[m], b[m]) || p[m] > std::max(a[m], b[m])) return false;
    }
    return true;
  };
  return (o1 == 0 && on(p1, p2, q1)) || (o2 == 0 && on(p1, p2, q2)) ||
         (o3 == 0 && on(q1, q2, p1)) || (o4 == 0 && on(q1, q2, p2));
}

// Closed triangle abc (non-degenerate in the projection dropping k) contains p (same plane).
bool point_in_triangle_2d(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int k) {
  const int o1 = orient2d(a, b, p, k), o2 = orient2d(b, c, p, k), o3 = orient2d(c, a, p, k);
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

bool segment_triangle_2d(const Vec3& s0, const Vec3& s1, const Triangle& t, int k) {
  const auto& [a, b, c] = t.v;
  return point_in_triangle_2d(s0, a, b, c, k) || point_in_triangle_2d(s1, a, b, c, k) ||
         segments_meet_2d(s0, s1, a, b, k) || segments_meet_2d(s0, s1, b, c, k) ||
         segments_meet_2d(s0, s1, c, a, k);
}

// Closed segment [s0, s1] (non-degenerate) against closed non-degenerate triangle t, given the
// exact sides o0, o1 of s0 and s1 relative to t's plane (orient3d(a, b, c, s)).
bool segment_triangle(const Vec3& s0, const Vec3& s1, int o0, int o1, const Triangle& t) {
  const auto& [a, b, c] = t.v;
  if (o0 * o1 > 0) return false;  // both strictly on one side
  if (o0 == 0 && o1 == 0) return segment_triangle_2d(s0, s1, t, projection_axis(a, b, c));
  // The segment meets the plane in exactly one point; it is in the closed triangle iff the line
  // s0 s1 passes on the same side (or on) each directed edge (Plucker side tests as orient3d).
  const int e0 = orient3d(s0, s1, a, b), e1 = orient3d(s0, s1, b, c), e2 = orient3d(s0, s1, c, a);
  return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

bool segment_triangle(const Vec3& s0, const Vec3& s1, const Triangle& t) {
  const auto& [a, b, c] = t.v;
  return segment_triangle(s0, s1, orient3d(a, b, c, s0), orient3d(a, b, c, s1), t);
}

// Two non-degenerate, non-coplanar triangles with the exact sides o1 of T1's vertices relative to
// T2's plane and o2 of T2's relative to T1's: T1 ∩ T2 lies on the planes' common line; its ends are
// ends of T1 ∩ L or of T2 ∩ L, which lie on the triangles' edges. So they meet iff some edge of
// one meets the other.
bool edges_meet(const Triangle& t1, const Triangle& t2, const int o1[3], const int o2[3]) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (segment_triangle(t1.v[i], t1.v[j], o1[i], o1[j], t2)) return true;
    if (segment_triangle(t2.v[i], t2.v[j], o2[i], o2[j], t1)) return true;
  }
  return false;
}

bool point_triangle(const Vec3& p, const Triangle& t) {
  const auto& [a, b, c] = t.v;
  return orient3d(a, b, c, p) == 0 && point_in_triangle_2d(p, a, b, c, projection_axis(a, b, c));
}

bool segment_segment(const Vec3& p1, const Vec3& p2, const Vec3& q1, const Vec3& q2) {
  if (orient3d(p1, p2, q1, q2) != 0) return false;  // skew lines
  // Coplanar: project along an axis normal to their common plane, found from a point of q that
  // is off the line p1 p2. If there is none, all four points are collinear.
  for (const Vec3* q : {&q1, &q2}) {
    for (int k = 0; k < 3; ++k) {
      if (orient2d(p1, p2, *q, k) != 0) return segments_meet_2d(p1, p2, q1, q2, k);
    }
  }
  // Collinear: closed intervals along a coordinate on which p1 and p2 differ.
  const int m = argmax_abs(p2 - p1);
  return std::max(std::min(p1[m], p2[m]), std::min(q1[m], q2[m])) <=
         std::min(std::max(p1[m], p2[m]), std::max(q1[m], q2[m]));
}

// A triangle's exact shape: the point, segment or triangle its three vertices span.
struct Shape {
  enum Kind { kPoint, kSegment, kTriangle } kind;
  Vec3 p, q;  // the point (p), or the segment's endpoints (p, q)
};

Shape classify(const Triangle& t) {
  const auto& [a, b, c] = t.v;
  if (a == b && b == c) return {Shape::kPoint, a, a};
  if (!collinear(a, b, c)) return {Shape::kTriangle, a, a};
  // Collinear: the extreme pair along a coordinate on which they are not all equal.
  const int m = argmax_abs(a.cwiseMax(b).cwiseMax(c) - a.cwiseMin(b).cwiseMin(c));
  const Vec3* mn = &a;
  const Vec3* mx = &a;
  for (const Vec3* x : {&b, &c}) {
    if ((*x)[m] < (*mn)[m]) mn = x;
    if ((*x)[m] > (*mx)[m]) mx = x;
  }
  return {Shape::kSegment, *mn, *mx};
}

bool shape_triangle(const Shape& s, const Triangle& t) {
  return s.kind == Shape::kPoint ? point_triangle(s.p, t) : segment_triangle(s.p, s.q, t);
}

bool shape_shape(const Shape& s, const Shape& r) {
  if (s.kind == Shape::kPoint && r.kind == Shape::kPoint) return s.p == r.p;
  if (s.kind == Shape::kPoint) return collinear(r.p, r.q, s.p) && between(r.p, r.q, s.p);
  if (r.kind == Shape::kPoint) return collinear(s.p, s.q, r.p) && between(s.p, s.q, r.p);
  return segment_segment(s.p, s.q, r.p, r.q);
}

// Both triangles non-degenerate and in one plane.
bool coplanar_triangles(const Triangle& t1, const Triangle& t2) {
  const int k = projection_axis(t1.v[0], t1.v[1], t1.v[2]);
  for (int i = 0; i < 3; ++i) {
    if (point_in_triangle_2d(t1.v[i], t2.v[0], t2.v[1], t2.v[2], k)) return true;
    if (point_in_triangle_2d(t2.v[i], t1.v[0], t1.v[1], t1.v[2], k)) return true;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (segments_meet_2d(t1.v[i], t1.v[(i + 1) % 3], t2.v[j], t2.v[(j + 1) % 3], k)) return true;
    }
  }
  return false;
}

// ================================================================================================
// Moller 1997 in floating point with proven error bounds.
// ================================================================================================

// A triangle's plane N . (x - v0) = 0 with N = (v1 - v0) x (v2 - v0), and for each component of N
// the permanent P_k = |a_i b_j| + |a_j b_i| that bounds its rounding error (TrianglePlane).
using Plane = TrianglePlane;

[[gnu::always_inline]] inline void plane_of(const Triangle& t, Plane& p) {
  const Vec3 a = t.v[1] - t.v[0], b = t.v[2] - t.v[0];
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double x = a[i] * b[j], y = a[j] * b[i];
    p.n[k] = x - y;
    p.perm[k] = std::fabs(x) + std::fabs(y);
  }
}

// Is N exactly non-zero? Each computed component is within 4u P_k (+O(u^2)) of the exact one;
// a component above 8u P_k proves it. Otherwise ask the exact predicates.
inline bool non_degenerate(const Triangle& t, const Plane& p) {
  for (int k = 0; k < 3; ++k) {
    if (std::fabs(p.n[k]) > 8 * kU * p.perm[k]) return true;
  }
  return !collinear(t.v[0], t.v[1], t.v[2]);
}

// Signed distance (times |N|) of x to the plane of t, eq. (7), with an error bound:
// |d - d_exact| <= 16 u sum_k |w_k| P_k, w = x - v0. (First-order analysis: the components of N
// carry <= 4u P_k, rounding w adds u |N_k| |w_k|, the dot product 3u sum |N_k w_k|; |N_k| <= P_k
// gives 8u; 16u covers the second-order terms.) Inside the bound the sign is decided exactly.
struct Distance {
  double d;
  double err;
  int sign;
};

[[gnu::always_inline]] inline Distance plane_distance(const Triangle& t, const Plane& p,
                                                      const Vec3& x) {
  const Vec3 w = x - t.v[0];
  Distance r;
  r.d = p.n[0] * w[0] + p.n[1] * w[1] + p.n[2] * w[2];
  r.err = 16 * kU *
          (std::fabs(w[0]) * p.perm[0] + std::fabs(w[1]) * p.perm[1] + std::fabs(w[2]) * p.perm[2]);
  if (r.d > r.err) {
    r.sign = 1;
  } else if (-r.d > r.err) {
    r.sign = -1;
  } else {
    r.sign = orient3d(t.v[0], t.v[1], t.v[2], x);
  }
  return r;
}

// The interval on coordinate k covered by T ∩ (other plane), eq. (8)-(9), with an error bound on
// its ends. Endpoints: vertices with distance exactly 0, and the crossings of edges whose ends
// have strictly opposite signs, t = P_i + (P_j - P_i) d_i / (d_i - d_j) (eq. 9, sign typo fixed).
// Error of r = d_i / (d_i - d_j), with E = E_i + E_j, S = |d_i| + |d_j| (computed) and D, D' the
// exact and computed d_i - d_j: |D| >= S - E, |D'| >= S - 2E, and r' - r = (d_i' - d_i) / D' +
// d_i (D - D') / (D D') with |d_i| <= |D| (exact signs are opposite), so |r' - r| <= 2E / (S - 2E),
// which is <= 4E / S when S > 4E; rounding adds a few u. Error of t: <= |P_j - P_i| (dr + 2u) +
// u (|P_i| + |P_j - P_i|). Returns false when a crossing is too ill-conditioned (S <= 4E).
struct Interval {
  double lo, hi, err;
};

[[gnu::always_inline]] inline bool crossing_interval(const Triangle& t, const Distance d[3], int k,
                                                     Interval& out) {
  out.lo = INFINITY;
  out.hi = -INFINITY;
  out.err = 0.0;
  const auto add = [&out](double value, double err) {
    out.lo = std::min(out.lo, value);
    out.hi = std::max(out.hi, value);
    out.err = std::max(out.err, err);
  };
  for (int i = 0; i < 3; ++i) {
    if (d[i].sign == 0) add(t.v[i][k], 0.0);
    const int j = (i + 1) % 3;
    if (d[i].sign * d[j].sign >= 0) continue;
    const double s = std::fabs(d[i].d) + std::fabs(d[j].d);
    const double e = d[i].err + d[j].err;
    if (!(s > 4 * e)) return false;
    const double pi = t.v[i][k], pj = t.v[j][k];
    const double dp = pj - pi;
    const double r = d[i].d / (d[i].d - d[j].d);
    const double dr = 4 * e / s + 4 * kU;
    add(pi + dp * r, std::fabs(dp) * (dr + 4 * kU) + 2 * kU * (std::fabs(pi) + std::fabs(dp)));
  }
  return true;
}

// -------------------------------------------------------------------------------------------------
// The reference variants, for measurement only: Moller's published structure in plain floating
// point, with his absolute epsilon (naive) or none (plain). Coplanar pairs use a plain
// floating-point edge and containment test.
// -------------------------------------------------------------------------------------------------

bool coplanar_float(const Triangle& t1, const Triangle& t2, const Vec3& n) {
  const int k = argmax_abs(n);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const auto cross2 = [i, j](const Vec3& a, const Vec3& b, const Vec3& c) {
    return (b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]);
  };
  const auto edges_cross = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const double o1 = cross2(a, b, c), o2 = cross2(a, b, d);
    const double o3 = cross2(c, d, a), o4 = cross2(c, d, b);
    return o1 * o2 <= 0 && o3 * o4 <= 0 && !(o1 == 0 && o2 == 0);
  };
  const auto inside = [&](const Vec3& p, const Triangle& t) {
    const double a = cross2(t.v[0], t.v[1], p), b = cross2(t.v[1], t.v[2], p),
                 c = cross2(t.v[2], t.v[0], p);
    return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
  };
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      if (edges_cross(t1.v[a], t1.v[(a + 1) % 3], t2.v[b], t2.v[(b + 1) % 3])) return true;
    }
  }
  return inside(t1.v[0], t2) || inside(t2.v[0], t1);
}

bool moller_float(const Triangle& t1, const Triangle& t2, double epsilon) {
  const auto distances = [epsilon](const Triangle& t, const Triangle& other, double d[3], Vec3& n) {
    n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    const double offset = -n.dot(t.v[0]);
    for (int i = 0; i < 3; ++i) {
      d[i] = n.dot(other.v[i]) + offset;
      if (std::fabs(d[i]) < epsilon) d[i] = 0.0;
    }
  };
  double du[3], dv[3];
  Vec3 n1, n2;
  distances(t1, t2, du, n1);
  if (du[0] * du[1] > 0 && du[0] * du[2] > 0) return false;
  distances(t2, t1, dv, n2);
  if (dv[0] * dv[1] > 0 && dv[0] * dv[2] > 0) return false;
  if (dv[0] == 0 && dv[1] == 0 && dv[2] == 0) return coplanar_float(t1, t2, n1);
  const Vec3 dir = n1.cross(n2);
  const int k = argmax_abs(dir);
  // Interval of t on coordinate k; vertices on the plane count as endpoints.
  const auto interval = [k](const Triangle& t, const double d[3], double& lo, double& hi) {
    lo = INFINITY;
    hi = -INFINITY;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (d[i] == 0) {
        lo = std::min(lo, t.v[i][k]);
        hi = std::max(hi, t.v[i][k]);
      }
      if (d[i] * d[j] < 0) {
        const double x = t.v[i][k] + (t.v[j][k] - t.v[i][k]) * d[i] / (d[i] - d[j]);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    }
  };
  double lo1, hi1, lo2, hi2;
  interval(t1, dv, lo1, hi1);
  interval(t2, du, lo2, hi2);
  return !(hi1 < lo2 || hi2 < lo1);
}

// True when every coordinate is finite: x - x is 0 for a finite x and NaN for NaN or inf.
[[gnu::always_inline]] inline bool finite(const Triangle& t) {
  const Vec3 zero = (t.v[0] - t.v[0]) + (t.v[1] - t.v[1]) + (t.v[2] - t.v[2]);
  return zero[0] + zero[1] + zero[2] == 0.0;
}

}  // namespace

// Exact test: classify, then dispatch (see tritri.h).
bool tri_tri_intersect_predicates(const Triangle& t1, const Triangle& t2) {
  if (!finite(t1) || !finite(t2)) return false;  // no set of points (tritri.h)
  const Shape s1 = classify(t1), s2 = classify(t2);
  if (s1.kind != Shape::kTriangle && s2.kind != Shape::kTriangle) return shape_shape(s1, s2);
  if (s1.kind != Shape::kTriangle) return shape_triangle(s1, t2);
  if (s2.kind != Shape::kTriangle) return shape_triangle(s2, t1);
  // Two proper triangles. Reject when one lies strictly on one side of the other's plane.
  int o1[3], o2[3];
  for (int i = 0; i < 3; ++i) {
    o1[i] = orient3d(t2.v[0], t2.v[1], t2.v[2], t1.v[i]);
    o2[i] = orient3d(t1.v[0], t1.v[1], t1.v[2], t2.v[i]);
  }
  const auto one_side = [](const int o[3]) {
    return (o[0] > 0 && o[1] > 0 && o[2] > 0) || (o[0] < 0 && o[1] < 0 && o[2] < 0);
  };
  if (one_side(o1) || one_side(o2)) return false;
  if (o1[0] == 0 && o1[1] == 0 && o1[2] == 0) return coplanar_triangles(t1, t2);
  return edges_meet(t1, t2, o1, o2);
}

namespace {

// A lower bound on the distance (metres) between the plane of p and a triangle whose vertices'
// distances d (times |N|, with their error bounds) all have one strict sign: each exact |D_i| >=
// |d_i| - err_i, and the exact normal's length |N| <= |n| + 4u |P| (plane_of: each component within
// 4u P_k). The factors 1 +- 1e-12 absorb the rounding of these few operations (a few u) many times
// over. 0 when a vertex's distance is not above its error bound (its sign came from orient3d).
double plane_gap(const Plane& p, const Distance d[3]) {
  double nearest = std::fabs(d[0].d) - d[0].err;
  for (int i = 1; i < 3; ++i) nearest = std::min(nearest, std::fabs(d[i].d) - d[i].err);
  if (!(nearest > 0)) return 0;
  const double length = p.n.norm() * (1 + 1e-12) + 8 * kU * p.perm.norm();
  return nearest * (1 - 1e-12) / length;
}

// Moller 1997, eq. (6)-(9), with every floating-point decision certified by an error bound. With
// `gap`, a rejection by a plane also gives plane_gap (tritri.h). `q1`, when given, is T1's plane
// from triangle_plane(t1): the same numbers the test would compute (plane_of, non_degenerate,
// finite), taken instead of computed, so the answer and the gap are the same bit for bit.
template <bool kGap>
[[gnu::always_inline]] inline bool moller_certified(const Triangle& t1, const Triangle& t2,
                                                    double* gap, const Plane* q1) {
  // No set of points (tritri.h).
  if (q1 ? !q1->finite : !finite(t1)) return false;
  if (!finite(t2)) return false;
  // Eq. (6)-(7): T1's vertices against T2's plane; reject if all strictly on one side.
  Plane p2;
  plane_of(t2, p2);
  if (!non_degenerate(t2, p2)) return tri_tri_intersect_predicates(t1, t2);
  Distance d1[3];
  for (int i = 0; i < 3; ++i) d1[i] = plane_distance(t2, p2, t1.v[i]);
  if (d1[0].sign == d1[1].sign && d1[1].sign == d1[2].sign && d1[0].sign != 0) {
    if constexpr (kGap) *gap = plane_gap(p2, d1);
    return false;
  }
  // The same for T2's vertices against T1's plane; coplanar pairs are decided exactly in 2D.
  Plane computed;
  if (!q1) plane_of(t1, computed);
  const Plane& p1 = q1 ? *q1 : computed;
  if (q1 ? !q1->proper : !non_degenerate(t1, p1)) return tri_tri_intersect_predicates(t1, t2);
  if (d1[0].sign == 0 && d1[1].sign == 0 && d1[2].sign == 0) return coplanar_triangles(t1, t2);
  Distance d2[3];
  for (int i = 0; i < 3; ++i) d2[i] = plane_distance(t1, p1, t2.v[i]);
  if (d2[0].sign == d2[1].sign && d2[1].sign == d2[2].sign && d2[0].sign != 0) {
    if constexpr (kGap) *gap = plane_gap(p1, d2);
    return false;
  }
  // Eq. (8): project on the coordinate axis most aligned with L = N1 x N2. Any axis gives a valid
  // answer when the decision clears its error bound (the coordinate is affine along L); a
  // near-degenerate axis only makes the bound fail and the exact test decide.
  const Vec3 dir = p1.n.cross(p2.n);
  const int k = argmax_abs(dir);
  // Inside the error bounds, the exact decision from the (exact) signs already known.
  const int o1[3] = {d1[0].sign, d1[1].sign, d1[2].sign};
  const int o2[3] = {d2[0].sign, d2[1].sign, d2[2].sign};
  Interval i1, i2;
  if (!crossing_interval(t1, d1, k, i1) || !crossing_interval(t2, d2, k, i2)) {
    return edges_meet(t1, t2, o1, o2);
  }
  // Certain when the overlap or the gap exceeds both ends' errors (with the subtraction's own
  // rounding, relative u, absorbed by the factor).
  const double err = 2 * std::max(i1.err, i2.err) * (1 + 8 * kU);
  const double overlap = std::min(i1.hi, i2.hi) - std::max(i1.lo, i2.lo);
  if (overlap > err) return true;
  if (-overlap > err) return false;
  return edges_meet(t1, t2, o1, o2);
}

}  // namespace

TrianglePlane triangle_plane(const Triangle& t) {
  TrianglePlane p;
  p.finite = finite(t);
  if (!p.finite) return p;  // never used: the test answers false first
  plane_of(t, p);
  p.proper = non_degenerate(t, p);
  return p;
}

bool tri_tri_intersect(const Triangle& t1, const Triangle& t2) {
  return moller_certified<false>(t1, t2, nullptr, nullptr);
}

bool tri_tri_intersect(const Triangle& t1, const Triangle& t2, double& gap) {
  gap = 0;
  return moller_certified<true>(t1, t2, &gap, nullptr);
}

bool tri_tri_intersect(const Triangle& t1, const TrianglePlane& p1, const Triangle& t2) {
  return moller_certified<false>(t1, t2, nullptr, &p1);
}

bool tri_tri_intersect(const Triangle& t1, const TrianglePlane& p1, const Triangle& t2,
                       double& gap) {
  gap = 0;
  return moller_certified<true>(t1, t2, &gap, &p1);
}

bool tri_tri_moller_naive(const Triangle& t1, const Triangle& t2) {
  return moller_float(t1, t2, tol::kNaiveMollerEpsilon);
}

bool tri_tri_moller_plain(const Triangle& t1, const Triangle& t2) {
  return moller_float(t1, t2, 0.0);
}

}  // namespace graspcd
