#include "graspcd/study/stress.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "graspcd/core/tolerances.h"
#include "graspcd/core/tritri.h"
#include "graspcd/exact/exact.h"
#include "graspcd/support/seeded.h"
#include "graspcd/version/envelope.h"

namespace graspcd::study {
namespace {

// The project's one seeded generator (graspcd/support/seeded.h): its draws are sequenced and
// its distributions written out, so the cases are the same on every compiler and standard library.
using seeded::chance;
using seeded::kPi;
using seeded::log_uniform;
using seeded::normal;
using seeded::random_rotation;
using seeded::random_sign;
using seeded::random_unit;
using seeded::Rng;
using seeded::rotation_about;
using seeded::uniform;
using seeded::uniform01;
using seeded::uniform_int;

// The signed gap of a case, as a fraction of its size: touching (0) one time in eight, else
// +-10^[log10 lo, log10 hi], each sign half the time.
double signed_gap(Rng& rng, double lo, double hi) {
  if (chance(rng, 0.125)) return 0.0;
  const double sign = random_sign(rng);
  return sign * log_uniform(rng, lo, hi);
}

// A signed angle, log-uniform in magnitude.
double signed_log_uniform(Rng& rng, double lo, double hi) {
  const double sign = random_sign(rng);
  return sign * log_uniform(rng, lo, hi);
}

// ---- The classes ------------------------------------------------------------------------------

enum ClassId {
  kBoxScale,
  kBoxFar,
  kBoxParallelFaces,
  kBoxParallelEdges,
  kBoxSliver,
  kBoxGap,
  kTriScale,
  kTriFar,
  kTriParallelEdges,
  kTriCoplanar,
  kTriNearCoplanar,
  kTriSliver,
  kTriDegenerate,
  kTriGap,
  kClassCount
};

const std::vector<StressClass> kClasses = {
    {"box_scale", StressKind::kBoxes,
     "sizes 1e-4..1e4 m near the origin; vertex-face or edge-edge contact, gap +-1e-9..1e-1 of "
     "the size or touching",
     15000},
    {"box_far", StressKind::kBoxes,
     "sizes 1e-4..1e4 m, 1e-3..1e5 m from the origin; contacts and gaps as box_scale", 15000},
    {"box_parallel_faces", StressKind::kBoxes,
     "face on face, B turned 1e-12..1e-3 rad from A's axes; gaps as box_scale", 10000},
    {"box_parallel_edges", StressKind::kBoxes,
     "edge across edge at 1e-12..1e-3 rad (separated only by their cross-product axis)", 20000},
    {"box_sliver", StressKind::kBoxes,
     "slivers and flat boxes: half-extents of aspect 1e6, some zero; contacts as box_scale", 10000},
    {"box_gap", StressKind::kBoxes,
     "size 0.1..10 m: touching, or gap/penetration +-1e-9..1e-6 of the size; vertex-face, "
     "edge-edge, parallel faces",
     15000},
    {"tri_scale", StressKind::kTriangles,
     "sizes 1e-4..1e4 m near the origin; vertex-face or edge-edge contact, gap +-1e-9..1e-1 or "
     "touching",
     200000},
    {"tri_far", StressKind::kTriangles,
     "sizes 1e-4..1e4 m, 1e-3..1e5 m from the origin; contacts and gaps as tri_scale", 200000},
    {"tri_parallel_edges", StressKind::kTriangles,
     "edge across edge at 1e-12..1e-3 rad, gaps as tri_scale", 200000},
    {"tri_coplanar", StressKind::kTriangles,
     "exactly coplanar (vertex or edge against an edge, in-plane gap) and parallel planes at a "
     "tiny distance",
     200000},
    {"tri_near_coplanar", StressKind::kTriangles,
     "planes 1e-12..1e-3 rad apart: in-plane contact tilted, or overlapping triangles crossing "
     "near their common centre",
     200000},
    {"tri_sliver", StressKind::kTriangles,
     "slivers of aspect 1e6: a vertex on a sliver, a needle on a face, crossing sliver edges",
     200000},
    {"tri_degenerate", StressKind::kTriangles,
     "zero-area triangles: repeated vertices and collinear points (segments), three equal "
     "vertices (points), against triangles and segments",
     200000},
    {"tri_gap", StressKind::kTriangles,
     "size 0.1..10 m: touching, or gap/penetration +-1e-9..1e-6 of the size", 200000},
};

// ---- Box pairs ----------------------------------------------------------------------------------

// Half-extents of a box of size `size` (its largest half-extent): each 0.2..1 of it, or for a
// sliver one or two of them 1e-6 of it (aspect 1e6) or zero (a flat box, a rectangle or a segment).
Vec3 box_halves(Rng& rng, double size, bool sliver) {
  const double h0 = size * uniform(rng, 0.2, 1.0);
  const double h1 = size * uniform(rng, 0.2, 1.0);
  Vec3 h(h0, h1, size);
  if (sliver) {
    const int thin = uniform_int(rng, 1, 2);
    for (int k = 0; k < thin; ++k) h[k] = chance(rng, 0.5) ? size * 1e-6 : 0.0;
  }
  // A random order of the axes, so the long one is not always the third.
  std::swap(h[2], h[uniform_int(rng, 0, 2)]);
  return h;
}

// B's offset from its centre to its lowest corner along n, or with `skip` (an axis of B
// perpendicular to n) to the midpoint of its lowest edge along that axis.
Vec3 lowest_feature_offset(const Mat3& axes, const Vec3& half, const Vec3& n, int skip = -1) {
  Vec3 o = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    if (j == skip) continue;
    const double s = axes.col(j).dot(n) > 0 ? -1.0 : 1.0;
    o += s * half[j] * axes.col(j);
  }
  return o;
}

// A vertex of B on a face of A, then B moved by g along the face's outer normal n: g > 0
// separates them along n, g < 0 pushes the vertex into A (overlap).
BoxPairCase box_vertex_on_face(Rng& rng, const Obb& a, const Mat3& b_axes, const Vec3& b_half,
                               double g) {
  const int i = uniform_int(rng, 0, 2);
  const Vec3 n = random_sign(rng) * a.axes.col(i);
  Vec3 p = a.center + a.half[i] * n;
  for (int k = 0; k < 3; ++k) {
    if (k != i) p += uniform(rng, -0.9, 0.9) * a.half[k] * a.axes.col(k);
  }
  BoxPairCase pair{a, Obb{Vec3::Zero(), b_axes, b_half}};
  pair.b.center = p + g * n - lowest_feature_offset(b_axes, b_half, n);
  return pair;
}

// An edge of B across an edge of A at the angle `theta`, the midpoints of both edges at one point
// p, then B moved by g along n, the bisector of the faces at A's edge: g > 0 separates them along
// n (the direction of A's edge x B's edge), g < 0 pushes B's edge into A. B is A turned by phi
// about A's edge (0.15..0.6 rad: B's lowest feature along n stays an edge), then by theta about n
// (which keeps that edge lowest).
BoxPairCase box_edge_across_edge(Rng& rng, const Obb& a, const Vec3& b_half, double theta,
                                 double g) {
  const int k = uniform_int(rng, 0, 2), i = (k + 1) % 3, j = (k + 2) % 3;
  const double si = random_sign(rng), sj = random_sign(rng);
  const Vec3 n = (si * a.axes.col(i) + sj * a.axes.col(j)).normalized();
  const Vec3 p = a.center + si * a.half[i] * a.axes.col(i) + sj * a.half[j] * a.axes.col(j) +
                 uniform(rng, -0.5, 0.5) * a.half[k] * a.axes.col(k);
  const double phi_sign = random_sign(rng);
  const double phi = phi_sign * uniform(rng, 0.15, 0.6);
  const Mat3 b_axes = rotation_about(n, theta) * rotation_about(a.axes.col(k), phi) * a.axes;
  BoxPairCase pair{a, Obb{Vec3::Zero(), b_axes, b_half}};
  pair.b.center = p + g * n - lowest_feature_offset(b_axes, b_half, n, k);
  return pair;
}

// A vertex-face or edge-edge contact (half each) between two randomly turned boxes.
BoxPairCase box_contact(Rng& rng, const Vec3& a_center, double size, bool sliver, double g_rel) {
  const Obb a{a_center, random_rotation(rng), box_halves(rng, size, sliver)};
  const Vec3 b_half = box_halves(rng, size * log_uniform(rng, 0.3, 3.0), sliver);
  const double g = g_rel * size;
  if (chance(rng, 0.5)) return box_vertex_on_face(rng, a, random_rotation(rng), b_half, g);
  return box_edge_across_edge(rng, a, b_half, uniform(rng, 0.05, kPi / 2), g);
}

BoxPairCase make_box_case(ClassId id, Rng& rng) {
  switch (id) {
    case kBoxScale: {
      const double size = log_uniform(rng, 1e-4, 1e4);
      const Vec3 centre = size * random_unit(rng);
      return box_contact(rng, centre, size, false, signed_gap(rng, 1e-9, 1e-1));
    }
    case kBoxFar: {
      const double size = log_uniform(rng, 1e-4, 1e4);
      const double distance = log_uniform(rng, 1e-3, 1e5);
      const Vec3 centre = distance * random_unit(rng);
      return box_contact(rng, centre, size, false, signed_gap(rng, 1e-9, 1e-1));
    }
    case kBoxParallelFaces: {
      const double size = log_uniform(rng, 1e-2, 1e2);
      const Obb a{size * random_unit(rng), random_rotation(rng), box_halves(rng, size, false)};
      const Vec3 turn_axis = random_unit(rng);
      const Mat3 b_axes = rotation_about(turn_axis, log_uniform(rng, 1e-12, 1e-3)) * a.axes;
      const Vec3 b_half = box_halves(rng, size, false);
      return box_vertex_on_face(rng, a, b_axes, b_half, signed_gap(rng, 1e-9, 1e-1) * size);
    }
    case kBoxParallelEdges: {
      const double size = log_uniform(rng, 1e-2, 1e2);
      const Obb a{size * random_unit(rng), random_rotation(rng), box_halves(rng, size, false)};
      const Vec3 b_half = box_halves(rng, size, false);
      const double theta = signed_log_uniform(rng, 1e-12, 1e-3);
      return box_edge_across_edge(rng, a, b_half, theta, signed_gap(rng, 1e-9, 1e-1) * size);
    }
    case kBoxSliver: {
      const double size = log_uniform(rng, 1e-2, 1e2);
      const Vec3 centre = size * random_unit(rng);
      return box_contact(rng, centre, size, true, signed_gap(rng, 1e-9, 1e-1));
    }
    case kBoxGap: {
      const double size = log_uniform(rng, 0.1, 10.0);
      const double g = signed_gap(rng, 1e-9, 1e-6) * size;
      const Obb a{size * random_unit(rng), random_rotation(rng), box_halves(rng, size, false)};
      const Vec3 b_half = box_halves(rng, size, false);
      switch (uniform_int(rng, 0, 2)) {
        case 0:
          return box_vertex_on_face(rng, a, random_rotation(rng), b_half, g);
        case 1:
          return box_edge_across_edge(rng, a, b_half, uniform(rng, 0.05, kPi / 2), g);
        default:
          return box_vertex_on_face(rng, a, a.axes, b_half, g);  // exactly parallel faces
      }
    }
    default:
      break;
  }
  throw std::logic_error("make_box_case: not a box class");
}

// ---- Triangle pairs ---------------------------------------------------------------------------
//
// Each pair is built in a canonical frame of size ~1 with its contact at or near the origin and the
// plane z = 0 as T1's plane, then placed: by a random rotation, a scale and a translation (the
// coordinates are rounded: near-degenerate), or by an "exact-plane" placement (a rotation about z,
// a power-of-two scale, a translation and a signed permutation of the axes) that keeps every
// plane z = const exactly planar, so that coplanar pairs stay coplanar in the doubles.

struct Placement {
  Mat3 R = Mat3::Identity();
  double scale = 1.0;
  Vec3 t = Vec3::Zero();
  std::array<int, 3> perm{0, 1, 2};  // the exact-plane placement's axis permutation
  Vec3 sign = Vec3::Ones();
};

Vec3 place(const Placement& pl, const Vec3& x) {
  const Vec3 y = pl.R * (pl.scale * x) + pl.t;
  return Vec3(pl.sign[0] * y[pl.perm[0]], pl.sign[1] * y[pl.perm[1]], pl.sign[2] * y[pl.perm[2]]);
}

TrianglePairCase place(const Placement& pl, const Triangle& t1, const Triangle& t2) {
  TrianglePairCase c;
  for (int k = 0; k < 3; ++k) {
    c.t1.v[k] = place(pl, t1.v[k]);
    c.t2.v[k] = place(pl, t2.v[k]);
  }
  return c;
}

Placement random_placement(Rng& rng, double size, double distance) {
  Placement pl;
  pl.R = random_rotation(rng);
  pl.scale = size;
  pl.t = distance * random_unit(rng);
  return pl;
}

Placement exact_plane_placement(Rng& rng, double size, double distance) {
  Placement pl;
  pl.R = rotation_about(Vec3::UnitZ(), uniform(rng, 0, 2 * kPi));
  pl.scale = std::ldexp(1.0, static_cast<int>(std::lround(std::log2(size))));
  pl.t = distance * random_unit(rng);
  pl.perm = {0, 1, 2};
  const int swap = uniform_int(rng, 0, 2);
  std::swap(pl.perm[swap], pl.perm[2]);
  for (int k = 0; k < 3; ++k) pl.sign[k] = random_sign(rng);
  return pl;
}

// A "fat" triangle in the plane z = `z` around (cx, cy): vertex i at angle 2 pi i / 3 + -0.4 rad
// and radius 0.5..1 times `r`, so the centre is well inside.
Triangle fat_triangle(Rng& rng, double cx, double cy, double r, double z = 0.0) {
  Triangle t;
  const double turn = uniform(rng, 0, 2 * kPi);
  for (int i = 0; i < 3; ++i) {
    const double angle = turn + 2 * kPi * i / 3 + uniform(rng, -0.4, 0.4);
    const double radius = r * uniform(rng, 0.5, 1.0);
    t.v[i] = Vec3(cx + radius * std::cos(angle), cy + radius * std::sin(angle), z);
  }
  return t;
}

// A point of t with barycentric weights of at least 0.1 / 1.3 each (well inside).
Vec3 inner_point(Rng& rng, const Triangle& t) {
  const double w0 = uniform(rng, 0.1, 1.0), w1 = uniform(rng, 0.1, 1.0),
               w2 = uniform(rng, 0.1, 1.0);
  return (w0 * t.v[0] + w1 * t.v[1] + w2 * t.v[2]) / (w0 + w1 + w2);
}

// A point above p (z 0.2..1 higher, up to 1 sideways).
Vec3 above(Rng& rng, const Vec3& p) {
  const double x = uniform(rng, -1, 1);
  const double y = uniform(rng, -1, 1);
  const double z = uniform(rng, 0.2, 1.0);
  return p + Vec3(x, y, z);
}

// Vertex on face: T1 in z = 0, T2's apex at p + g z for a point p inside T1, T2's other vertices
// above: g > 0 disjoint, g < 0 T2 pierces T1 near p.
std::pair<Triangle, Triangle> tri_vertex_on_face(Rng& rng, const Triangle& t1, double g) {
  const Vec3 p = inner_point(rng, t1) + Vec3(0, 0, g);
  return {t1, Triangle{{p, above(rng, p), above(rng, p)}}};
}

// Edge across edge: T1 in the plane y = 0 below its edge along x through the origin; T2 in the
// vertical plane at angle theta to it, above its edge, which is lifted by g. Both planes contain
// the z axis, where T1 spans [-h1', 0] and T2 [g, g + h2']: g > 0 disjoint, g < 0 intersecting.
// h1 and h2 are the heights of the third vertices (0: random in 0.3..1; 1e-6 makes a sliver).
std::pair<Triangle, Triangle> tri_edge_across_edge(Rng& rng, double theta, double g,
                                                   double h1 = 0.0, double h2 = 0.0) {
  if (h1 <= 0.0) h1 = uniform(rng, 0.3, 1.0);
  if (h2 <= 0.0) h2 = uniform(rng, 0.3, 1.0);
  const Vec3 u(std::cos(theta), std::sin(theta), 0.0);
  const Vec3 lift(0, 0, g);
  const Triangle t1{{Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(uniform(rng, -0.5, 0.5), 0, -h1)}};
  const Triangle t2{{lift - u, lift + u, lift + uniform(rng, -0.5, 0.5) * u + Vec3(0, 0, h2)}};
  return {t1, t2};
}

// Coplanar contact in z = 0: T1 in x <= 0 touching the line x = 0 with a vertex or an edge,
// T2 in x >= g with a vertex or an edge on x = g across from it. g > 0 disjoint; g < 0 T2's
// vertex or edge enters T1 (a vertex: T1's wedge at (0, y0) opens to -x).
std::pair<Triangle, Triangle> tri_coplanar_contact(Rng& rng, double g) {
  // A point (x0 + dx, y) with dx and y drawn in this order.
  const auto point = [&rng](double x0, double dx_lo, double dx_hi, double y_lo, double y_hi) {
    const double dx = uniform(rng, dx_lo, dx_hi);
    const double y = uniform(rng, y_lo, y_hi);
    return Vec3(x0 + dx, y, 0.0);
  };
  const double y0 = uniform(rng, -0.2, 0.2);
  Triangle t1, t2;
  if (chance(rng, 0.5)) {  // vertex against vertex (both wedges open away from x = 0)
    t1 = Triangle{{Vec3(0, y0, 0), point(0, -1, -0.3, y0 - 1, y0 - 0.3),
                   point(0, -1, -0.3, y0 + 0.3, y0 + 1)}};
    t2 = Triangle{{Vec3(g, y0, 0), point(g, 0.3, 1, -1, 1), point(g, 0.3, 1, -1, 1)}};
  } else {  // edge against edge, overlapping along y
    t1 = Triangle{{point(0, 0, 0, y0 - 1, y0 - 0.2), point(0, 0, 0, y0 + 0.2, y0 + 1),
                   point(0, -1, -0.3, -1, 1)}};
    t2 = Triangle{{point(g, 0, 0, y0 + 0.1, y0 + 1), point(g, 0, 0, y0 - 1, y0 - 0.1),
                   point(g, 0.3, 1, -1, 1)}};
  }
  return {t1, t2};
}

// The triangle turned by `angle` about the line through `pivot` along y.
Triangle tilted_about_y(const Triangle& t, const Vec3& pivot, double angle) {
  const Mat3 R = rotation_about(Vec3::UnitY(), angle);
  Triangle r;
  for (int k = 0; k < 3; ++k) r.v[k] = pivot + R * (t.v[k] - pivot);
  return r;
}

TrianglePairCase make_triangle_case(ClassId id, Rng& rng) {
  switch (id) {
    case kTriScale:
    case kTriFar:
    case kTriGap: {
      const bool gap_class = id == kTriGap;
      const double size = gap_class ? log_uniform(rng, 0.1, 10.0) : log_uniform(rng, 1e-4, 1e4);
      const double distance =
          id == kTriFar ? log_uniform(rng, 1e-3, 1e5) : size * uniform(rng, 0.0, 1.0);
      const double g = gap_class ? signed_gap(rng, 1e-9, 1e-6) : signed_gap(rng, 1e-9, 1e-1);
      const auto [t1, t2] = chance(rng, 0.5)
                                ? tri_vertex_on_face(rng, fat_triangle(rng, 0, 0, 1), g)
                                : tri_edge_across_edge(rng, uniform(rng, 0.05, kPi / 2), g);
      return place(random_placement(rng, size, distance), t1, t2);
    }
    case kTriParallelEdges: {
      const double size = log_uniform(rng, 1e-2, 1e2);
      const double theta = signed_log_uniform(rng, 1e-12, 1e-3);
      const auto [t1, t2] = tri_edge_across_edge(rng, theta, signed_gap(rng, 1e-9, 1e-1));
      return place(random_placement(rng, size, size * uniform(rng, 0, 10)), t1, t2);
    }
    case kTriCoplanar: {
      const double size = log_uniform(rng, 1e-4, 1e4);
      const Placement pl = exact_plane_placement(rng, size, size * log_uniform(rng, 1e-2, 1e3));
      if (chance(rng, 0.75)) {
        const auto [t1, t2] = tri_coplanar_contact(rng, signed_gap(rng, 1e-9, 1e-1));
        return place(pl, t1, t2);
      }
      // Parallel planes at a tiny distance (half the time none), overlapping in projection.
      const double dz = chance(rng, 0.5) ? 0.0 : signed_gap(rng, 1e-9, 1e-1);
      const Triangle t1 = fat_triangle(rng, 0, 0, 1);
      return place(pl, t1, fat_triangle(rng, 0.1, 0.1, 1, dz));
    }
    case kTriNearCoplanar: {
      const double size = log_uniform(rng, 1e-2, 1e2);
      const double angle = signed_log_uniform(rng, 1e-12, 1e-3);
      const Placement pl = random_placement(rng, size, size * uniform(rng, 0, 10));
      if (chance(rng, 0.5)) {
        // The coplanar contact with T2 tilted about its own contact line x = g: T2 rises (or
        // sinks) away from it; its contact vertex or edge stays in T1's plane.
        const double g = signed_gap(rng, 1e-9, 1e-1);
        const auto [t1, t2] = tri_coplanar_contact(rng, g);
        return place(pl, t1, tilted_about_y(t2, Vec3(g, 0, 0), angle));
      }
      // Two overlapping triangles, T2 tilted about a line through their common centre and shifted
      // by a fraction of what the tilt spans: the planes cross inside both, or just outside.
      const Triangle t1 = fat_triangle(rng, 0, 0, 1);
      const double dz_sign = random_sign(rng);
      const double dz = dz_sign * std::fabs(angle) * uniform(rng, 0.0, 2.0);
      const Triangle t2 = tilted_about_y(fat_triangle(rng, 0, 0, 1, dz), Vec3(0, 0, dz), angle);
      return place(pl, t1, t2);
    }
    case kTriSliver: {
      const double size = log_uniform(rng, 1e-2, 1e2);
      const double g = signed_gap(rng, 1e-9, 1e-1);
      const Placement pl = random_placement(rng, size, size * uniform(rng, 0, 10));
      const Triangle sliver{
          {Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0), Vec3(uniform(rng, -0.3, 0.3), 1e-6, 0)}};
      switch (uniform_int(rng, 0, 2)) {
        case 0: {  // a fat triangle's vertex on the sliver
          const auto [t1, t2] = tri_vertex_on_face(rng, sliver, g);
          return place(pl, t1, t2);
        }
        case 1: {  // a needle's tip on a fat triangle
          const Triangle fat = fat_triangle(rng, 0, 0, 1);
          const Vec3 tip = inner_point(rng, fat) + Vec3(0, 0, g);
          const Vec3 base = above(rng, tip);
          return place(pl, fat, Triangle{{tip, base, base + Vec3(1e-6, 0, 0)}});
        }
        default: {  // crossing sliver edges (heights 1e-6)
          const double theta = uniform(rng, 0.05, kPi / 2);
          const double h2 = chance(rng, 0.5) ? 1e-6 : 0.0;
          const auto [t1, t2] = tri_edge_across_edge(rng, theta, g, 1e-6, h2);
          return place(pl, t1, t2);
        }
      }
    }
    case kTriDegenerate: {
      const double size = log_uniform(rng, 1e-2, 1e2);
      const double distance = size * uniform(rng, 0, 10);
      const double g = signed_gap(rng, 1e-9, 1e-1);
      const Triangle fat = fat_triangle(rng, 0, 0, 1);
      const Vec3 p = inner_point(rng, fat) + Vec3(0, 0, g);
      switch (uniform_int(rng, 0, 3)) {
        case 0: {  // a repeated vertex: the segment from p to a point above (any placement)
          const Vec3 q = above(rng, p);
          return place(random_placement(rng, size, distance), Triangle{{p, p, q}}, fat);
        }
        case 1: {  // three collinear points on a vertical line (kept collinear by the placement)
          const double len = uniform(rng, 0.2, 1.0);
          const Triangle segment{
              {p + Vec3(0, 0, len), p + Vec3(0, 0, 0.5 * len), p}};  // middle point exact
          return place(exact_plane_placement(rng, size, distance), fat, segment);
        }
        case 2: {  // a point (three equal vertices) on or just off the triangle's plane
          const Vec3 q = chance(rng, 0.5) ? Vec3(p[0], p[1], 0.0) : p;
          return place(exact_plane_placement(rng, size, distance), Triangle{{q, q, q}}, fat);
        }
        default: {  // two segments (repeated vertices) crossing in the plane, or g apart
          const double a = uniform(rng, 0, kPi);
          const Vec3 d1(std::cos(a), std::sin(a), 0.0);
          const double b = a + kPi / 2 + uniform(rng, -1, 1);  // 0.57..2.57 rad across d1
          const Vec3 d2(std::cos(b), std::sin(b), 0.0);
          const Vec3 lift(0, 0, chance(rng, 0.5) ? 0.0 : g);
          const Triangle s1{{-d1, d1, d1}};
          const Triangle s2{{lift - 0.7 * d2, lift - 0.7 * d2, lift + d2}};
          return place(exact_plane_placement(rng, size, distance), s1, s2);
        }
      }
    }
    default:
      break;
  }
  throw std::logic_error("make_triangle_case: not a triangle class");
}

