// Seeded random geometry shared by the tests and the benchmarks: triangles, boxes, and adversarial
// triangle pairs (touching, coplanar, near-coplanar, slivers, zero-area) built so that their
// degeneracies are exact in double.
//
// Every generator takes the caller's generator (seeded.h, the project's one seeded generator),
// seeded explicitly by the test, so each run on any compiler sees the same numbers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb.h"
#include "graspcd/support/seeded.h"

namespace graspcd::testing {

using seeded::chance;
using seeded::kPi;
using seeded::log_uniform;
using seeded::normal;
using seeded::random_in_cube;
using seeded::random_rotation;
using seeded::random_sign;
using seeded::random_unit;
using seeded::Rng;
using seeded::rotation_about;
using seeded::shuffle;
using seeded::uniform;
using seeded::uniform01;
using seeded::uniform_in_box;
using seeded::uniform_int;
using seeded::uniform_vec3;

// ---- Triangles and boxes ----------------------------------------------------------------------

// A triangle with vertices uniform in the cube of side `size` centred at `near`.
inline Triangle random_triangle(Rng& rng, const Vec3& near, double size) {
  return Triangle{{random_in_cube(rng, near, size / 2), random_in_cube(rng, near, size / 2),
                   random_in_cube(rng, near, size / 2)}};
}

// A "fat" triangle about `center`: in a uniformly random plane through it, vertex i at angle
// 2 pi i / 3 +- 0.5 rad and at distance (0.3 .. 1) * size / 2, so `center` is inside it. Two of
// them about the same point always intersect; offsetting one centre by up to +-0.25 sizes per axis
// keeps about half of the pairs intersecting.
inline Triangle random_fat_triangle(Rng& rng, const Vec3& center, double size) {
  const Mat3 R = random_rotation(rng);
  Triangle t;
  for (int i = 0; i < 3; ++i) {
    const double angle = 2 * kPi * i / 3 + uniform(rng, -0.5, 0.5);
    const double radius = uniform(rng, 0.3, 1.0) * size / 2;
    t.v[i] = center + R * Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.0);
  }
  return t;
}

// A uniformly rotated box centred at `center`, half-extents log-uniform in [min_half, max_half].
inline Obb random_box(Rng& rng, const Vec3& center, double min_half, double max_half) {
  Obb box;
  box.center = center;
  box.axes = random_rotation(rng);
  for (int i = 0; i < 3; ++i) box.half[i] = log_uniform(rng, min_half, max_half);
  return box;
}

