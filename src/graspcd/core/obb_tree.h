// The OBB tree (paper sections 2-3): built top-down, nodes in one contiguous array.
#pragma once

#include <cstdint>
#include <vector>

#include "graspcd/core/obb.h"
#include "graspcd/core/tritri.h"

namespace graspcd {

// A node in depth-first order: the first child of an internal node is the next node in the array,
// `right` indexes the second child; a leaf has right == -1 and owns triangles
// [first, first + count) of ObbTree::triangles().
struct ObbNode {
  Obb box;
  std::int32_t right = -1;
  std::int32_t first = 0;
  std::int32_t count = 0;
  bool is_leaf() const { return right < 0; }
};

// A node's box frame in its parent's box frame (RAPID's layout, Gottschalk, Lin, Manocha 1996):
// R = P^T C and t = P^T (c_C - c_P) for the parent's axes P and centre c_P and the node's axes C
// and centre c_C; for the root, its own axes and centre (the parent is the mesh frame). The tree
// query carries relative frames down with these, one 3x3 product per step.
struct NodeFrame {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
};

struct ObbTreeOptions {
  int leaf_size = 1;                 // at most this many triangles per leaf (>= 1)
  ObbFit fit = ObbFit::kCovariance;  // how each node's box is fitted
};

class ObbTree {
 public:
  ObbTree() = default;

  // Top-down build: fit a box to the node's triangles, split them by centroid at the mean centroid
  // along the box's longest axis (the other axes in decreasing length when one side would be
  // empty; a median split when all centroids coincide), recurse until a node holds at most
  // leaf_size triangles. O(n log n) expected. Throws std::invalid_argument on an empty input or
  // leaf_size < 1.
  static ObbTree build(std::vector<Triangle> triangles, const ObbTreeOptions& options = {});
  static ObbTree build(const TriangleMesh& mesh, const ObbTreeOptions& options = {});

  const std::vector<ObbNode>& nodes() const { return nodes_; }
  // in_parent()[i]: node i's frame in its parent's (NodeFrame), parallel to nodes().
  const std::vector<NodeFrame>& in_parent() const { return in_parent_; }
  // Triangles in leaf order; face_ids()[i] is the index of triangles()[i] in the input.
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<std::int32_t>& face_ids() const { return face_ids_; }
  // planes()[i] = triangle_plane(triangles()[i]) (tritri.h), computed once at the build: the tree
  // query's triangle test takes A's planes from here instead of computing them per test.
  const std::vector<TrianglePlane>& planes() const { return planes_; }
  int depth() const { return depth_; }
  // The largest distance from the root box's centre to a point of any node's box: every box of the
  // tree lies in the ball of this radius around the root's centre (a child's box may reach outside
  // its parent's). Metres; 0 for an empty tree.
  double reach() const { return reach_; }
  const ObbNode& root() const { return nodes_.front(); }

  // The same tree with every node box stored as floats would store it (centre, axes and
  // half-extents each rounded to the nearest float), the triangles unchanged: the precision a
  // float-node tree has, for the study's error sweep (the arithmetic stays double). With `pad`,
  // each half-extent grows by a bound on what the rounding moved the box's points,
  // 2^-21 (|c|_inf + sum of half-extents), so the rounded box still contains the exact one.
  ObbTree rounded_to_float(bool pad) const;

 private:
  // Fills in_parent_ and reach_ from nodes_.
  void link_frames();

  std::vector<ObbNode> nodes_;
  std::vector<NodeFrame> in_parent_;
  std::vector<Triangle> triangles_;
  std::vector<std::int32_t> face_ids_;
  std::vector<TrianglePlane> planes_;
  int depth_ = 0;
  double reach_ = 0;
};

}  // namespace graspcd