// Each class its own stream: splitmix64 of (seed, class) seeds the engine.
Rng class_rng(std::size_t index, std::uint64_t seed) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + (index + 1) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return Rng(z ^ (z >> 31));
}

ClassId class_id(std::size_t index, StressKind kind) {
  if (index >= kClasses.size() || kClasses[index].kind != kind) {
    throw std::invalid_argument("stress: class index out of range or of the other kind");
  }
  return static_cast<ClassId>(index);
}

// ---- Evaluation -------------------------------------------------------------------------------

// The pair's size for relative gaps: the scale kSatRelativeSlack multiplies.
double pair_size(const Obb& a, const Obb& b) {
  return a.half.sum() + b.half.sum() + (b.center - a.center).lpNorm<1>();
}

// The slack of sat.h as tolerances.h documents it: an axis separates only when its gap
// (unnormalised, metres times |L|) exceeds it.
double sat_slack(const Obb& a, const Obb& b) {
  return tol::kSatRelativeSlack * pair_size(a, b) +
         tol::kSatRoundoffFactor * (a.center.lpNorm<1>() + b.center.lpNorm<1>());
}

// True when the exact gap on each of the 15 SAT axes (unnormalised, as sat.cpp measures it) is
// at most sat_slack plus the rounding of the SAT's own arithmetic (kSatRoundoffFactor times the
// pair's size): a "may overlap" the documented slack explains.
bool within_sat_band(const Obb& a, const Obb& b) {
  const double band = sat_slack(a, b) + tol::kSatRoundoffFactor * pair_size(a, b);
  for (int axis = 1; axis <= 15; ++axis) {
    if (exact::sat_axis_gap(a, b, axis) > band) return false;
  }
  return true;
}

