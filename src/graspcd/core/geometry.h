// Basic geometric types of the core: points, triangles, meshes and rigid poses.
// Pure geometry: nothing here knows of MuJoCo, CGAL or files.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace graspcd {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// A triangle as three vertices. Closed set; a zero-area triangle is the segment or point it spans.
struct Triangle {
  std::array<Vec3, 3> v;
};

// An indexed triangle mesh in its own frame (metres). Faces index `vertices`.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int32_t, 3>> faces;

  Triangle triangle(std::size_t face) const {
    const auto& f = faces[face];
    return Triangle{{vertices[f[0]], vertices[f[1]], vertices[f[2]]}};
  }
};

// A rigid placement x_A = R x_B + t of frame B in frame A. R must be orthonormal to within
// kOrthonormalTol (tolerances.h); callers validate poses that come from input.
struct Pose {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
};

// True when every number of the pose is finite. A pose read from a simulation that went bad may
// not be; the callers skip such a pose (and count it) rather than query a meaningless placement.
inline bool finite_pose(const Pose& p) { return p.R.allFinite() && p.t.allFinite(); }

// Applies a pose to a point in double arithmetic, one rounding per operation in a fixed order
// (the build disables FMA contraction). Every consumer that must see the same transformed doubles
// (the tree query's leaves and the CGAL ground truth) goes through this one function, so exactness
// claims are about the same numbers.
inline Vec3 apply_pose(const Pose& pose, const Vec3& x) {
  const Mat3& R = pose.R;
  return Vec3(((R(0, 0) * x[0] + R(0, 1) * x[1]) + R(0, 2) * x[2]) + pose.t[0],
              ((R(1, 0) * x[0] + R(1, 1) * x[1]) + R(1, 2) * x[2]) + pose.t[1],
              ((R(2, 0) * x[0] + R(2, 1) * x[1]) + R(2, 2) * x[2]) + pose.t[2]);
}

inline Triangle apply_pose(const Pose& pose, const Triangle& tri) {
  return Triangle{
      {apply_pose(pose, tri.v[0]), apply_pose(pose, tri.v[1]), apply_pose(pose, tri.v[2])}};
}

// The index (0, 1 or 2) of the largest |v_k|; the first one on ties.
inline int argmax_abs(const Vec3& v) {
  const double x = std::abs(v[0]), y = std::abs(v[1]), z = std::abs(v[2]);
  return x >= y ? (x >= z ? 0 : 2) : (y >= z ? 1 : 2);
}

// True when R^T R is the identity to within `tol` entrywise and det(R) > 0.
bool is_rotation(const Mat3& R, double tol);

// All mesh triangles in face order, each with `pose` applied through apply_pose.
std::vector<Triangle> posed_triangles(const TriangleMesh& mesh, const Pose& pose);

}  // namespace graspcd
