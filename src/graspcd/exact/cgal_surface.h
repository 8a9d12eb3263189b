// A graspcd triangle soup as a CGAL Surface_mesh: shared by the exact module's .cpp files only
// (hausdorff.cpp, simplify.cpp). It includes CGAL, so no header outside src/graspcd/exact/ may
// include it (docs/design.md, "Layers").
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd::exact::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

// The meshes as one CGAL surface: the soup repaired (equal points merged, faces with a repeated
// vertex dropped), oriented (vertices duplicated where the surface is not a manifold) and
// converted. No point is moved.
Mesh surface_of(const std::vector<const TriangleMesh*>& meshes);

// A CGAL surface as a graspcd triangle mesh (removed elements skipped, faces triangulated as
// given: every face of `mesh` must be a triangle).
TriangleMesh triangle_mesh_of(const Mesh& mesh);

}  // namespace graspcd::exact::detail
