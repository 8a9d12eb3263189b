// Containment: whether a triangle mesh is closed, whether a point lies in the solid a closed mesh
// bounds, and whether one mesh lies wholly inside another's solid.
//
// docs/design.md, "Semantics": mesh collision is surface intersection, so a mesh wholly inside a
// closed mesh does not collide with it; this module is the separate, separately reported
// containment check. Every answer is exact on the input doubles (Shewchuk's predicates,
// core/predicates.h, and a symbolic perturbation): no tolerance decides an answer; the one slack
// used here (culling the tree's boxes, see point_side) only adds work, never changes a result.
//
// Definitions (all on the doubles as given, after apply_pose where a pose places a mesh):
//  - Welding: two vertices are the same vertex when their coordinates compare equal (==; so -0.0
//    and 0.0 weld). Coordinates must be finite.
//  - Closed: at least one face with three distinct welded vertices, and every undirected edge of
//    such faces used by exactly two faces that traverse it in opposite directions. A face with two
//    equal welded vertices ("collapsed": it spans a segment or a point) has no edges of its own
//    and is ignored by this test; it is counted and still part of the surface everywhere else.
//  - The solid of a closed mesh: the points from which a ray to infinity in general position
//    crosses the surface an odd number of times (the parity rule; CGAL's Side_of_triangle_mesh
//    uses the same), together with the surface itself: the solid is a closed set, so a point ON
//    the surface (on a face, an edge or a vertex) is inside. For a closed mesh without
//    self-intersections this is the bounded region the surface encloses; nested shells alternate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb_tree.h"

namespace graspcd {

// The edge structure of a triangle mesh after welding. Counts, so that callers can print why a
// mesh is not closed (describe()).
struct Closedness {
  std::size_t faces = 0;               // faces examined
  std::size_t collapsed_faces = 0;     // faces with two equal welded vertices (ignored by closed())
  std::size_t vertices = 0;            // distinct welded vertices used by the faces
  std::size_t edges = 0;               // distinct undirected edges of the non-collapsed faces
  std::size_t boundary_edges = 0;      // used by one face
  std::size_t non_manifold_edges = 0;  // used by three or more faces
  std::size_t misoriented_edges = 0;   // used by two faces traversing it in the same direction
  // One face per connected component of the surface (faces linked through shared welded vertices,
  // collapsed faces included), the smallest face index of each, ascending. Indices refer to the
  // input of closedness(): the mesh's faces, the triangle vector, or tree.triangles().
  std::vector<std::int32_t> component_faces;

  bool closed() const {
    return faces > collapsed_faces && boundary_edges == 0 && non_manifold_edges == 0 &&
           misoriented_edges == 0;
  }
  // One line: "closed (F faces, V vertices, E edges, C components)" or "not closed: 3 boundary
  // edges, 1 non-manifold edge, ..." naming every non-zero count.
  std::string describe() const;
};

// The closedness of a mesh, a triangle soup, or the triangles of a tree (tree.triangles(), in
// leaf order, so component_faces index tree.triangles()). O(n log n) in the number of faces.
Closedness closedness(const TriangleMesh& mesh);
Closedness closedness(const std::vector<Triangle>& triangles);
Closedness closedness(const ObbTree& tree);

enum class PointSide { kOutside, kOnSurface, kInside };

const char* point_side_name(PointSide side);

// The ray p + t * sign * e_axis, t >= 0, along which point_side counts crossings. axis -1: chosen
// per query (the axis and sign along which p lies farthest from the root box's centre, so the ray
// leaves the mesh soon). Every choice gives the same answer; only the work differs.
struct RayDirection {
  int axis = -1;  // 0, 1, 2, or -1 for automatic
  int sign = 1;   // +1 or -1
};

// Work done by point_side queries; summed over calls until reset.
struct PointQueryStats {
  std::uint64_t queries = 0;
  // Tree nodes whose box was tested against the ray.
  std::uint64_t nodes_visited = 0;
  // Triangles tested exactly (those past the exact bounding-box filter).
  std::uint64_t triangle_tests = 0;

