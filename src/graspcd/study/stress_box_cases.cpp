#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "graspcd/study/stress_cases.h"

namespace graspcd::study::stress_cases {

namespace {

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

}  // namespace

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

}  // namespace graspcd::study::stress_cases
