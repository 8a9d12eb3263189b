// core/penetration.h: the point-triangle distance against a dense sampling of the triangle, and the
// deepest vertex inside a closed mesh against depths known in closed form (boxes).
#include "graspcd/core/penetration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "graspcd/core/obb_tree.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/seeded.h"

namespace graspcd {
namespace {

// The distance to a sampling of the closed triangle (barycentric grid, n steps per side): an upper
// bound that is within the grid's spacing of the true distance.
double sampled_distance(const Vec3& p, const Triangle& t, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double u = static_cast<double>(i) / n;
      const double v = static_cast<double>(j) / n;
      const Vec3 q = t.v[0] + u * (t.v[1] - t.v[0]) + v * (t.v[2] - t.v[0]);
      best = std::min(best, (p - q).norm());
    }
  }
  return best;
}

TEST(PenetrationTest, PointTriangleDistanceMatchesASampledTriangleInEveryRegion) {
  seeded::Rng rng(21);
  const auto u = [](seeded::Rng& r) { return seeded::uniform(r, -1, 1); };
  constexpr int kGrid = 200;
  for (int k = 0; k < 300; ++k) {
    const Triangle t{
        {Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng))}};
    const Vec3 p(2 * u(rng), 2 * u(rng), 2 * u(rng));
    const double exact = point_triangle_distance(p, t);
    const double sampled = sampled_distance(p, t, kGrid);
    const double spacing =
        std::max({(t.v[1] - t.v[0]).norm(), (t.v[2] - t.v[0]).norm(), (t.v[2] - t.v[1]).norm()}) /
        kGrid;
    EXPECT_LE(exact, sampled + 1e-12) << k;
    EXPECT_GE(exact, sampled - spacing) << k;
  }
}

TEST(PenetrationTest, ADegenerateTriangleIsItsSegment) {
  const Triangle segment{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}};
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(1, 3, 4), segment), 5.0);
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(5, 4, 0), segment), 5.0);
  const Triangle point{{Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}};
  EXPECT_DOUBLE_EQ(point_triangle_distance(Vec3(1, 1, 3), point), 2.0);
}

// A box of half-extents (1, 2, 3): a point at local (x, y, z) inside lies min(1-|x|, 2-|y|, 3-|z|)
// deep.
TEST(PenetrationTest, TheDeepestPointInsideABoxIsFoundWithItsDepth) {
  const ObbTree box = ObbTree::build(testing::make_box_mesh(1, 2, 3));
  const std::vector<Vec3> points = {Vec3(5, 0, 0),        Vec3(0.9, 0, 0), Vec3(0, 1.5, 0),
                                    Vec3(0.2, 0.1, -2.3), Vec3(1, 0, 0),   Vec3(0, 0, 3.01)};
  const VertexPenetration p = deepest_point_inside(box, points);
  EXPECT_EQ(p.inside, 4u);  // (1, 0, 0) lies on the surface: inside the closed solid, depth 0
  EXPECT_EQ(p.point, 3u);
  EXPECT_NEAR(p.depth, 0.7, 1e-12);
  // Nothing inside: depth 0, no point.
  const VertexPenetration none = deepest_point_inside(box, {Vec3(5, 0, 0), Vec3(0, 0, -4)});
  EXPECT_EQ(none.inside, 0u);
  EXPECT_EQ(none.depth, 0.0);
  EXPECT_EQ(none.point, std::numeric_limits<std::size_t>::max());
}

TEST(PenetrationTest, TheScanStopsOnceTheLimitIsPassed) {
  const ObbTree box = ObbTree::build(testing::make_box_mesh(1, 1, 1));
  const std::vector<Vec3> points = {Vec3(0.5, 0, 0), Vec3(0, 0, 0), Vec3(0.1, 0, 0)};
  const VertexPenetration p = deepest_point_inside(box, points, 0.4);
  EXPECT_EQ(p.point, 0u);
  EXPECT_EQ(p.inside, 1u);
  EXPECT_NEAR(p.depth, 0.5, 1e-12);
  EXPECT_NEAR(deepest_point_inside(box, points).depth, 1.0, 1e-12);
}

}  // namespace
}  // namespace graspcd
