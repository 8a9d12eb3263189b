// The distance from points to a triangle surface, by CGAL's AABB tree (the judge of where a
// contact point lies, the race), and the face nearest a point (decompose --simplify). This
// header does not include CGAL.
#pragma once

#include <cstddef>
#include <memory>

#include "graspcd/core/geometry.h"

namespace graspcd::exact {

// A surface, its AABB tree built once (CGAL::AABB_tree over the triangles, Epick kernel).
class SurfaceDistance {
 public:
  // Throws std::invalid_argument on a mesh without faces.
  explicit SurfaceDistance(const TriangleMesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;
  SurfaceDistance(const SurfaceDistance&) = delete;
  SurfaceDistance& operator=(const SurfaceDistance&) = delete;

  // The Euclidean distance (m) from `point` to the nearest point of the surface, in the mesh's
  // frame: CGAL's closest point (squared_distance, rounded once by the square root).
  double distance(const Vec3& point) const;

  // The index in the mesh's `faces` of a face nearest `point` (CGAL's closest_point_and_primitive;
  // zero-area faces are not in the tree, so never this face; a tie goes to the face CGAL meets
  // first).
  std::size_t nearest_face(const Vec3& point) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace graspcd::exact