  PointQueryStats& operator+=(const PointQueryStats& o);
};

// Where p lies relative to the solid bounded by the tree's triangles, placed by `tree_pose`
// (x = R x_tree + t, each vertex through apply_pose: the same doubles tree_query.h's collide() and
// the CGAL ground truth see). The mesh must be closed (closedness(tree).closed()); for an open
// mesh the parity, hence the answer, depends on the ray and means nothing.
//
// Algorithm: ray parity (the Jordan-Brouwer separation theorem; the crossing-number test of
// E. Haines, "Point in Polygon Strategies", Graphics Gems IV, 1994, in 3D) along an axis-parallel
// ray, made exact:
//  - every sign is an exact predicate on the doubles (Shewchuk 1997): orient3d for the side of a
//    face's plane, orient2d in the projection along the ray for the side of a face's edge;
//  - a ray through an edge or a vertex is resolved by Simulation of Simplicity (H. Edelsbrunner,
//    E. P. Mucke, ACM Transactions on Graphics 9(1), 1990): p is perturbed to p + eps e_u + eps^2
//    e_v (u, v the other two axes in cyclic order) for an infinitesimal eps > 0, so a zero edge
//    sign becomes the sign of the leading non-zero perturbation term, computed from exact
//    coordinate comparisons. The perturbation is the same for every face and antisymmetric per
//    edge, so the faces around an edge or a vertex that the ray passes through are counted exactly
//    as a slightly moved ray, which misses every edge and vertex, crosses them: the count is the
//    exact crossing count of a generic ray from a point arbitrarily close to p, whose parity is
//    p's side when p is off the surface;
//  - p on the surface (orient3d = 0 and p in the closed face, decided exactly) is answered
//    kOnSurface.
// Acceleration: the tree is descended only through nodes whose box the ray may hit, a test of the
// box's 3 face normals and the 3 cross products of the ray with the box axes (the separating axis
// theorem for a box and a half-line) in floating point, with SAT's slack of tolerances.h (relative
// kSatRelativeSlack of the box size and distance, plus kSatRoundoffFactor of the coordinates'
// magnitudes, |t| of the pose included), which exceeds the test's rounding error by orders of
// magnitude: a box is culled only when the ray provably misses it, so culling never changes the
// answer. At the leaves an exact bounding-box comparison drops the faces the ray cannot reach.
// This relies on every node box containing its triangles, as ObbTree::build guarantees (a tree
// from ObbTree::rounded_to_float(false) does not, and is not a valid input).
PointSide point_side(const ObbTree& tree, const Pose& tree_pose, const Vec3& p,
                     const RayDirection& ray = {}, PointQueryStats* stats = nullptr);
PointSide point_side(const ObbTree& tree, const Vec3& p, PointQueryStats* stats = nullptr);

// The same by brute force over every face (no tree, O(n)): the reference for tests and for
// one-off queries on a soup.
PointSide point_side(const std::vector<Triangle>& triangles, const Vec3& p,
                     const RayDirection& ray = {});

// point_side(...) != kOutside: the solid is closed, so the surface counts as inside.
bool point_inside(const ObbTree& tree, const Vec3& p);
bool point_inside(const ObbTree& tree, const Pose& tree_pose, const Vec3& p);
bool point_inside(const std::vector<Triangle>& triangles, const Vec3& p);

// Whether B (tree `b`, placed in A's frame by `b_in_a`) lies wholly inside A's solid: A is closed,
// the surfaces do not intersect (closed sets: touching counts as intersecting), and one vertex of
// every connected component of B's surface lies inside A. Why that suffices: a connected piece of
// B's surface that misses A's surface lies in one connected component of the complement of A's
// surface, on which the parity (inside or outside) is constant, so one of its points decides for
// all of it (a component's vertex is never on A's surface, since the surfaces do not meet).
// Testing one vertex of B alone would be wrong for a B with several components.
// What "inside" gives: B's surface lies in the interior of A's solid. When A's surface is one
// component (no cavities) B's own solid then lies in A's solid too; a B that wraps one of A's
// cavities passes the check though the cavity is outside A.
// An open or non-manifold A answers false (its "solid" is undefined), as does an empty B.
// `a_closedness` and `b_closedness` must be closedness(a) and closedness(b) (computed once per
// tree; std::invalid_argument if their face counts do not match the trees).
// `surfaces_intersect`: the caller's answer for the pair at this pose (tree_query.h's collide);
// the overload without it runs collide() with SAT in first-contact mode.
//
// This is the definition of docs/design.md's containment check; the cost is one point query per
// component of B after the surface query.
bool mesh_inside(const ObbTree& a, const Closedness& a_closedness, const Pose& b_in_a,
                 const ObbTree& b, const Closedness& b_closedness, bool surfaces_intersect);
bool mesh_inside(const ObbTree& a, const Closedness& a_closedness, const Pose& b_in_a,
                 const ObbTree& b, const Closedness& b_closedness);

// Both directions at once, in A's frame (B's vertices and triangles placed by b_in_a through
// apply_pose, A's as given: never the inverse pose, so both directions see the doubles of the
// surface query). At most one of the two containments holds for non-empty meshes.
struct MeshContainment {
  bool surfaces_intersect = false;
  bool b_inside_a = false;  // mesh_inside(a, ..., b, ...)
  bool a_inside_b = false;  // every component of A inside B's solid, B closed, no intersection
};
MeshContainment mesh_containment(const ObbTree& a, const Closedness& a_closedness,
                                 const Pose& b_in_a, const ObbTree& b,
                                 const Closedness& b_closedness, bool surfaces_intersect);
MeshContainment mesh_containment(const ObbTree& a, const Closedness& a_closedness,
                                 const Pose& b_in_a, const ObbTree& b,
                                 const Closedness& b_closedness);

}  // namespace graspcd
