// CGAL's AABB tree as a point-to-surface distance (surface_distance.h).
#include "graspcd/exact/surface_distance.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace graspcd::exact {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalTriangle = Kernel::Triangle_3;
using Iterator = std::vector<CgalTriangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

struct SurfaceDistance::Impl {
  std::vector<CgalTriangle> triangles;
  std::vector<std::size_t> face_of_triangle;  // the mesh's face index of triangles[k]
  Tree tree;
};

SurfaceDistance::SurfaceDistance(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  if (mesh.faces.empty()) throw std::invalid_argument("SurfaceDistance: a mesh without faces");
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle t = mesh.triangle(f);
    const CgalTriangle c(point(t.v[0]), point(t.v[1]), point(t.v[2]));
    if (c.is_degenerate()) continue;
    impl_->triangles.push_back(c);
    impl_->face_of_triangle.push_back(f);
  }
  if (impl_->triangles.empty()) throw std::invalid_argument("SurfaceDistance: no area");
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

double SurfaceDistance::distance(const Vec3& p) const {
  return std::sqrt(CGAL::to_double(impl_->tree.squared_distance(point(p))));
}

std::size_t SurfaceDistance::nearest_face(const Vec3& p) const {
  const Iterator nearest = impl_->tree.closest_point_and_primitive(point(p)).second;
  return impl_->face_of_triangle[static_cast<std::size_t>(nearest - impl_->triangles.cbegin())];
}

}  // namespace graspcd::exact
