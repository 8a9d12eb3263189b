// The exact twin of the core, built on CGAL (the only translation unit of graspcd that includes
// it). Every routine decides its question exactly on the input doubles: CGAL's filtered exact
// predicates for the triangles, an interval filter with exact rational fallback for the boxes.
#include "graspcd/exact/exact.h"

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <CGAL/version.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <stdexcept>

namespace graspcd::exact {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using CgalTriangle = Kernel::Triangle_3;

Point to_point(const Vec3& p) { return Point(p[0], p[1], p[2]); }

// A triangle classified exactly by what it spans: a point (dim 0, p[0]), a segment (dim 1, between
// its extreme points p[0] and p[1]) or a proper triangle (dim 2, p[0..2]).
struct Simplex {
  int dim = 2;
  std::array<Point, 3> p;
};

Simplex classify(const Triangle& t) {
  Simplex s;
  s.p = {to_point(t.v[0]), to_point(t.v[1]), to_point(t.v[2])};
  if (!CGAL::collinear(s.p[0], s.p[1], s.p[2])) return s;
  // Three collinear points (possibly coincident): on a line the lexicographic order of points is
  // their order along the line, so its minimum and maximum are the segment's extreme points.
  const auto by_xyz = [](const Point& x, const Point& y) {
    return CGAL::compare_xyz(x, y) == CGAL::SMALLER;
  };
  const auto [lo, hi] = std::minmax_element(s.p.begin(), s.p.end(), by_xyz);
  const Point first = *lo;
  const Point last = *hi;
  s.p[0] = first;
  s.p[1] = last;
  s.dim = first == last ? 0 : 1;
  return s;
}

// Box arithmetic, written once for two number types: CGAL::Interval_nt (a certified enclosure, the
// filter) and CGAL::Exact_rational (exact: every double is a rational). Only +, -, * and abs are
// used, so the rational results are exact and the intervals contain them.
using Rational = CGAL::Exact_rational;
using Interval = CGAL::Interval_nt_advanced;  // needs CGAL::Protect_FPU_rounding around its use

template <class NT>
using NVec = std::array<NT, 3>;

template <class NT>
NVec<NT> convert(const Vec3& v) {
  return {NT(v[0]), NT(v[1]), NT(v[2])};
}

template <class NT>
NVec<NT> cross(const NVec<NT>& x, const NVec<NT>& y) {
  return {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
}

template <class NT>
NT dot(const NVec<NT>& x, const NVec<NT>& y) {
  return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

bool is_zero(const NVec<Rational>& x) {
  return CGAL::is_zero(x[0]) && CGAL::is_zero(x[1]) && CGAL::is_zero(x[2]);
}

// A box as a centre and three generators g_i = half_i * axis_i (the column scaled by its
// half-extent): the box is {c + sum_i u_i g_i : |u_i| <= 1}.
template <class NT>
struct NBox {
  NVec<NT> center;
  std::array<NVec<NT>, 3> axis;       // the columns as given
  std::array<NVec<NT>, 3> generator;  // half_i * axis_i
};

template <class NT>
NBox<NT> convert(const Obb& box) {
  NBox<NT> r;
  r.center = convert<NT>(box.center);
  for (int i = 0; i < 3; ++i) {
    r.axis[i] = convert<NT>(Vec3(box.axes.col(i)));
    const NT h(box.half[i]);
    r.generator[i] = {r.axis[i][0] * h, r.axis[i][1] * h, r.axis[i][2] * h};
  }
  return r;
}

// The gap between the projections of the boxes on the line spanned by L (unnormalised):
// |(cB - cA) . L| - sum_i |gA_i . L| - sum_j |gB_j . L|. Positive iff L separates them strictly.
template <class NT>
NT projection_gap(const NBox<NT>& a, const NBox<NT>& b, const NVec<NT>& L) {
  const NVec<NT> d = {b.center[0] - a.center[0], b.center[1] - a.center[1],
                      b.center[2] - a.center[2]};
  NT gap = CGAL::abs(dot(d, L));
  for (int i = 0; i < 3; ++i) {
    gap -= CGAL::abs(dot(a.generator[i], L));
    gap -= CGAL::abs(dot(b.generator[i], L));
  }
  return gap;
}

// The 15 candidate axes of the separating axis theorem for two parallelepipeds: A's face normals
// A_i x A_j, B's face normals B_i x B_j, and the edge-edge directions A_i x B_j.
template <class NT>
std::array<NVec<NT>, 15> candidate_axes(const NBox<NT>& a, const NBox<NT>& b) {
  std::array<NVec<NT>, 15> axes;
  for (int i = 0; i < 3; ++i) {
    axes[i] = cross(a.axis[(i + 1) % 3], a.axis[(i + 2) % 3]);
    axes[3 + i] = cross(b.axis[(i + 1) % 3], b.axis[(i + 2) % 3]);
    for (int j = 0; j < 3; ++j) axes[6 + 3 * i + j] = cross(a.axis[i], b.axis[j]);
  }
  return axes;
}

// A triangle's axis-aligned bounding box. Exact: min and max of doubles are not rounded.
CGAL::Bbox_3 bounding_box(const Triangle& t) {
  const Vec3 lo = t.v[0].cwiseMin(t.v[1]).cwiseMin(t.v[2]);
  const Vec3 hi = t.v[0].cwiseMax(t.v[1]).cwiseMax(t.v[2]);
  return CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
}

}  // namespace

// CGAL's exact do_intersect (Epick: interval filter, exact fallback) between the simplices the two
// triangles span. CGAL's Triangle_3/Triangle_3 test (Guigue-Devillers 2003) needs proper triangles,
// so each input is first classified exactly as point, segment or triangle, and the pair goes to
// the matching overload; all of them treat their operands as closed sets.
bool tri_tri_intersect(const Triangle& a, const Triangle& b) {
  const Simplex s = classify(a);
  const Simplex t = classify(b);
  // Order the pair by dimension so that only six combinations remain.
  const Simplex& lo = s.dim <= t.dim ? s : t;
  const Simplex& hi = s.dim <= t.dim ? t : s;
  switch (lo.dim * 3 + hi.dim) {
    case 0:  // point, point
      return lo.p[0] == hi.p[0];
    case 1:  // point, segment
      return CGAL::do_intersect(lo.p[0], Segment(hi.p[0], hi.p[1]));
    case 2:  // point, triangle
      return CGAL::do_intersect(lo.p[0], CgalTriangle(hi.p[0], hi.p[1], hi.p[2]));
    case 4:  // segment, segment
      return CGAL::do_intersect(Segment(lo.p[0], lo.p[1]), Segment(hi.p[0], hi.p[1]));
    case 5:  // segment, triangle
      return CGAL::do_intersect(Segment(lo.p[0], lo.p[1]), CgalTriangle(hi.p[0], hi.p[1], hi.p[2]));
    case 8:  // triangle, triangle
      return CGAL::do_intersect(CgalTriangle(lo.p[0], lo.p[1], lo.p[2]),
                                CgalTriangle(hi.p[0], hi.p[1], hi.p[2]));
    default:
      throw std::logic_error("exact::tri_tri_intersect: impossible dimension pair");
  }
}

// CGAL::orientation(p, q, r, s): the sign of det[q-p; r-p; s-p], POSITIVE for the right-handed
// tetrahedron (0, e_x, e_y, e_z) (checked in tests/exact/exact_test.cpp).
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return static_cast<int>(CGAL::orientation(to_point(a), to_point(b), to_point(c), to_point(d)));
}

// The separating axis theorem for convex polytopes, decided exactly on the doubles as given: an
// interval filter (CGAL::Interval_nt) and exact rational arithmetic where it cannot decide.
//
// Why the 15 axes suffice, for any linearly independent columns and any half-extents >= 0: the
// boxes are disjoint iff 0 is not in B - A = (cB - cA) + Z, where Z is the zonotope with the six
// generators gA_i, gB_j. The boxes are disjoint iff some direction L has
// f(L) = d . L - sum_k |g_k . L| > 0 (d = cB - cA; L and -L give the |d . L| of the test). f is
// linear on each cell of the arrangement of the six planes {L : axis_k . L = 0} (the columns as
// given, zero extents included, whose normals span R^3), and each cell is a pointed polyhedral
// cone generated by its extreme rays, which lie on two of the planes: they are cross products of
// two columns. A linear function positive somewhere on a cone is positive on one of its extreme
// rays, so if any L separates, one of the 15 cross products does (a zero cross product is no ray:
// its gap is 0 and it never separates). Closed boxes: only a strict gap separates.
bool box_box_overlap(const Obb& a, const Obb& b) {
  // Filter: each axis' gap in interval arithmetic. A gap certainly positive separates; a gap
  // certainly <= 0 rules its axis out; only the undecided axes are evaluated exactly.
  std::array<bool, 15> undecided{};
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const NBox<Interval> ia = convert<Interval>(a);
    const NBox<Interval> ib = convert<Interval>(b);
    const std::array<NVec<Interval>, 15> axes = candidate_axes(ia, ib);
    for (int k = 0; k < 15; ++k) {
      const Interval gap = projection_gap(ia, ib, axes[k]);
      if (gap.inf() > 0) return false;
      undecided[k] = !(gap.sup() <= 0);
    }
  }
  if (std::none_of(undecided.begin(), undecided.end(), [](bool u) { return u; })) return true;
  // Exact rational arithmetic for the undecided axes.
  const NBox<Rational> ra = convert<Rational>(a);
  const NBox<Rational> rb = convert<Rational>(b);
  const std::array<NVec<Rational>, 15> axes = candidate_axes(ra, rb);
  for (int k = 0; k < 15; ++k) {
    if (undecided[k] && CGAL::is_positive(projection_gap(ra, rb, axes[k]))) return false;
  }
  return true;
}

