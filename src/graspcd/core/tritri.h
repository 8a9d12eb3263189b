// Triangle-triangle intersection tests. Triangles are closed sets: touching (a shared vertex or
// edge, a vertex on a face, coplanar contact) counts as intersecting. A zero-area triangle is the
// segment or point it spans. A triangle with a NaN or infinite coordinate is no set of points: the
// two exact tests answer false for it (and never enter exact arithmetic on it). Every test here
// answers exactly as CGAL would on the same doubles, except the two reference variants at the
// bottom, which are kept only to be measured.
#pragma once

#include "graspcd/core/geometry.h"

namespace graspcd {

// The project's test: Moller 1997 (paper section 6, eq. 6-9 with eq. 9's sign typo corrected),
// evaluated in floating point with a proven error bound on every decision; a decision inside its
// bound, a coplanar pair and a degenerate triangle are decided exactly by
// tri_tri_intersect_predicates.
bool tri_tri_intersect(const Triangle& t1, const Triangle& t2);

// The same answer; when it is "no" because one triangle lies strictly on one side of the other's
// plane (eq. 6-7), `gap` (metres) receives a lower bound on the distance between the two triangles:
// the nearest of that triangle's vertices' distances to the plane, each less its error bound and
// divided by an upper bound on the normal's length; otherwise (they intersect, or another test
// decided) 0. The tree query keeps it with a front's leaf pair (tree_query.h).
bool tri_tri_intersect(const Triangle& t1, const Triangle& t2, double& gap);

// A triangle's plane as the test above computes it (Moller 1997, eq. 6): N = (v1 - v0) x (v2 - v0)
// in floating point, with perm_k = |a_i b_j| + |a_j b_i| (a = v1 - v0, b = v2 - v0) bounding each
// component's rounding; `finite` says every coordinate is finite, `proper` (when finite) that N is
// exactly non-zero (decided exactly near zero). For triangles that are tested many times (a tree's,
// ObbTree::planes()), computed once.
struct TrianglePlane {
  Vec3 n = Vec3::Zero();
  Vec3 perm = Vec3::Zero();
  bool finite = false;
  bool proper = false;
};
TrianglePlane triangle_plane(const Triangle& t);

// tri_tri_intersect with t1's plane given (p1 = triangle_plane(t1)): the same answer and the same
// gap, bit for bit, without computing t1's plane again.
bool tri_tri_intersect(const Triangle& t1, const TrianglePlane& p1, const Triangle& t2);
bool tri_tri_intersect(const Triangle& t1, const TrianglePlane& p1, const Triangle& t2,
                       double& gap);

// An exact test built from orientation predicates only (predicates.h): each triangle is classified
// exactly as point, segment or triangle; non-coplanar triangles intersect iff an edge of one meets
// the other; coplanar ones are decided in a projection that preserves incidence. Slower; the
// fallback of tri_tri_intersect and an independent exact answer.
bool tri_tri_intersect_predicates(const Triangle& t1, const Triangle& t2);

// Moller's reference code as published: absolute epsilon tol::kNaiveMollerEpsilon on the
// unnormalised plane distances. Wrong at grasp scale; kept for the study's error sweep.
bool tri_tri_moller_naive(const Triangle& t1, const Triangle& t2);

// Moller with no epsilon at all, in plain floating point: misses touching pairs. Benchmark
// baseline.
bool tri_tri_moller_plain(const Triangle& t1, const Triangle& t2);

}  // namespace graspcd