void run_box_class(std::size_t index, int count, std::uint64_t seed,
                   const std::vector<BoxMethod>& methods, std::vector<StressRow>& rows) {
  const std::vector<BoxPairCase> cases = make_box_cases(index, count, seed);
  std::vector<char> truth(cases.size());
  for (std::size_t c = 0; c < cases.size(); ++c) {
    truth[c] = exact::box_box_overlap(cases[c].a, cases[c].b);
  }
  // Per case, computed the first time a method needs it.
  std::vector<std::optional<double>> gap_rel(cases.size());
  std::vector<std::optional<bool>> in_band(cases.size());
  for (const BoxMethod& m : methods) {
    StressRow row;
    row.class_name = kClasses[index].name;
    row.kind = StressKind::kBoxes;
    row.method = m.name;
    row.reference = m.reference;
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const BoxPairCase& pair = cases[c];
      const BoxAnswer answer = m.test(pair.a, pair.b);
      ++row.cases;
      row.overlapping += truth[c];
      row.perceptron_capped += answer.capped;
      if (truth[c] && answer.disjoint) ++row.false_separated;
      if (truth[c] || answer.disjoint) continue;
      ++row.false_overlap;
      if (!gap_rel[c]) gap_rel[c] = exact::box_box_gap(pair.a, pair.b) / pair_size(pair.a, pair.b);
      row.max_false_overlap_gap_rel = std::max(row.max_false_overlap_gap_rel, *gap_rel[c]);
      if (m.sat_band) {
        if (!in_band[c]) in_band[c] = within_sat_band(pair.a, pair.b);
        if (!*in_band[c]) ++row.outside_band;
      }
    }
    rows.push_back(row);
  }
}

