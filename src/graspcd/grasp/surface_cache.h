// The true surfaces of a model's geoms as the grasp's exact measures see them: the start check
// (start_check.h) and the true meshes' penetration (true_penetration.h). Each surface is built the
// first time one of them needs it and kept for as long as the model is grasped, so that a batch of
// grasps (object_batch.h) builds it once, and a geom that never comes near the object is never
// built.
//
// A surface is a geom's triangles in its own frame (MuJoCo's float vertices of a mesh, not its
// hull, every face kept; a primitive's tessellation, mujoco/primitives.h), shared by every geom of
// the same mesh or of the same primitive shape: its OBB tree, its closedness, its vertices and its
// probes (vertices and points along its edges at most a spacing apart). MuJoCo's convex hull of a
// mesh (mesh_graph, what its native collision sees) is kept beside it for the hull start check.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <vector>

#include "graspcd/core/containment.h"
#include "graspcd/core/geometry.h"
#include "graspcd/core/obb_tree.h"

namespace graspcd::grasp {

// Points that probe another solid: each once, grouped by the tree's triangles (in leaf order):
// the probes of triangle k are points[start[k], start[k + 1]), each kept with the first triangle
// that has it, so that a query takes only the probes of the leaves whose boxes meet the solid.
struct SurfaceProbes {
  std::vector<Vec3> points;
  std::vector<std::size_t> start;
};

class GeomSurface {
 public:
  explicit GeomSurface(std::vector<Triangle> local);

  const ObbTree& tree() const { return tree_; }
  const Closedness& closedness() const { return closedness_; }
  bool closed() const { return closedness_.closed(); }
  // The vertices, each once (sorted).
  const std::vector<Vec3>& vertices() const { return vertices_; }
  // The farthest vertex from the geom's origin, m.
  double radius() const { return radius_; }
  // The box along the geom's axes around its vertices: its centre and half extents.
  const Vec3& aligned_center() const { return aligned_center_; }
  const Vec3& aligned_half() const { return aligned_half_; }
  // The vertices and the points along each edge at most `spacing` apart (an edge of length L gets
  // ceil(L / spacing) - 1 points, evenly), made the first time a spacing is asked for.
  const SurfaceProbes& probes(double spacing) const;

 private:
  ObbTree tree_;
  Closedness closedness_;
  std::vector<Vec3> vertices_;
  double radius_ = 0;
  Vec3 aligned_center_ = Vec3::Zero();
  Vec3 aligned_half_ = Vec3::Zero();
  mutable std::map<double, SurfaceProbes> probes_;
};

class SurfaceCache {
 public:
  // `m` must outlive the cache; its geoms' types, sizes and meshes must not change meanwhile
  // (poses may: surfaces are in the geoms' frames).
  explicit SurfaceCache(const mjModel* m);
  ~SurfaceCache();
  SurfaceCache(const SurfaceCache&) = delete;
  SurfaceCache& operator=(const SurfaceCache&) = delete;

  const mjModel* model() const { return m_; }
  // The true surface of geom g, or null for a geom without one (a plane, a height field).
  const GeomSurface* surface(int g);
  // Whether geom g's true surface is closed (core/containment.h), without building its tree;
  // false without a surface.
  bool closed(int g);
  // MuJoCo's convex hull of a mesh geom (MuJoCo 2.2's mesh_graph; the mesh's faces when it has
  // no graph), the true surface for any other geom.
  const GeomSurface* hull(int g);

 private:
  // A primitive's key: its type and the sizes (unused ones 0).
  using PrimitiveKey = std::array<double, 4>;
  std::unique_ptr<GeomSurface>* slot(int g, bool hull);

  const mjModel* m_;
  std::map<int, std::unique_ptr<GeomSurface>> meshes_, hulls_;  // by mesh id
  std::map<PrimitiveKey, std::unique_ptr<GeomSurface>> primitives_;
  std::map<int, bool> closed_;  // by mesh id, before a tree is built
};

// The deepest probe of one surface inside another's closed solid, when it lies deeper than a
// floor: what the start check and the true penetration ask.
struct ProbeDepth {
  double depth = 0;  // the deepest probe's depth if deeper than the floor, else 0
  // The deepest any probe can lie: the found depth, or the largest depth inside the solid's
  // bounding box of the probes left untested (at most the floor).
  double bound = 0;
};

// The probes of `probed` at `spacing` placed in `solid`'s frame by `pose`, and of them the deepest
// inside solid's closed solid when it lies deeper than `floor` (exact inside test and distance to
// the surface, as core/penetration.h's deepest_point_inside measures them). The work goes to the
// probes that can lie deeper than the floor: only the probes of the probed tree's leaves whose
// boxes meet the solid's root box are placed; a probe that lies no deeper than the floor inside
// the solid's boxes (its root box and its box along the geom's axes) is left, since a probe
// inside the solid lies at most as deep inside it as inside any box around it (the segment from
// the probe to the nearest point of the box's boundary leaves the solid, so it crosses its
// surface); one within the floor of the surface is left too; only the rest get the inside test.
// So the depth is exact whenever the deepest probe lies deeper than the floor. `placed` is
// scratch. The solid must be closed.
ProbeDepth deepest_probe_inside(const GeomSurface& solid, const GeomSurface& probed,
                                const Pose& pose, double spacing, double floor,
                                std::vector<Vec3>& placed);

// The faces of a mesh's convex hull as MuJoCo 2.2 keeps it for its native collision (mesh_graph);
// empty for a mesh without a graph.
std::vector<Triangle> mesh_hull_triangles(const mjModel* m, int mesh_id);

}  // namespace graspcd::grasp
