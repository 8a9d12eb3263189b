#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "graspcd/study/stress_cases.h"

namespace graspcd::study::stress_cases {

namespace {

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

// tri_scale, tri_far and tri_gap: a vertex on a face or crossing edges, randomly placed.
TrianglePairCase scale_far_or_gap_case(ClassId id, Rng& rng) {
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

// tri_parallel_edges: edges crossing at 1e-12..1e-3 rad.
TrianglePairCase parallel_edges_case(Rng& rng) {
  const double size = log_uniform(rng, 1e-2, 1e2);
  const double theta = signed_log_uniform(rng, 1e-12, 1e-3);
  const auto [t1, t2] = tri_edge_across_edge(rng, theta, signed_gap(rng, 1e-9, 1e-1));
  return place(random_placement(rng, size, size * uniform(rng, 0, 10)), t1, t2);
}

// tri_coplanar: a coplanar contact, or parallel planes at a tiny distance, placed exactly.
TrianglePairCase coplanar_case(Rng& rng) {
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

// tri_near_coplanar: planes 1e-12..1e-3 rad apart.
TrianglePairCase near_coplanar_case(Rng& rng) {
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

// tri_sliver: slivers of aspect 1e6 against fat triangles and each other.
TrianglePairCase sliver_case(Rng& rng) {
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

// tri_degenerate: segments and points (zero-area triangles) against triangles and segments.
TrianglePairCase degenerate_case(Rng& rng) {
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

}  // namespace

TrianglePairCase make_triangle_case(ClassId id, Rng& rng) {
  switch (id) {
    case kTriScale:
    case kTriFar:
    case kTriGap:
      return scale_far_or_gap_case(id, rng);
    case kTriParallelEdges:
      return parallel_edges_case(rng);
    case kTriCoplanar:
      return coplanar_case(rng);
    case kTriNearCoplanar:
      return near_coplanar_case(rng);
    case kTriSliver:
      return sliver_case(rng);
    case kTriDegenerate:
      return degenerate_case(rng);
    default:
      break;
  }
  throw std::logic_error("make_triangle_case: not a triangle class");
}

}  // namespace graspcd::study::stress_cases