// The triangle with its vertices in another order: perm 0-5 enumerates the six orders (0 is the
// identity, 1-2 the other cyclic ones, 3-5 the reflections).
inline Triangle permuted(const Triangle& t, int perm) {
  static constexpr int kOrder[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                       {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  const int* o = kOrder[perm];
  return Triangle{{t.v[o[0]], t.v[o[1]], t.v[o[2]]}};
}

// ---- Adversarial triangle pairs ---------------------------------------------------------------
//
// Each class is first built in a canonical frame on an integer lattice (the triangles are
// kLattice = 1024 steps across) with optional "fine" offsets of 2^-k steps (k <= 28). Every such
// coordinate needs at most 12 + 28 bits, so it is exact in double. It is then placed in one of two
// ways:
//  - lattice placement: a signed permutation of the axes, a scale by the lattice step (a power of
//    two near size / 1024) and a translation by a lattice point (within 4 sizes of the origin, or
//    about 1000 sizes away for the far variants: at most 2^21 steps, so the sums stay below 53
//    bits). Every operation is exact, so the built degeneracy (a vertex exactly on a face, two
//    parallel planes exactly 2^-k steps apart) holds in the doubles and the answer is known.
//  - rotated placement: a uniform random rotation about the canonical origin and a translation by
//    a random point (near the origin or about 1000 sizes away). The coordinates are rounded, so
//    the pair is merely near-degenerate and CGAL decides; vertices shared by construction stay
//    bit-identical (the same double operations on the same inputs), so touching pairs that share
//    a vertex still have a known answer.

enum class PairClass {
  kCoplanarOverlap,   // same plane, a vertex of T2 strictly inside T1
  kCoplanarDisjoint,  // same plane, separated by a line with a gap of 1 step down to 2^-28 steps
  kSharedEdge,        // T2 reuses an edge of T1 (in any order), third vertex anywhere
  kSharedVertex,      // T2 reuses a vertex of T1
  kVertexOnFace,      // a vertex of T2 exactly on T1 (inside, on an edge or at a vertex)
  kVertexNearFace,    // as kVertexOnFace but lifted off T1's plane by 2^-k steps, T2 above
  kEdgeThroughEdge,   // an edge of T2 crosses an edge of T1 at one point; the rest apart
  kNearCoplanar,      // T2 tilted against T1's plane by 1e-9 .. 1e-3 rad, overlapping in plane
  kParallelPlanes,    // parallel planes 2^-k steps (k = 0 .. 28) apart, overlapping in projection
  kSliver,            // aspect ratio about 1e6, against a sliver or an ordinary triangle
  kZeroAreaSegment,   // T1 spans a segment (three collinear points or a repeated vertex)
  kZeroAreaPoint,     // T1 spans a point (three equal vertices)
  kCount
};

inline constexpr int kPairClassCount = static_cast<int>(PairClass::kCount);

inline const char* pair_class_name(PairClass c) {
  switch (c) {
    case PairClass::kCoplanarOverlap:
      return "coplanar_overlap";
    case PairClass::kCoplanarDisjoint:
      return "coplanar_disjoint";
    case PairClass::kSharedEdge:
      return "shared_edge";
    case PairClass::kSharedVertex:
      return "shared_vertex";
    case PairClass::kVertexOnFace:
      return "vertex_on_face";
    case PairClass::kVertexNearFace:
      return "vertex_near_face";
    case PairClass::kEdgeThroughEdge:
      return "edge_through_edge";
    case PairClass::kNearCoplanar:
      return "near_coplanar";
    case PairClass::kParallelPlanes:
      return "parallel_planes";
    case PairClass::kSliver:
      return "sliver";
    case PairClass::kZeroAreaSegment:
      return "zero_area_segment";
    case PairClass::kZeroAreaPoint:
      return "zero_area_point";
    case PairClass::kCount:
      break;
  }
  return "?";
}

enum class Placement { kLattice, kLatticeFar, kRotated, kRotatedFar };

inline const char* placement_name(Placement p) {
  switch (p) {
    case Placement::kLattice:
      return "lattice";
    case Placement::kLatticeFar:
      return "lattice_far";
    case Placement::kRotated:
      return "rotated";
    case Placement::kRotatedFar:
      return "rotated_far";
  }
  return "?";
}

inline bool is_far(Placement p) {
  return p == Placement::kLatticeFar || p == Placement::kRotatedFar;
}
inline bool is_lattice(Placement p) {
  return p == Placement::kLattice || p == Placement::kLatticeFar;
}

struct AdversarialPair {
  Triangle t1, t2;
  PairClass cls = PairClass::kCoplanarOverlap;
  Placement placement = Placement::kLattice;
  int expected = -1;  // 1 intersect, 0 disjoint (known by construction), -1 unknown: CGAL decides
};

namespace detail {

inline constexpr std::int64_t kLattice = 1024;

// A fine offset 2^-k lattice steps, k in [0, 28].
inline double fine_step(Rng& rng) {
  return std::ldexp(1.0, -static_cast<int>(uniform_int(rng, 0, 28)));
}

inline double lattice_coordinate(Rng& rng, std::int64_t lo, std::int64_t hi) {
  return static_cast<double>(uniform_int(rng, lo, hi));
}

// A point of the lattice box [lo, hi]^2 x {z}, coordinates multiples of `mult`.
inline Vec3 lattice_point_2d(Rng& rng, std::int64_t lo, std::int64_t hi, std::int64_t mult,
                             double z) {
  const std::int64_t x = mult * uniform_int(rng, lo / mult, hi / mult);
  const std::int64_t y = mult * uniform_int(rng, lo / mult, hi / mult);
  return Vec3(static_cast<double>(x), static_cast<double>(y), z);
}

// Twice the signed area of the canonical triangle's xy projection (exact: small integers).
inline double area2_xy(const Vec3& a, const Vec3& b, const Vec3& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// A non-degenerate lattice triangle in the plane z = 0 within [lo, hi]^2, coordinates multiples of
// `mult` (mult = 6 makes the centroid and the edge midpoints lattice points too).
inline Triangle lattice_triangle_2d(Rng& rng, std::int64_t lo, std::int64_t hi, std::int64_t mult) {
  Triangle t;
  do {
    for (auto& v : t.v) v = lattice_point_2d(rng, lo, hi, mult, 0.0);
  } while (area2_xy(t.v[0], t.v[1], t.v[2]) == 0.0);
  return t;
}

inline Vec3 centroid(const Triangle& t) { return (t.v[0] + t.v[1] + t.v[2]) / 3.0; }

inline Vec3 lattice_point_3d(Rng& rng, std::int64_t lo, std::int64_t hi) {
  const double x = lattice_coordinate(rng, lo, hi);
  const double y = lattice_coordinate(rng, lo, hi);
  const double z = lattice_coordinate(rng, lo, hi);
  return Vec3(x, y, z);
}

// A point of closed triangle t that is a lattice point when t's coordinates are multiples of 6:
// a vertex, an edge midpoint or the centroid.
inline Vec3 special_point(Rng& rng, const Triangle& t) {
  const int which = static_cast<int>(uniform_int(rng, 0, 6));
  if (which < 3) return t.v[which];
  if (which < 6) return (t.v[which - 3] + t.v[(which - 2) % 3]) / 2.0;
  return centroid(t);
}

// The canonical pair of each class, in lattice units; `expected` as defined above.
struct CanonicalPair {
  Triangle t1, t2;
  int expected = -1;
  bool exact_only = false;  // the construction needs lattice placement to keep `expected`
};

inline CanonicalPair canonical_pair(PairClass cls, Rng& rng) {
  constexpr std::int64_t N = kLattice;
  CanonicalPair c;
  switch (cls) {
    case PairClass::kCoplanarOverlap: {
      c.t1 = lattice_triangle_2d(rng, 0, N, 6);
      const Vec3 inside = centroid(c.t1);
      do {
        c.t2 = Triangle{{inside, lattice_point_2d(rng, -N / 2, 3 * N / 2, 1, 0.0),
                         lattice_point_2d(rng, -N / 2, 3 * N / 2, 1, 0.0)}};
      } while (area2_xy(c.t2.v[0], c.t2.v[1], c.t2.v[2]) == 0.0);
      c.expected = 1;
      c.exact_only = true;
      break;
    }
    case PairClass::kCoplanarDisjoint: {
      // T1 in x <= a touching the line x = a, T2 in x >= a before it is moved away by the gap:
      // one lattice step or 2^-k of one.
      const std::int64_t a = uniform_int(rng, N / 4, 3 * N / 4);
      const auto side = [&](std::int64_t lo, std::int64_t hi) {
        Triangle t;
        do {
          t.v[0] = Vec3(static_cast<double>(a), lattice_coordinate(rng, 0, N), 0.0);
          for (int i = 1; i < 3; ++i) {
            const double x = lattice_coordinate(rng, lo, hi);
            const double y = lattice_coordinate(rng, 0, N);
            t.v[i] = Vec3(x, y, 0.0);
          }
        } while (area2_xy(t.v[0], t.v[1], t.v[2]) == 0.0);
        return t;
      };
      c.t1 = side(0, a);
      c.t2 = side(a, N);
      const double gap = uniform_int(rng, 0, 1) ? 1.0 : fine_step(rng);
      for (auto& v : c.t2.v) v[0] += gap;
      c.expected = 0;
      c.exact_only = true;
      break;
    }
    case PairClass::kSharedEdge: {
      c.t1 = lattice_triangle_2d(rng, 0, N, 1);
      const int i = static_cast<int>(uniform_int(rng, 0, 2));
      const Vec3 p = c.t1.v[i], q = c.t1.v[(i + 1) % 3];
      Vec3 s;
      const int where = static_cast<int>(uniform_int(rng, 0, 2));
      if (where == 0) {  // coplanar, anywhere (often on the other side)
        do s = lattice_point_2d(rng, -N / 2, 3 * N / 2, 1, 0.0);
        while (area2_xy(p, q, s) == 0.0);
      } else {  // off the plane
        s = lattice_point_3d(rng, -N / 2, 3 * N / 2);
        if (s[2] == 0.0) s[2] = 1.0;
      }
      c.t2 = uniform_int(rng, 0, 1) ? Triangle{{q, p, s}} : Triangle{{p, s, q}};
      c.expected = 1;
      break;
    }
    case PairClass::kSharedVertex: {
      c.t1 = lattice_triangle_2d(rng, 0, N, 1);
      const Vec3 p = c.t1.v[uniform_int(rng, 0, 2)];
      // The other two vertices on one side of T1's plane (touching at p only) or anywhere.
      const bool above = uniform_int(rng, 0, 1) == 1;
      Vec3 s = lattice_point_3d(rng, -N / 2, 3 * N / 2);
      Vec3 r = lattice_point_3d(rng, -N / 2, 3 * N / 2);
      if (above) {
        s[2] = std::abs(s[2]) + 1;
        r[2] = std::abs(r[2]) + 1;
      }
      c.t2 = Triangle{{s, p, r}};
      c.expected = 1;
      break;
    }
    case PairClass::kVertexOnFace:
    case PairClass::kVertexNearFace: {
      c.t1 = lattice_triangle_2d(rng, 0, N, 6);
      Vec3 p = special_point(rng, c.t1);
      Vec3 s = lattice_point_3d(rng, -N / 2, 3 * N / 2);
      Vec3 r = lattice_point_3d(rng, -N / 2, 3 * N / 2);
      const bool near = cls == PairClass::kVertexNearFace;
      if (near || uniform_int(rng, 0, 1)) {  // T2 above T1's plane, touching at p only
        s[2] = std::abs(s[2]) + 1;
        r[2] = std::abs(r[2]) + 1;
      }
      if (near) p[2] = fine_step(rng);
      c.t2 = Triangle{{p, s, r}};
      c.expected = near ? 0 : 1;
      c.exact_only = true;
      break;
    }
    case PairClass::kEdgeThroughEdge: {
      // T1's edge along x at (y0, z = 0), T1 below z = 0; T2's edge along y at (x0, z = 0), T2
      // above: they meet at (x0, y0, 0) only (or miss by a fine lift of T2).
      const std::int64_t x0 = uniform_int(rng, 1, N - 1), y0 = uniform_int(rng, 1, N - 1);
      const double xa = lattice_coordinate(rng, 0, x0 - 1);
      const double xb = lattice_coordinate(rng, x0 + 1, N);
      const double yc = lattice_coordinate(rng, 0, y0 - 1);
      const double yd = lattice_coordinate(rng, y0 + 1, N);
      const double r1x = lattice_coordinate(rng, 0, N);
      const double r1y = lattice_coordinate(rng, 0, N);
      const double r1z = -lattice_coordinate(rng, 1, N);
      const double r2x = lattice_coordinate(rng, 0, N);
      const double r2y = lattice_coordinate(rng, 0, N);
      const double r2z = lattice_coordinate(rng, 1, N);
      const Vec3 r1(r1x, r1y, r1z), r2(r2x, r2y, r2z);
      const double lift = uniform_int(rng, 0, 2) == 0 ? fine_step(rng) : 0.0;
      const double y = static_cast<double>(y0), x = static_cast<double>(x0);
      c.t1 = Triangle{{Vec3(xa, y, 0), Vec3(xb, y, 0), r1}};
      c.t2 = Triangle{{Vec3(x, yc, lift), Vec3(x, yd, lift), r2 + Vec3(0, 0, lift)}};
      c.expected = lift == 0.0 ? 1 : 0;
      c.exact_only = true;
      break;
    }
    case PairClass::kNearCoplanar: {
      // Lattice form: T2's vertices lifted by small multiples of 2^-k steps, a tilt of about
      // 2^-k / 1024 rad (1e-3 .. 4e-12). The rotated placement tilts by an angle instead.
      c.t1 = lattice_triangle_2d(rng, 0, N, 1);
      c.t2 = lattice_triangle_2d(rng, 0, N, 1);
      const double h = fine_step(rng);
      for (auto& v : c.t2.v) v[2] = h * static_cast<double>(uniform_int(rng, -4, 4));
      break;
    }
    case PairClass::kParallelPlanes: {
      c.t1 = lattice_triangle_2d(rng, 0, N, 6);
      const Vec3 inside = centroid(c.t1);
      do {
        c.t2 = Triangle{{inside, lattice_point_2d(rng, -N / 2, 3 * N / 2, 1, 0.0),
                         lattice_point_2d(rng, -N / 2, 3 * N / 2, 1, 0.0)}};
      } while (area2_xy(c.t2.v[0], c.t2.v[1], c.t2.v[2]) == 0.0);
      const double gap = uniform_int(rng, 0, 3) == 0 ? 1.0 : fine_step(rng);
      for (auto& v : c.t2.v) v[2] = gap;
      c.expected = 0;
      c.exact_only = true;
      break;
    }
    case PairClass::kSliver: {
      // T1: base along x across the lattice, apex 2^-10 steps off it (aspect ~1e6). T2: another
      // sliver or an ordinary triangle crossing T1's region, coplanar or not.
      const double thin = 0x1p-10;
      const double y1 = lattice_coordinate(rng, 0, N);
      c.t1 = Triangle{{Vec3(0, y1, 0), Vec3(static_cast<double>(N), y1, 0),
                       Vec3(lattice_coordinate(rng, 0, N), y1 + thin, 0)}};
      const double z =
          uniform_int(rng, 0, 1) ? 0.0 : thin * static_cast<double>(uniform_int(rng, -2, 2));
      if (uniform_int(rng, 0, 1)) {  // a crossing sliver along y
        const double x2 = lattice_coordinate(rng, 0, N);
        const double off = thin * static_cast<double>(uniform_int(rng, -3, 3));
        c.t2 = Triangle{{Vec3(x2, y1 - static_cast<double>(uniform_int(rng, 0, N)) + off, z),
                         Vec3(x2, y1 + static_cast<double>(uniform_int(rng, 0, N)) + off, -z),
                         Vec3(x2 + thin, y1 + off, z)}};
      } else {  // an ordinary triangle whose plane passes near T1
        const double dy[3] = {-lattice_coordinate(rng, 0, 8), thin * lattice_coordinate(rng, -2, 2),
                              lattice_coordinate(rng, 0, 8)};
        for (int i = 0; i < 3; ++i) {
          const double x = lattice_coordinate(rng, 0, N);
          const double zi = lattice_coordinate(rng, -N, N);
          c.t2.v[i] = Vec3(x, y1 + dy[i], zi);
        }
      }
      break;
    }
    case PairClass::kZeroAreaSegment: {
      // T1: p, p + d, p + 2d (or p, p + 2d, p: a repeated endpoint) in any order; T2 a lattice
      // triangle in z = 0. The segment passes through a special point of T2 (known:
      // intersecting), lies parallel to T2's plane 2^-k steps above it (known: disjoint), lies in
      // T2's plane, or is random.
      c.t2 = lattice_triangle_2d(rng, 0, N, 6);
      const int mode = static_cast<int>(uniform_int(rng, 0, 4));
      Vec3 d = lattice_point_3d(rng, -N / 4, N / 4);
      if (mode == 2 || mode == 3) d[2] = 0.0;
      if (d.isZero()) d = Vec3(1, 0, 0);
      Vec3 p;
      if (mode <= 1) {  // p + t d at t = 0, 1 or 2 lands on the special point
        const Vec3 on = special_point(rng, c.t2);
        p = on - d * static_cast<double>(uniform_int(rng, 0, 2));
        c.expected = 1;
      } else if (mode == 2) {
        p = lattice_point_2d(rng, -N / 2, 3 * N / 2, 1, 0.0);
        p[2] += fine_step(rng);
        c.expected = 0;
      } else if (mode == 3) {
        p = lattice_point_2d(rng, -N / 2, 3 * N / 2, 1, 0.0);
      } else {
        p = lattice_point_3d(rng, -N / 2, 3 * N / 2);
      }
      c.t1 = uniform_int(rng, 0, 3) == 0 ? Triangle{{p, p + 2 * d, p}}
                                         : Triangle{{p + d, p, p + 2 * d}};
      c.exact_only = true;
      break;
    }
    case PairClass::kZeroAreaPoint: {
      // T1: a point; T2 a triangle, a segment or a point. The point is a special point of T2,
      // lifted off by a fine step, or random.
      c.t2 = lattice_triangle_2d(rng, 0, N, 6);
      const int shape = static_cast<int>(uniform_int(rng, 0, 2));
      if (shape == 1) c.t2.v[2] = c.t2.v[0] + 2.0 * (c.t2.v[1] - c.t2.v[0]);  // segment
      if (shape == 2) c.t2.v[1] = c.t2.v[2] = c.t2.v[0];                      // point
      const int mode = static_cast<int>(uniform_int(rng, 0, 2));
      Vec3 p = mode == 2 ? lattice_point_3d(rng, 0, N) : special_point(rng, c.t2);
      if (shape == 2 && mode == 0) p = c.t2.v[0];
      c.expected = mode == 0 ? 1 : -1;
      if (mode == 1) {
        p[2] += fine_step(rng);
        c.expected = 0;
      }
      c.exact_only = true;
      c.t1 = Triangle{{p, p, p}};
      break;
    }
    case PairClass::kCount:
      break;
  }
  return c;
}

}  // namespace detail

// One adversarial pair of class `cls`, triangles about `size` metres across, placed as asked.
// The pair's order is randomised (T1 and T2 swapped half the time), and so are the vertex orders.
inline AdversarialPair make_adversarial(PairClass cls, Placement placement, double size, Rng& rng) {
  detail::CanonicalPair c = detail::canonical_pair(cls, rng);
  AdversarialPair out;
  out.cls = cls;
  out.placement = placement;
  out.expected = c.expected;
  const bool far = is_far(placement);

  std::array<Vec3, 6> points = {c.t1.v[0], c.t1.v[1], c.t1.v[2], c.t2.v[0], c.t2.v[1], c.t2.v[2]};
  if (is_lattice(placement)) {
    // Lattice placement: signed axis permutation, scale by a power of two, lattice translation.
    const int e = static_cast<int>(std::floor(std::log2(size))) -
                  static_cast<int>(std::log2(static_cast<double>(detail::kLattice)));
    std::array<int, 3> axis = {0, 1, 2};
    shuffle(axis, rng);
    Vec3 sign;
    for (int k = 0; k < 3; ++k) sign[k] = uniform_int(rng, 0, 1) ? 1.0 : -1.0;
    const std::int64_t reach = far ? 1000 * detail::kLattice : 4 * detail::kLattice;
    Vec3 origin;
    for (int k = 0; k < 3; ++k) {
      std::int64_t o = uniform_int(rng, -reach, reach);
      if (far && std::abs(o) < reach / 2) o += o < 0 ? -reach / 2 : reach / 2;
      origin[k] = static_cast<double>(o);
    }
    for (auto& p : points) {
      Vec3 q;
      for (int k = 0; k < 3; ++k) q[k] = std::ldexp(origin[k] + sign[k] * p[axis[k]], e);
      p = q;
    }
  } else {
    if (c.exact_only) out.expected = -1;
    const double step = size / static_cast<double>(detail::kLattice);
    Mat3 R = random_rotation(rng);
    if (cls == PairClass::kNearCoplanar) {
      // Tilt T2 about an in-plane axis through its centroid by 1e-9 .. 1e-3 rad, lattice z = 0.
      for (int i = 3; i < 6; ++i) points[i][2] = 0.0;
      const Vec3 pivot = (points[3] + points[4] + points[5]) / 3.0;
      const double phi = uniform(rng, 0, 2 * kPi);
      const Mat3 tilt =
          rotation_about(Vec3(std::cos(phi), std::sin(phi), 0), log_uniform(rng, 1e-9, 1e-3));
      for (int i = 3; i < 6; ++i) points[i] = pivot + tilt * (points[i] - pivot);
    }
    const double reach = far ? 1000 * size : 4 * size;
    Vec3 origin = random_in_cube(rng, Vec3::Zero(), reach);
    if (far) origin += reach * random_unit(rng);
    for (auto& p : points) p = origin + R * (step * p);
  }
  out.t1 = Triangle{{points[0], points[1], points[2]}};
  out.t2 = Triangle{{points[3], points[4], points[5]}};
  out.t1 = permuted(out.t1, static_cast<int>(uniform_int(rng, 0, 5)));
  out.t2 = permuted(out.t2, static_cast<int>(uniform_int(rng, 0, 5)));
  if (uniform_int(rng, 0, 1)) std::swap(out.t1, out.t2);
  return out;
}

}  // namespace graspcd::testing