void run_triangle_class(std::size_t index, int count, std::uint64_t seed,
                        const std::vector<TriangleMethod>& methods, std::vector<StressRow>& rows) {
  const std::vector<TrianglePairCase> cases = make_triangle_cases(index, count, seed);
  std::vector<char> truth(cases.size());
  for (std::size_t c = 0; c < cases.size(); ++c) {
    truth[c] = exact::tri_tri_intersect(cases[c].t1, cases[c].t2);
  }
  for (const TriangleMethod& m : methods) {
    StressRow row;
    row.class_name = kClasses[index].name;
    row.kind = StressKind::kTriangles;
    row.method = m.name;
    row.reference = m.reference;
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const bool answer = m.intersect(cases[c].t1, cases[c].t2);
      ++row.cases;
      row.overlapping += truth[c];
      if (truth[c] && !answer) ++row.false_separated;
      if (!truth[c] && answer) ++row.false_overlap;
    }
    row.outside_band = row.false_overlap;  // the triangle tests are exact: no band
    rows.push_back(row);
  }
}

int cases_for(const StressClass& cls, const StressOptions& options) {
  if (options.cases > 0) return options.cases;
  return options.quick ? std::max(50, cls.default_cases / 50) : cls.default_cases;
}

std::string format_double(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

const std::vector<StressClass>& stress_classes() { return kClasses; }

std::vector<BoxPairCase> make_box_cases(std::size_t index, int count, std::uint64_t seed) {
  const ClassId id = class_id(index, StressKind::kBoxes);
  Rng rng = class_rng(index, seed);
  std::vector<BoxPairCase> cases;
  cases.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) cases.push_back(make_box_case(id, rng));
  return cases;
}

