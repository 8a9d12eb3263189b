#include "graspcd/core/geometry.h"

#include <cmath>

namespace graspcd {

bool is_rotation(const Mat3& R, double tol) {
  if (!R.allFinite()) return false;
  const Mat3 gram = R.transpose() * R;
  if ((gram - Mat3::Identity()).cwiseAbs().maxCoeff() > tol) return false;
  return R.determinant() > 0.0;
}

std::vector<Triangle> posed_triangles(const TriangleMesh& mesh, const Pose& pose) {
  std::vector<Triangle> out;
  out.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    out.push_back(apply_pose(pose, mesh.triangle(f)));
  }
  return out;
}

}  // namespace graspcd
