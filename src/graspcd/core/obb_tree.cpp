#include "graspcd/core/obb_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace graspcd {
namespace {

// One pending node of the top-down build: triangles order[begin, end), its depth, and the parent
// whose `right` must point at it (-1 for the root and for first children, which always directly
// follow their parent in depth-first order).
struct PendingNode {
  std::size_t begin, end;
  int depth;
  std::int32_t parent;
};

// Splits order[begin, end) at the mean centroid along `axis`; returns the split position, or
// `begin`/`end` when one side would be empty.
std::size_t split_at_mean(std::vector<std::int32_t>& order, std::size_t begin, std::size_t end,
                          const std::vector<Vec3>& centroids, const Vec3& axis) {
  double mean = 0.0;
  for (std::size_t i = begin; i < end; ++i) mean += centroids[order[i]].dot(axis);
  mean /= static_cast<double>(end - begin);
  const auto mid = std::partition(order.begin() + static_cast<std::ptrdiff_t>(begin),
                                  order.begin() + static_cast<std::ptrdiff_t>(end),
                                  [&](std::int32_t t) { return centroids[t].dot(axis) < mean; });
  return static_cast<std::size_t>(mid - order.begin());
}

}  // namespace

// Top-down construction (paper section 2; Gottschalk, Lin, Manocha 1996, section 4.2: split at
// the mean of the centroids along the longest box axis).
ObbTree ObbTree::build(std::vector<Triangle> triangles, const ObbTreeOptions& options) {
  if (triangles.empty()) throw std::invalid_argument("ObbTree::build: no triangles");
  if (options.leaf_size < 1) throw std::invalid_argument("ObbTree::build: leaf_size < 1");
  const std::size_t n = triangles.size();
  std::vector<Vec3> centroids(n);
  for (std::size_t i = 0; i < n; ++i) {
    centroids[i] = (triangles[i].v[0] + triangles[i].v[1] + triangles[i].v[2]) / 3.0;
  }
  std::vector<std::int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);

  ObbTree tree;
  tree.nodes_.reserve(2 * n / static_cast<std::size_t>(options.leaf_size) + 1);
  tree.triangles_.reserve(n);
  tree.face_ids_.reserve(n);
  std::vector<PendingNode> stack{{0, n, 0, -1}};
  std::vector<Triangle> node_triangles;
  while (!stack.empty()) {
    const PendingNode pending = stack.back();
    stack.pop_back();
    const auto index = static_cast<std::int32_t>(tree.nodes_.size());
    if (pending.parent >= 0) tree.nodes_[pending.parent].right = index;
    tree.depth_ = std::max(tree.depth_, pending.depth);

    // Fit the node's box to its triangles.
    node_triangles.clear();
    for (std::size_t i = pending.begin; i < pending.end; ++i) {
      node_triangles.push_back(triangles[order[i]]);
    }
    ObbNode node;
    node.box = fit_obb(node_triangles, options.fit);
    const std::size_t count = pending.end - pending.begin;

    // Split by centroid along the longest axis, then the others by decreasing length; when every
    // axis leaves one side empty (all centroids equal), split the range in half.
    std::size_t mid = pending.begin;
    if (count > static_cast<std::size_t>(options.leaf_size)) {
      std::array<int, 3> axes{0, 1, 2};
      std::sort(axes.begin(), axes.end(),
                [&](int x, int y) { return node.box.half[x] > node.box.half[y]; });
      for (int axis : axes) {
        mid = split_at_mean(order, pending.begin, pending.end, centroids, node.box.axes.col(axis));
        if (mid != pending.begin && mid != pending.end) break;
      }
      if (mid == pending.begin || mid == pending.end) mid = pending.begin + count / 2;
    }

    if (mid == pending.begin) {  // a leaf: its triangles go to the tree in leaf order
      node.first = static_cast<std::int32_t>(tree.triangles_.size());
      node.count = static_cast<std::int32_t>(count);
      for (std::size_t i = pending.begin; i < pending.end; ++i) {
        tree.triangles_.push_back(triangles[order[i]]);
        tree.face_ids_.push_back(order[i]);
      }
      tree.nodes_.push_back(node);
      continue;
    }
    tree.nodes_.push_back(node);
    // The second child is pushed first so that the first child is built next, at index + 1.
    stack.push_back({mid, pending.end, pending.depth + 1, index});
    stack.push_back({pending.begin, mid, pending.depth + 1, -1});
  }
  tree.planes_.reserve(n);
  for (const Triangle& t : tree.triangles_) tree.planes_.push_back(triangle_plane(t));
  tree.link_frames();
  return tree;
}

void ObbTree::link_frames() {
  in_parent_.assign(nodes_.size(), NodeFrame{});
  reach_ = 0;
  if (nodes_.empty()) return;
  for (const ObbNode& node : nodes_) {
    // The centre's distance plus the half-diagonal: the farthest a corner can be.
    reach_ =
        std::max(reach_, (node.box.center - nodes_[0].box.center).norm() + node.box.half.norm());
  }
  in_parent_[0] = {nodes_[0].box.axes, nodes_[0].box.center};
  const auto child_in = [](const Obb& parent, const Obb& child) {
    return NodeFrame{parent.axes.transpose() * child.axes,
                     parent.axes.transpose() * (child.center - parent.center)};
  };
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const ObbNode& node = nodes_[i];
    if (node.is_leaf()) continue;
    in_parent_[i + 1] = child_in(node.box, nodes_[i + 1].box);
    in_parent_[static_cast<std::size_t>(node.right)] =
        child_in(node.box, nodes_[static_cast<std::size_t>(node.right)].box);
  }
}

ObbTree ObbTree::build(const TriangleMesh& mesh, const ObbTreeOptions& options) {
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) triangles.push_back(mesh.triangle(f));
  return build(std::move(triangles), options);
}

ObbTree ObbTree::rounded_to_float(bool pad) const {
  // A point c + A diag(h) u moves by at most |dc| + sum_i h_i |dA_i| + |dh| when c, A, h are
  // rounded to float (relative error 2^-24 per component, |A_i| = 1): below 2^-21 (|c|_inf +
  // sum h) per coordinate with room for the cast back and the products.
  //
  // The rounding goes through a volatile float: GCC 12 at -O2/-O3 compiled Eigen's
  // half.cast<float>().cast<double>() into a no-op for the half-extents (the centre was rounded),
  // which ObbTree.RoundedToFloatIsFloatAndPaddedStillContains caught; clang was right.
  const auto to_float = [](double x) -> double {
    volatile float f = static_cast<float>(x);
    return f;
  };
  ObbTree out = *this;
  for (ObbNode& node : out.nodes_) {
    Obb& box = node.box;
    const double bound = std::ldexp(box.center.cwiseAbs().maxCoeff() + box.half.sum(), -21);
    for (int i = 0; i < 3; ++i) {
      box.center[i] = to_float(box.center[i]);
      box.half[i] = to_float(box.half[i]);
      for (int j = 0; j < 3; ++j) box.axes(i, j) = to_float(box.axes(i, j));
    }
    if (pad) box.half.array() += bound;
  }
  out.link_frames();
  return out;
}

}  // namespace graspcd