std::vector<TrianglePairCase> make_triangle_cases(std::size_t index, int count,
                                                  std::uint64_t seed) {
  const ClassId id = class_id(index, StressKind::kTriangles);
  Rng rng = class_rng(index, seed);
  std::vector<TrianglePairCase> cases;
  cases.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) cases.push_back(make_triangle_case(id, rng));
  return cases;
}

std::vector<BoxMethod> default_box_methods(const DetectorOptions& options) {
  std::vector<BoxMethod> methods;
  for (const Method m : all_methods()) {
    BoxMethod bm;
    bm.name = method_name(m);
    const bool neurosat = m == Method::kNeuroSat || m == Method::kNeuroSatSticky;
    bm.sat_band = m == Method::kSat || m == Method::kSatCached || neurosat;
    const int limit = neurosat ? options.switch_passes : options.cap;
    DetectorOptions fresh = options;
    fresh.cache_slots = 1;  // a fresh detector per case: no state to carry
    bm.test = [m, fresh, limit](const Obb& a, const Obb& b) {
      Detector detector(m, fresh);
      QueryCounters counters;
      BoxAnswer answer;
      answer.disjoint = detector.box_disjoint(a, b, counters);
      answer.capped =
          uses_perceptron(m) && counters.perceptron_passes >= static_cast<std::uint64_t>(limit);
      return answer;
    };
    methods.push_back(std::move(bm));
  }
  return methods;
}

