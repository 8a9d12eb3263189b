// Shewchuk 1997 (see predicates.h): stage-A filters and exact expansion arithmetic.
#include "graspcd/core/predicates.h"

#include <cmath>

#include "graspcd/core/tolerances.h"

namespace graspcd::predicates {
namespace {

constexpr double kEps = tol::kUnitRoundoff;
// Shewchuk's error bounds of the plain floating-point determinants (stage A).
constexpr double kOrient2dErrBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dErrBound = (7.0 + 56.0 * kEps) * kEps;
// Dekker's splitter 2^ceil(53/2) + 1.
constexpr double kSplitter = 134217729.0;

// --- Error-free transformations (Shewchuk, section 2) -------------------------------------------

// x + y == a + b exactly, x = fl(a + b).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

// x + y == a - b exactly, x = fl(a - b).
inline void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double b_virtual = a - x;
  const double a_virtual = x + b_virtual;
  y = (a - a_virtual) + (b_virtual - b);
}

// a == hi + lo, each with at most 26 significant bits.
inline void split(double a, double& hi, double& lo) {
  const double c = kSplitter * a;
  const double a_big = c - a;
  hi = c - a_big;
  lo = a - hi;
}

// x + y == a * b exactly, x = fl(a * b) (Dekker's Two-Product).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  const double err1 = x - ahi * bhi;
  const double err2 = err1 - alo * bhi;
  const double err3 = err2 - ahi * blo;
  y = alo * blo - err3;
}

// --- Expansions: nonoverlapping components in increasing magnitude, zeros eliminated ---------

// A fixed-capacity expansion. Capacity 256 holds every intermediate of orient3d (at most 192).
struct Expansion {
  static constexpr int kCapacity = 256;
  double c[kCapacity];
  int n = 0;

  int sign() const { return n == 0 ? 0 : (c[n - 1] > 0.0 ? 1 : -1); }
};

// The exact difference a - b as an expansion of one or two components.
Expansion difference(double a, double b) {
  Expansion e;
  double hi, lo;
  two_diff(a, b, hi, lo);
  if (lo != 0.0) e.c[e.n++] = lo;
  if (hi != 0.0) e.c[e.n++] = hi;
  return e;
}

// x + y == a + b exactly, given |a| >= |b| or a == 0.
inline void fast_two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  y = b - (x - a);
}

// e + f (Shewchuk's Fast-Expansion-Sum with zero elimination): merge the components by magnitude,
// then one chain of Two-Sums. Linear in the lengths; valid under round-to-nearest-even.
Expansion sum(const Expansion& e, const Expansion& f) {
  if (e.n == 0) return f;
  if (f.n == 0) return e;
  Expansion h;
  int i = 0, j = 0;
  // The next component in order of increasing magnitude.
  const auto next = [&]() {
    if (j >= f.n || (i < e.n && (f.c[j] > e.c[i]) == (f.c[j] > -e.c[i]))) return e.c[i++];
    return f.c[j++];
  };
  double q = next();
  double q_new, hh;
  fast_two_sum(next(), q, q_new, hh);
  q = q_new;
  if (hh != 0.0) h.c[h.n++] = hh;
  while (i < e.n || j < f.n) {
    two_sum(q, next(), q_new, hh);
    q = q_new;
    if (hh != 0.0) h.c[h.n++] = hh;
  }
  if (q != 0.0 || h.n == 0) h.c[h.n++] = q;
  if (h.n == 1 && h.c[0] == 0.0) h.n = 0;
  return h;
}

Expansion negate(Expansion e) {
  for (int i = 0; i < e.n; ++i) e.c[i] = -e.c[i];
  return e;
}

