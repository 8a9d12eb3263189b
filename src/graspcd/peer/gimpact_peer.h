// Bullet's GImpact as a second peer for mesh-against-mesh queries, beside FCL (fcl_peer.h): a
// thin adapter from graspcd's meshes and poses to btGImpactMeshShape against btGImpactMeshShape
// through btGImpactCollisionAlgorithm (Bullet 3.24, Debian's libbullet-dev). Used by the
// benchmarks only, never by src/graspcd/core or src/graspcd/mujoco (docs/design.md, "Layers").
//
// GImpact: F. Leon, "GIMPACT: Geometric tools for VR" (GIMPACT 0.3, 2006), Bullet's concave
// triangle-mesh collision: a BVH of triangle boxes per mesh, box-tree against box-tree, and per
// overlapping triangle pair the clip method (btPrimitiveTriangle::
// find_triangle_collision_clip_method: each triangle clipped against the other's edge planes,
// the penetration taken along the other's face normal).
//
// Precision: Bullet is built twice by Debian; this adapter is compiled with BT_USE_DOUBLE_PRECISION
// and linked to the -float64 libraries only (never mixed with the float ones), so the vertices
// and poses are the doubles graspcd uses. Margins are 0 (GImpact's default is 0.01 m). Bullet's
// headers are kept out of this one (pimpl).
#pragma once

#include <cstdint>
#include <memory>

#include "graspcd/core/geometry.h"

namespace graspcd::peer {

struct GimpactQueryResult {
  bool intersect = false;      // at least one contact point at depth <= 0 (touching counts)
  std::uint64_t contacts = 0;  // contact points GImpact generated at depth <= 0, before Bullet's
                               // persistent manifold keeps 4 of them
};

// A mesh as btGImpactMeshShape (a copy of the vertices and faces, margin 0, its box tree built
// once), in the mesh's own frame. Move-only.
class GimpactMesh {
 public:
  // Throws std::invalid_argument on a mesh without faces or a face index out of range.
  explicit GimpactMesh(const TriangleMesh& mesh);
  ~GimpactMesh();
  GimpactMesh(GimpactMesh&&) noexcept;
  GimpactMesh& operator=(GimpactMesh&&) noexcept;
  GimpactMesh(const GimpactMesh&) = delete;
  GimpactMesh& operator=(const GimpactMesh&) = delete;

  std::size_t triangle_count() const;

  struct Impl;  // the Bullet objects; defined in gimpact_peer.cpp

 private:
  friend class GimpactQuery;
  std::unique_ptr<Impl> impl_;
};

// GImpact's mesh-mesh collision of `a` (at the identity) and `b` placed by `b_in_a`
// (x_A = R x_B + t, as graspcd::collide): btGImpactCollisionAlgorithm::processCollision with a
// result that counts every contact point it adds. The dispatcher and its configuration are made
// once per query object and kept, as a Bullet world keeps them.
class GimpactQuery {
 public:
  GimpactQuery();
  ~GimpactQuery();
  GimpactQuery(const GimpactQuery&) = delete;
  GimpactQuery& operator=(const GimpactQuery&) = delete;

  GimpactQueryResult collide(const GimpactMesh& a, const GimpactMesh& b, const Pose& b_in_a);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace graspcd::peer
