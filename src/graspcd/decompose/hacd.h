// Approximate convex decomposition of a triangle mesh with HACD, hierarchical approximate convex
// decomposition (K. Mamou and F. Ghorbel, "A simple and efficient approach for 3D mesh approximate
// convex decomposition", ICIP 2009), as Debian ships it in libbullet-extras-dev (libHACD). This
// header does not include HACD; HACD is reached from hacd.cpp alone.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "graspcd/core/geometry.h"

namespace graspcd::decompose {

// The knobs of HACD that graspcd sets. HACD merges clusters of faces along the dual graph of the
// mesh (faces adjacent across an edge), the merge of least cost (concavity, then compactness)
// first, while more than `max_pieces` clusters remain. graspcd gives HACD no concavity threshold,
// so the count is max_pieces, except that it is smaller for a mesh of fewer faces and larger for a
// mesh of more components than max_pieces: HACD joins components only when they come within
// 1.5% of the bounding box diagonal of each other (its connection distance), and never merges
// across a gap, so every component gives at least one piece.
struct HacdOptions {
  std::size_t max_pieces = 16;  // HACD's "number of clusters", >= 1
  // Called as HACD merges (its call-back): the share of the merges done, 0 to 1. HACD's first
  // stage, the cost of every edge of the dual graph, reports nothing.
  std::function<void(double)> progress;
};

// One convex piece: the convex hull of a cluster of the input's faces (of their vertices, by
// qhull; HACD's partition of the faces, not its simplified hulls), in the input's
// coordinates (no scaling or shift), faces oriented outward. A flat cluster (its points on one
// plane, e.g. a cup's flat bottom, which has no solid hull and which MuJoCo would refuse) becomes
// a slab: its points and the same points moved 0.5% of the bounding box diagonal against the
// cluster's outward normal (its faces' area-weighted normal), which for a mesh oriented outward
// is into the object.
struct ConvexPiece {
  TriangleMesh hull;
};

struct Decomposition {
  std::vector<ConvexPiece> pieces;  // every piece has a full-dimensional hull
  std::size_t slabs = 0;            // pieces made from flat clusters (see ConvexPiece)
  // Clusters without a hull even as a slab (collinear points, or faces whose normals cancel):
  // left out; the caller warns.
  std::size_t flat_clusters = 0;
};

// A partition of a mesh's faces into clusters: cluster_of_face[f] < clusters for every face f.
struct Partition {
  std::vector<std::size_t> cluster_of_face;
  std::size_t clusters = 0;
};

// HACD's partition of `mesh`'s faces (at least one face; see HacdOptions). Throws
// std::runtime_error when HACD fails.
Partition hacd_partition(const TriangleMesh& mesh, const HacdOptions& options);

// The convex pieces of a partition of `mesh`'s faces (`partition` has one entry per face of
// `mesh`): one per cluster, the hull of the cluster's vertices (see ConvexPiece). A cluster with
// no face gives no piece and is not counted. Throws std::runtime_error when every cluster is
// flat.
Decomposition pieces_of_partition(const TriangleMesh& mesh, const Partition& partition);

// The convex hull of `points` by qhull, faces turned outward; empty (no faces) when the points
// have no full-dimensional hull (flat, collinear, fewer than 4).
TriangleMesh convex_hull(const std::vector<Vec3>& points);

// Decomposes `mesh` (at least one face): pieces_of_partition(mesh, hacd_partition(mesh,
// options)). Throws std::runtime_error when HACD fails or every cluster is flat. The pieces'
// count is HACD's (see HacdOptions).
Decomposition hacd_decompose(const TriangleMesh& mesh, const HacdOptions& options);

}  // namespace graspcd::decompose
