// The exact twin of the core: CGAL decides the same questions the core's fast routines answer, on
// the same doubles, with the same signatures, so tests and `--exact` can swap them. This header
// does not include CGAL; CGAL is reached from exact.cpp alone (docs/design.md, "Layers").
#pragma once

#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb.h"
#include "graspcd/core/tree_query.h"

namespace graspcd::exact {

// True when the closed triangles intersect (touching counts). A zero-area triangle is the segment
// or point it spans. Same signature as graspcd::tri_tri_intersect (core/tritri.h).
bool tri_tri_intersect(const Triangle& a, const Triangle& b);

// Sign (-1, 0, +1) of det[b-a; c-a; d-a]: +1 when d lies on the side of plane abc that
// (b-a) x (c-a) points to. Same convention as graspcd::predicates::orient3d.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// True when the closed boxes c + axes diag(half) u, |u|_inf <= 1, overlap, decided exactly from
// the doubles as given: the columns of `axes` need not be orthonormal (only linearly independent)
// and half-extents may be zero.
bool box_box_overlap(const Obb& a, const Obb& b);

// The gap between the projections of the two boxes on one of the 15 axes of sat.h (1-3: A's
// columns, 4-6: B's columns, 7 + 3 i + j: A_i x B_j), the axis taken as given, unnormalised:
// |(cB - cA) . L| - sum_i hA_i |A_i . L| - sum_j hB_j |B_j . L|. Computed exactly, rounded to
// double once at the end, so its sign is exact: positive iff this axis separates the boxes.
// Units: metres times |L|. Returns 0 for a zero axis (parallel columns).
double sat_axis_gap(const Obb& a, const Obb& b, int sat_axis);

// The largest gap between the boxes' projections over the candidate axes of box_box_overlap,
// each axis normalised to unit length (rounded once per axis): positive iff the boxes are
// disjoint (exact sign), and never more than their Euclidean distance (metres).
double box_box_gap(const Obb& a, const Obb& b);

// True when every vertex of t lies strictly on one side of the plane of u (a proper triangle) and
// at a distance of at least `gap` (metres) from it: then the triangles lie at least `gap` apart.
// Decided exactly (gap^2 |N|^2 <= (N . (x - u0))^2 in rationals, N = (u1 - u0) x (u2 - u0)).
bool plane_keeps_apart(const Triangle& t, const Triangle& u, double gap);

// Every intersecting pair (index in a, index in b) of two triangle soups, sorted ascending; with
// first_contact, at most one pair (any). Brute force over the candidate pairs whose bounding boxes
// meet, each decided by tri_tri_intersect above: the ground truth for the tree queries.
std::vector<TrianglePair> mesh_mesh_pairs(const std::vector<Triangle>& a,
                                          const std::vector<Triangle>& b,
                                          bool first_contact = false);

// True when the plane {x : w.x + d = 0} strictly separates the closed boxes, A on the side
// w.x + d > 0 and B on w.x + d < 0, decided exactly on the doubles as given. Checks the
// perceptron's proofs (core/perceptron.h).
bool plane_separates_boxes(const Vec3& w, double d, const Obb& a, const Obb& b);

// The CGAL version this module was compiled against, e.g. "5.5.1".
const char* cgal_version();

// Where each point lies relative to the solid bounded by the closed triangle soup `triangles`:
// +1 inside (CGAL::ON_BOUNDED_SIDE), 0 on the surface (ON_BOUNDARY), -1 outside. The judge of
// core/containment.h's point_side: CGAL::Side_of_triangle_mesh (ray shooting on an AABB tree with
// Epick's exact predicates; a ray through an edge or a vertex is replaced by a random one) on a
// Surface_mesh built from the soup with vertices welded by exact coordinates; faces with two equal
// vertices are dropped. Inside means an odd number of crossings, as in the core. Throws
// std::invalid_argument when the welded soup is not a closed triangle mesh for CGAL.
std::vector<int> side_of_closed_mesh(const std::vector<Triangle>& triangles,
                                     const std::vector<Vec3>& points);

// side_of_closed_mesh(triangles, {point})[0] >= 0: inside or on the surface (the solid is closed).
// Builds CGAL's mesh and tree per call: use side_of_closed_mesh for many points.
bool point_inside_closed_mesh(const std::vector<Triangle>& triangles, const Vec3& point);

}  // namespace graspcd::exact