// One SAT axis (sat.h numbering), taken as given, its gap evaluated exactly and rounded once.
double sat_axis_gap(const Obb& a, const Obb& b, int sat_axis) {
  if (sat_axis < 1 || sat_axis > 15) {
    throw std::invalid_argument("exact::sat_axis_gap: axis must be in 1..15");
  }
  const NBox<Rational> ra = convert<Rational>(a);
  const NBox<Rational> rb = convert<Rational>(b);
  NVec<Rational> L;
  if (sat_axis <= 3) {
    L = ra.axis[sat_axis - 1];
  } else if (sat_axis <= 6) {
    L = rb.axis[sat_axis - 4];
  } else {
    L = cross(ra.axis[(sat_axis - 7) / 3], rb.axis[(sat_axis - 7) % 3]);
  }
  if (is_zero(L)) return 0.0;
  return CGAL::to_double(projection_gap(ra, rb, L));
}

// The SAT candidate axes of box_box_overlap, each gap divided by |L| in floating point. The
// normalised gap on any direction is a lower bound of the distance between two convex sets.
double box_box_gap(const Obb& a, const Obb& b) {
  const NBox<Rational> ra = convert<Rational>(a);
  const NBox<Rational> rb = convert<Rational>(b);
  double best = -std::numeric_limits<double>::infinity();
  for (const NVec<Rational>& L : candidate_axes(ra, rb)) {
    if (is_zero(L)) continue;
    const double length = std::sqrt(CGAL::to_double(dot(L, L)));
    if (!(length > 0)) continue;  // |L|^2 underflowed: no usable direction
    best = std::max(best, CGAL::to_double(projection_gap(ra, rb, L)) / length);
  }
  return best;
}

