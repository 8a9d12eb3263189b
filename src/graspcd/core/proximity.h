// How close two triangle surfaces come: the distance between segments and between triangles, and
// between the surfaces of two OBB trees, up to a cap. The grasp's verdicts ask it whether a hand
// part touches the object on the true meshes (within a tolerance), and where.
#pragma once

#include <cstdint>
#include <vector>

#include "graspcd/core/geometry.h"
#include "graspcd/core/obb_tree.h"

namespace graspcd {

// The distance between the closed segments [p1, q1] and [p2, q2] and a closest point of each.
// Algorithm: C. Ericson, Real-Time Collision Detection (2005), 5.1.9 "Closest points of two line
// segments" (a segment of zero length is its point).
struct SegmentDistance {
  double distance = 0;
  Vec3 on_first = Vec3::Zero();
  Vec3 on_second = Vec3::Zero();
};
SegmentDistance segment_distance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2);

// The distance between two closed triangles and a point where they are that close: 0 when they
// intersect (tri_tri_intersect, decided exactly; the point is then the mean of the points where
// an edge of one crosses the other, or of their vertices for coplanar overlaps); else the least
// of the six vertex-triangle distances (point_triangle_distance, penetration.h) and the nine
// edge-edge distances, the distance of two disjoint triangles (Ericson, 5.1.9, and PQP's
// TriDist, Larsen et al., "Fast proximity queries with swept sphere volumes", 1999), with the
// midpoint of the two closest points.
struct TriangleDistance {
  double distance = 0;
  Vec3 point = Vec3::Zero();
};
TriangleDistance triangle_distance(const Triangle& a, const Triangle& b);

// The least distance between the surfaces of the trees `a` and `b`, b's triangles placed in a's
// frame by `b_in_a`, when it is less than `cap`; else `cap`. Branch and bound over node pairs:
// a pair whose boxes, A's grown by the least distance so far on every side, SAT finds disjoint
// (sat.h: never for overlapping boxes) is skipped, since every point within that distance of A's
// box lies in the grown box. With `stop_at` >= 0 the search ends at the first triangle pair at
// most that far apart and returns its distance: then an upper bound of the least, which is at
// most `stop_at` exactly when the least is.
double tree_distance(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, double cap,
                     double stop_at = -1);

// A pair of triangles (indices into a.triangles() and b.triangles(), leaf order) within the
// distance asked, their distance and a point where they are that close (in a's frame).
struct NearTriangles {
  std::int32_t a = 0, b = 0;
  double distance = 0;
  Vec3 point = Vec3::Zero();
};

// Every triangle pair of the two trees at most `within` apart, appended to `out` in the order
// of the depth-first descent.
void triangles_within(const ObbTree& a, const ObbTree& b, const Pose& b_in_a, double within,
                      std::vector<NearTriangles>& out);

}  // namespace graspcd