// e * b (Shewchuk's Scale-Expansion with zero elimination).
Expansion scale(const Expansion& e, double b) {
  Expansion h;
  if (e.n == 0 || b == 0.0) return h;
  double q, lo;
  two_product(e.c[0], b, q, lo);
  if (lo != 0.0) h.c[h.n++] = lo;
  for (int i = 1; i < e.n; ++i) {
    double prod_hi, prod_lo, sum1, err1, sum2, err2;
    two_product(e.c[i], b, prod_hi, prod_lo);
    two_sum(q, prod_lo, sum1, err1);
    if (err1 != 0.0) h.c[h.n++] = err1;
    two_sum(prod_hi, sum1, sum2, err2);
    if (err2 != 0.0) h.c[h.n++] = err2;
    q = sum2;
  }
  if (q != 0.0) h.c[h.n++] = q;
  return h;
}

// e * f, as the sum of e scaled by each component of f.
Expansion product(const Expansion& e, const Expansion& f) {
  Expansion h;
  for (int i = 0; i < f.n; ++i) h = sum(h, scale(e, f.c[i]));
  return h;
}

// x * y - z * w, exactly.
Expansion cross_term(const Expansion& x, const Expansion& y, const Expansion& z,
                     const Expansion& w) {
  return sum(product(x, y), negate(product(z, w)));
}

}  // namespace

FilterStats& filter_stats() {
  thread_local FilterStats stats;
  return stats;
}

int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  if (!(a.allFinite() && b.allFinite() && c.allFinite() && d.allFinite())) return 0;
  ++filter_stats().orient3d_exact_calls;
  // det[u; v; w] with u = b - a, v = c - a, w = d - a, each difference exact.
  Expansion u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = difference(b[k], a[k]);
    v[k] = difference(c[k], a[k]);
    w[k] = difference(d[k], a[k]);
  }
  // u . (v x w), component by component.
  const Expansion vw0 = cross_term(v[1], w[2], v[2], w[1]);
  const Expansion vw1 = cross_term(v[2], w[0], v[0], w[2]);
  const Expansion vw2 = cross_term(v[0], w[1], v[1], w[0]);
  const Expansion det = sum(sum(product(vw0, u[0]), product(vw1, u[1])), product(vw2, u[2]));
  return det.sign();
}

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // Stage A of Shewchuk's orient3d, written for det[b-a; c-a; d-a].
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  const double vywz = vy * wz, vzwy = vz * wy;
  const double vzwx = vz * wx, vxwz = vx * wz;
  const double vxwy = vx * wy, vywx = vy * wx;
  const double det = ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx);
  const double permanent = std::fabs(ux) * (std::fabs(vywz) + std::fabs(vzwy)) +
                           std::fabs(uy) * (std::fabs(vzwx) + std::fabs(vxwz)) +
                           std::fabs(uz) * (std::fabs(vxwy) + std::fabs(vywx));
  const double bound = kOrient3dErrBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  // A NaN or infinite input (or a product beyond the double range) has no sign to compute: 0,
  // without expansions (predicates.h).
  if (!std::isfinite(permanent)) return 0;
  // A zero permanent means every product has an exactly zero factor (differences of doubles are
  // zero only for equal doubles, and products cannot underflow in tol's coordinate range), so the
  // determinant is exactly zero: the common case of shared vertices, answered without expansions.
  if (permanent == 0.0) return 0;
  return orient3d_exact(a, b, c, d);
}

int orient2d_exact(const Vec3& a, const Vec3& b, const Vec3& c, int drop) {
  if (!(a.allFinite() && b.allFinite() && c.allFinite())) return 0;
  ++filter_stats().orient2d_exact_calls;
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  const Expansion det = cross_term(difference(b[i], a[i]), difference(c[j], a[j]),
                                   difference(b[j], a[j]), difference(c[i], a[i]));
  return det.sign();
}

int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop) {
  // Stage A of Shewchuk's orient2d on the kept coordinates (i, j).
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  const double left = (b[i] - a[i]) * (c[j] - a[j]);
  const double right = (b[j] - a[j]) * (c[i] - a[i]);
  const double det = left - right;
  const double permanent = std::fabs(left) + std::fabs(right);
  const double bound = kOrient2dErrBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  if (!std::isfinite(permanent)) return 0;  // a NaN or infinite input, as in orient3d
  if (permanent == 0.0) return 0;           // exactly zero, as in orient3d
  return orient2d_exact(a, b, c, drop);
}

}  // namespace graspcd::predicates
