// OBB tree structure: containment, leaf sizes, a permutation of the input, depth, errors.
#include "graspcd/core/obb_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "graspcd/support/meshes.h"

namespace graspcd {
namespace {

// Returns the triangle range [first, last) of node i's subtree (contiguous in depth-first order)
// and checks, on the way, that every node's box contains the vertices of its subtree.
std::pair<std::int32_t, std::int32_t> check_subtree(const ObbTree& tree, std::int32_t i) {
  const ObbNode& node = tree.nodes()[i];
  std::pair<std::int32_t, std::int32_t> range;
  if (node.is_leaf()) {
    range = {node.first, node.first + node.count};
  } else {
    const auto left = check_subtree(tree, i + 1);
    const auto right = check_subtree(tree, node.right);
    EXPECT_EQ(left.second, right.first);
    range = {left.first, right.second};
  }
  for (std::int32_t t = range.first; t < range.second; ++t) {
    for (const Vec3& v : tree.triangles()[t].v) EXPECT_TRUE(obb_contains(node.box, v));
  }
  return range;
}

void check_tree(const ObbTree& tree, const TriangleMesh& mesh, int leaf_size) {
  const auto range = check_subtree(tree, 0);
  EXPECT_EQ(range.first, 0);
  EXPECT_EQ(range.second, static_cast<std::int32_t>(mesh.faces.size()));
  for (const ObbNode& n : tree.nodes()) {
    if (n.is_leaf()) {
      EXPECT_GE(n.count, 1);
      EXPECT_LE(n.count, leaf_size);
    }
  }
  // face_ids is a permutation and triangles() holds the faces it names.
  std::vector<std::int32_t> ids = tree.face_ids();
  std::sort(ids.begin(), ids.end());
  for (std::size_t i = 0; i < ids.size(); ++i) ASSERT_EQ(ids[i], static_cast<std::int32_t>(i));
  for (std::size_t i = 0; i < tree.triangles().size(); ++i) {
    const Triangle expected = mesh.triangle(tree.face_ids()[i]);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(tree.triangles()[i].v[k], expected.v[k]);
  }
}

TEST(ObbTree, SphereTreeIsValidAndBalancedEnough) {
  const TriangleMesh sphere = testing::make_uv_sphere(0.05, 32, 64);
  for (int leaf_size : {1, 4, 16}) {
    for (ObbFit fit : {ObbFit::kCovariance, ObbFit::kHullArea}) {
      const ObbTree tree = ObbTree::build(sphere, {leaf_size, fit});
      check_tree(tree, sphere, leaf_size);
      const double n = static_cast<double>(sphere.faces.size());
      EXPECT_LE(tree.depth(), 3 * std::log2(n / leaf_size) + 2) << leaf_size;
    }
  }
}

// Float-node emulation (the study's sweep): every box component is a float; unpadded, each moved
// by at most half a float ulp; padded, every box still contains its subtree's vertices, also for a
// mesh far from the origin where the centre's rounding is largest.
TEST(ObbTree, RoundedToFloatIsFloatAndPaddedStillContains) {
  TriangleMesh sphere = testing::make_uv_sphere(0.05, 16, 32);
  for (Vec3& v : sphere.vertices) v += Vec3(0.7, -0.3, 0.2);
  const ObbTree tree = ObbTree::build(sphere);
  const ObbTree rounded = tree.rounded_to_float(false);
  const ObbTree padded = tree.rounded_to_float(true);
  ASSERT_EQ(rounded.nodes().size(), tree.nodes().size());
  const auto is_float = [](double x) { return static_cast<double>(static_cast<float>(x)) == x; };
  std::size_t changed = 0;
  for (std::size_t i = 0; i < tree.nodes().size(); ++i) {
    const Obb& a = tree.nodes()[i].box;
    const Obb& r = rounded.nodes()[i].box;
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(is_float(r.center[k]) && is_float(r.half[k]));
      EXPECT_LE(std::fabs(r.center[k] - a.center[k]), std::ldexp(std::fabs(a.center[k]), -24));
      EXPECT_LE(std::fabs(r.half[k] - a.half[k]), std::ldexp(a.half[k], -24));
      changed += r.center[k] != a.center[k];
      for (int j = 0; j < 3; ++j) EXPECT_TRUE(is_float(r.axes(k, j)));
    }
    EXPECT_GT(padded.nodes()[i].box.half.minCoeff(), r.half.minCoeff());
  }
  EXPECT_GT(changed, 0u) << "the rounding did something";
  check_tree(padded, sphere, 1);
}

TEST(ObbTree, NonConvexTorus) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.01, 48, 24);
  check_tree(ObbTree::build(torus, {1, ObbFit::kCovariance}), torus, 1);
}

TEST(ObbTree, IdenticalTrianglesSplitInHalf) {
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  for (int i = 0; i < 100; ++i) m.faces.push_back({0, 1, 2});
  const ObbTree tree = ObbTree::build(m, {1, ObbFit::kCovariance});
  check_tree(tree, m, 1);
  EXPECT_LE(tree.depth(), 8);  // median splits: ceil(log2(100)) = 7
}

TEST(ObbTree, BadArgumentsThrow) {
  EXPECT_THROW(ObbTree::build(std::vector<Triangle>{}), std::invalid_argument);
  const TriangleMesh sphere = testing::make_uv_sphere(1, 4, 4);
  EXPECT_THROW(ObbTree::build(sphere, {0, ObbFit::kCovariance}), std::invalid_argument);
}

}  // namespace
}  // namespace graspcd