std::vector<TriangleMethod> default_triangle_methods() {
  return {
      {"tri_tri_intersect",
       [](const Triangle& a, const Triangle& b) { return tri_tri_intersect(a, b); }},
      // tri_tri_intersect_predicates under its 0.1 label, so stress.json stays comparable.
      {"tri_tri_intersect_exact",
       [](const Triangle& a, const Triangle& b) { return tri_tri_intersect_predicates(a, b); }},
      {"moller_naive",
       [](const Triangle& a, const Triangle& b) { return tri_tri_moller_naive(a, b); }, true},
      {"moller_plain",
       [](const Triangle& a, const Triangle& b) { return tri_tri_moller_plain(a, b); }, true},
  };
}

bool StressReport::contract_broken() const {
  return std::any_of(rows.begin(), rows.end(), [](const StressRow& r) {
    return !r.reference && (r.false_separated > 0 || r.outside_band > 0);
  });
}

StressReport run_stress(const StressOptions& options,
                        const std::function<void(const std::string&)>& log) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<BoxMethod> box_methods =
      options.box_methods.empty() ? default_box_methods() : options.box_methods;
  const std::vector<TriangleMethod> triangle_methods =
      options.triangle_methods.empty() ? default_triangle_methods() : options.triangle_methods;
  StressReport report;
  report.seed = options.seed;
  report.quick = options.quick;
  for (const std::string& name : options.classes) {
    if (std::none_of(kClasses.begin(), kClasses.end(),
                     [&](const StressClass& cls) { return name == cls.name; })) {
      throw std::invalid_argument("stress: no class named '" + name + "'");
    }
  }
  for (std::size_t index = 0; index < kClasses.size(); ++index) {
    const StressClass& cls = kClasses[index];
    if (!options.classes.empty() && std::find(options.classes.begin(), options.classes.end(),
                                              cls.name) == options.classes.end()) {
      continue;
    }
    const int count = cases_for(cls, options);
    const auto class_start = std::chrono::steady_clock::now();
    if (cls.kind == StressKind::kBoxes) {
      run_box_class(index, count, options.seed, box_methods, report.rows);
    } else {
      run_triangle_class(index, count, options.seed, triangle_methods, report.rows);
    }
    if (log) {
      const std::chrono::duration<double> took = std::chrono::steady_clock::now() - class_start;
      log(std::string(cls.name) + ": " + std::to_string(count) + " cases, " +
          format_double(took.count()) + " s");
    }
  }
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  report.seconds = took.count();
  return report;
}