bool plane_keeps_apart(const Triangle& t, const Triangle& u, double gap) {
  const NVec<Rational> u0 = convert<Rational>(u.v[0]);
  const NVec<Rational> e1 = convert<Rational>(u.v[1]), e2 = convert<Rational>(u.v[2]);
  const NVec<Rational> n = cross(NVec<Rational>{e1[0] - u0[0], e1[1] - u0[1], e1[2] - u0[2]},
                                 NVec<Rational>{e2[0] - u0[0], e2[1] - u0[1], e2[2] - u0[2]});
  if (is_zero(n)) return false;
  const Rational g(gap), nn = dot(n, n);
  int side = 0;
  for (const Vec3& v : t.v) {
    const NVec<Rational> x = convert<Rational>(v);
    const Rational d = dot(n, NVec<Rational>{x[0] - u0[0], x[1] - u0[1], x[2] - u0[2]});
    const int s = CGAL::sign(d);
    if (s == 0 || (side != 0 && s != side)) return false;
    side = s;
    if (g * g * nn > d * d) return false;
  }
  return true;
}

// Candidate pairs from CGAL::box_intersection_d (Zomorodian and Edelsbrunner 2000: streamed
// segment tree over the triangles' axis-aligned boxes, closed topology so touching boxes are
// reported), each decided by tri_tri_intersect. Bounding boxes of doubles are exact, so no
// intersecting pair is lost. Before the segment tree, each soup keeps only the triangles whose box
// meets the other soup's whole box (closed): a box that misses the whole misses every box in it,
// so the candidates are the same, and a pose where the soups meet in a small region sorts a few
// boxes instead of every triangle's.
std::vector<TrianglePair> mesh_mesh_pairs(const std::vector<Triangle>& a,
                                          const std::vector<Triangle>& b, bool first_contact) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::int32_t>;
  const auto boxes_of = [](const std::vector<Triangle>& soup, CGAL::Bbox_3& whole) {
    std::vector<CGAL::Bbox_3> boxes;
    boxes.reserve(soup.size());
    for (const Triangle& t : soup) {
      boxes.push_back(bounding_box(t));
      whole += boxes.back();
    }
    return boxes;
  };
  CGAL::Bbox_3 whole_a, whole_b;  // empty (+inf, -inf) until a box is added
  const std::vector<CGAL::Bbox_3> all_a = boxes_of(a, whole_a);
  const std::vector<CGAL::Bbox_3> all_b = boxes_of(b, whole_b);
  const auto meets = [](const CGAL::Bbox_3& x, const CGAL::Bbox_3& y) {
    for (int k = 0; k < 3; ++k) {
      if (x.max(k) < y.min(k) || y.max(k) < x.min(k)) return false;
    }
    return true;
  };
  std::vector<Box> boxes_a;
  std::vector<Box> boxes_b;
  for (std::size_t i = 0; i < all_a.size(); ++i) {
    if (meets(all_a[i], whole_b)) boxes_a.emplace_back(all_a[i], static_cast<std::int32_t>(i));
  }
  for (std::size_t j = 0; j < all_b.size(); ++j) {
    if (meets(all_b[j], whole_a)) boxes_b.emplace_back(all_b[j], static_cast<std::int32_t>(j));
  }
  if (boxes_a.empty() || boxes_b.empty()) return {};

  // box_intersection_d cannot be stopped from its callback except by an exception.
  struct FirstContactFound {};
  std::vector<TrianglePair> pairs;
  const auto test_pair = [&](const Box& x, const Box& y) {
    if (!exact::tri_tri_intersect(a[x.info()], b[y.info()])) return;
    pairs.push_back({x.info(), y.info()});
    if (first_contact) throw FirstContactFound{};
  };
  try {
    CGAL::box_intersection_d(boxes_a.begin(), boxes_a.end(), boxes_b.begin(), boxes_b.end(),
                             test_pair, std::ptrdiff_t{10}, CGAL::Box_intersection_d::CLOSED,
                             CGAL::Box_intersection_d::BIPARTITE);
  } catch (const FirstContactFound&) {
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Exact: the smallest value of w.x + d over A's corners is w.cA + d - sum_i |w.gA_i|, the largest
// over B's is w.cB + d + sum_i |w.gB_i|; the plane separates strictly iff the first is > 0 and the
// second < 0.
bool plane_separates_boxes(const Vec3& w, double d, const Obb& a, const Obb& b) {
  const NVec<Rational> rw = convert<Rational>(w);
  const Rational rd(d);
  const NBox<Rational> ra = convert<Rational>(a), rb = convert<Rational>(b);
  Rational a_min = dot(rw, ra.center) + rd, b_max = dot(rw, rb.center) + rd;
  for (int i = 0; i < 3; ++i) {
    a_min -= CGAL::abs(dot(rw, ra.generator[i]));
    b_max += CGAL::abs(dot(rw, rb.generator[i]));
  }
  return CGAL::is_positive(a_min) && CGAL::is_negative(b_max);
}

const char* cgal_version() { return CGAL_VERSION_STR; }

// The soup welded by exact coordinates (std::map on CGAL's lexicographic order of the points),
// oriented and converted by CGAL's polygon-soup routines (orient_polygon_soup duplicates the
// vertices where the surface is not a manifold, so the conversion succeeds for every edge-manifold
// soup), then CGAL::Side_of_triangle_mesh, whose predicates (Epick) are exact.
std::vector<int> side_of_closed_mesh(const std::vector<Triangle>& triangles,
                                     const std::vector<Vec3>& points) {
  using Mesh = CGAL::Surface_mesh<Point>;
  std::vector<Point> vertices;
  std::vector<std::array<std::size_t, 3>> polygons;
  std::map<Point, std::size_t> index;
  const auto id = [&](const Vec3& v) {
    const Point p = to_point(v);
    const auto [it, added] = index.emplace(p, vertices.size());
    if (added) vertices.push_back(p);
    return it->second;
  };
  for (const Triangle& t : triangles) {
    const std::array<std::size_t, 3> f{id(t.v[0]), id(t.v[1]), id(t.v[2])};
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) continue;
    polygons.push_back(f);
  }
  namespace PMP = CGAL::Polygon_mesh_processing;
  PMP::orient_polygon_soup(vertices, polygons);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(vertices, polygons, mesh);
  if (mesh.is_empty() || !CGAL::is_closed(mesh) || !CGAL::is_triangle_mesh(mesh)) {
    throw std::invalid_argument("exact::side_of_closed_mesh: not a closed triangle mesh");
  }
  const CGAL::Side_of_triangle_mesh<Mesh, Kernel> side(mesh);
  std::vector<int> sides;
  sides.reserve(points.size());
  for (const Vec3& p : points) {
    switch (side(to_point(p))) {
      case CGAL::ON_BOUNDED_SIDE:
        sides.push_back(1);
        break;
      case CGAL::ON_BOUNDARY:
        sides.push_back(0);
        break;
      case CGAL::ON_UNBOUNDED_SIDE:
        sides.push_back(-1);
        break;
    }
  }
  return sides;
}

bool point_inside_closed_mesh(const std::vector<Triangle>& triangles, const Vec3& point) {
  return side_of_closed_mesh(triangles, {point}).front() >= 0;
}

}  // namespace graspcd::exact
