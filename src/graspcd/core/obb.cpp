#include "graspcd/core/obb.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

// qhull's reentrant C library, the one MuJoCo's mesh compiler calls too. Not the C++ library
// libqhullcpp: it replaces libqhull_r's print hook qh_fprintf process-wide with one that ends the
// process (exit 41, "QH10025 ... without QhullQh defined") whenever a qhull run it did not start,
// such as MuJoCo's on a degenerate mesh, prints a message.
#include <libqhull_r/libqhull_r.h>

#include "graspcd/core/tolerances.h"

namespace graspcd {
namespace {

// Eq. (1)-(3): mean and covariance of the 3n triangle vertices (each vertex counted once per
// triangle it belongs to). Eq. (2)'s normalising constant does not change the eigenvectors; we use
// 1 / 3n. The points are centred on the mean before the products, which keeps the sums accurate
// far from the origin.
Mat3 vertex_covariance(const std::vector<Vec3>& points, Vec3& mean) {
  mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Mat3 c = Mat3::Zero();
  for (const Vec3& p : points) {
    const Vec3 d = p - mean;
    c += d * d.transpose();
  }
  return c / static_cast<double>(points.size());
}

// Gottschalk, Lin, Manocha 1996, section 4.1: the covariance of the convex hull's surface, each
// hull triangle (p, q, r) weighted by its area A_i with centroid m_i:
//   mu = sum A_i m_i / A_H,
//   C_jk = sum (A_i / 12) (9 m_ij m_ik + p_j p_k + q_j q_k + r_j r_k) / A_H - mu_j mu_k.
// Returns false when the points have no 3D hull (flat, collinear, too few); the caller falls back
// to the vertex covariance.
bool hull_covariance(const std::vector<Vec3>& points, const Vec3& origin, Mat3& cov) {
  if (points.size() < 4) return false;
  std::vector<double> coords;
  coords.reserve(points.size() * 3);
  for (const Vec3& p : points) {
    for (int k = 0; k < 3; ++k) coords.push_back(p[k] - origin[k]);
  }
  // qhull's messages (a flat or degenerate point set is a precision error, answered by the
  // fallback) go nowhere; without /dev/null they go to stderr.
  static std::FILE* const quiet = std::fopen("/dev/null", "w");
  qhT qh_storage;
  qhT* qh = &qh_storage;  // the name the qhull macros below expect
  qh_zero(qh, quiet);
  char command[] = "qhull Qt";
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                     command, nullptr, quiet);
  double area_sum = 0.0;
  Vec3 mu = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  if (exit_code == 0) {
    facetT* facet = nullptr;
    FORALLfacets {
      Vec3 v[3];
      int count = 0;
      vertexT *vertex = nullptr, **vertexp = nullptr;
      FOREACHvertex_(facet->vertices) {
        if (count < 3) v[count] = Vec3(vertex->point[0], vertex->point[1], vertex->point[2]);
        ++count;
      }
      if (count != 3) continue;
      const double area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
      const Vec3 m = (v[0] + v[1] + v[2]) / 3.0;
      area_sum += area;
      mu += area * m;
      second += (area / 12.0) * (9.0 * m * m.transpose() + v[0] * v[0].transpose() +
                                 v[1] * v[1].transpose() + v[2] * v[2].transpose());
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int long_left = 0, total_left = 0;
  qh_memfreeshort(qh, &long_left, &total_left);
  // No full-dimensional hull (exit_code != 0, or no area): the caller falls back.
  if (!(area_sum > 0.0)) return false;
  mu /= area_sum;
  cov = second / area_sum - mu * mu.transpose();
  return cov.allFinite();
}

// Orthonormal right-handed axes from a symmetric matrix's eigenvectors (Eigen's
// SelfAdjointEigenSolver gives orthonormal eigenvectors, also for repeated eigenvalues).
Mat3 principal_axes(const Mat3& cov) {
  Eigen::SelfAdjointEigenSolver<Mat3> solver(cov);
  Mat3 axes = solver.info() == Eigen::Success ? solver.eigenvectors() : Mat3::Identity();
  if (!axes.allFinite()) axes = Mat3::Identity();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  return axes;
}

// The box with the given axes that holds every point: extreme projections, padded (tolerances.h).
Obb box_around(const std::vector<Vec3>& points, const Mat3& axes) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  double scale = 0.0;
  for (const Vec3& p : points) {
    const Vec3 q = axes.transpose() * p;
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
    scale = std::max(scale, p.cwiseAbs().maxCoeff());
  }
  Obb box;
  box.axes = axes;
  box.center = axes * ((lo + hi) / 2.0);
  box.half = (hi - lo) / 2.0 + Vec3::Constant(tol::kObbFitPad * scale);
  return box;
}

}  // namespace

std::array<Vec3, 8> obb_corners(const Obb& box) {
  std::array<Vec3, 8> corners;
  for (int k = 0; k < 8; ++k) {
    Vec3 c = box.center;
    for (int i = 0; i < 3; ++i) {
      const double s = (k >> i) & 1 ? 1.0 : -1.0;
      c += s * box.half[i] * box.axes.col(i);
    }
    corners[k] = c;
  }
  return corners;
}

Obb transform(const Pose& pose, const Obb& box) {
  Obb out;
  out.center = apply_pose(pose, box.center);
  out.axes = pose.R * box.axes;
  out.half = box.half;
  return out;
}

bool obb_contains(const Obb& box, const Vec3& p, double slack) {
  const Vec3 q = box.axes.transpose() * (p - box.center);
  for (int i = 0; i < 3; ++i) {
    if (std::fabs(q[i]) > box.half[i] + slack) return false;
  }
  return true;
}

Obb fit_obb(const std::vector<Triangle>& triangles, ObbFit method) {
  std::vector<Vec3> points;
  points.reserve(triangles.size() * 3);
  for (const Triangle& t : triangles) points.insert(points.end(), t.v.begin(), t.v.end());
  if (points.empty()) return Obb{};
  Vec3 mean;
  Mat3 cov = vertex_covariance(points, mean);
  if (method == ObbFit::kHullArea) {
    Mat3 hull_cov;
    if (hull_covariance(points, mean, hull_cov)) cov = hull_cov;
  }
  return box_around(points, principal_axes(cov));
}

}  // namespace graspcd