std::string stress_table(const StressReport& report) {
  const std::vector<std::string> header = {"class",
                                           "method",
                                           "cases",
                                           "overlapping",
                                           "false_separated",
                                           "false_overlap",
                                           "max_false_overlap_gap_rel",
                                           "outside_band",
                                           "perceptron_capped"};
  std::vector<std::vector<std::string>> lines = {header};
  for (const StressRow& r : report.rows) {
    const bool boxes = r.kind == StressKind::kBoxes;
    lines.push_back(
        {r.class_name, r.reference ? r.method + " (reference)" : r.method, std::to_string(r.cases),
         std::to_string(r.overlapping), std::to_string(r.false_separated),
         std::to_string(r.false_overlap), boxes ? format_double(r.max_false_overlap_gap_rel) : "-",
         std::to_string(r.outside_band), boxes ? std::to_string(r.perceptron_capped) : "-"});
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& line : lines) {
    for (std::size_t k = 0; k < line.size(); ++k) width[k] = std::max(width[k], line[k].size());
  }
  std::ostringstream out;
  for (const auto& line : lines) {
    for (std::size_t k = 0; k < line.size(); ++k) {
      // Names left-aligned, numbers right-aligned.
      const std::size_t pad = width[k] - line[k].size();
      if (k < 2) {
        out << line[k] << std::string(pad, ' ');
      } else {
        out << std::string(pad, ' ') << line[k];
      }
      out << (k + 1 < line.size() ? "  " : "\n");
    }
  }
  return out.str();
}

std::string stress_json(const StressReport& report) {
  using nlohmann::json;
  json classes = json::array();
  for (const StressClass& cls : kClasses) {
    classes.push_back({{"name", cls.name},
                       {"kind", cls.kind == StressKind::kBoxes ? "boxes" : "triangles"},
                       {"description", cls.description}});
  }
  json rows = json::array();
  for (const StressRow& r : report.rows) {
    const bool boxes = r.kind == StressKind::kBoxes;
    rows.push_back(
        {{"class", r.class_name},
         {"kind", boxes ? "boxes" : "triangles"},
         {"method", r.method},
         {"reference", r.reference},
         {"cases", r.cases},
         {"overlapping", r.overlapping},
         {"false_separated", r.false_separated},
         {"false_overlap", r.false_overlap},
         {"max_false_overlap_gap_rel", boxes ? json(r.max_false_overlap_gap_rel) : json(nullptr)},
         {"outside_band", r.outside_band},
         {"perceptron_capped", boxes ? json(r.perceptron_capped) : json(nullptr)}});
  }
  const json tolerances = {{"sat_relative_slack", tol::kSatRelativeSlack},
                           {"sat_roundoff_factor", tol::kSatRoundoffFactor},
                           {"perceptron_corner_factor", tol::kPerceptronCornerFactor},
                           {"perceptron_cap", tol::kPerceptronDefaultCap},
                           {"neurosat_switch", tol::kNeuroSatDefaultSwitch}};
  json j = {{"seed", report.seed},
            {"quick", report.quick},
            {"seconds", report.seconds},
            {"tolerances", tolerances},
            {"classes", classes},
            {"rows", rows},
            {"contract_broken", report.contract_broken()}};
  add_envelope(j);
  return j.dump(1) + "\n";
}

}  // namespace graspcd::study
