// OBB fit (eq. 1-3 and the hull-area variant): containment, frame, degenerate input, tightness.
#include "graspcd/core/obb.h"

#include <gtest/gtest.h>

#include <random>

#include "graspcd/support/meshes.h"
#include "graspcd/support/random_geometry.h"

namespace graspcd {
namespace {

void expect_valid_box(const Obb& box, const std::vector<Triangle>& tris) {
  const Mat3 gram = box.axes.transpose() * box.axes;
  EXPECT_LT((gram - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(box.axes.determinant(), 0.0);
  EXPECT_TRUE((box.half.array() >= 0.0).all());
  for (const Triangle& t : tris) {
    for (const Vec3& v : t.v) ASSERT_TRUE(obb_contains(box, v)) << v.transpose();
  }
}

double volume(const Obb& b) { return 8 * b.half.prod(); }

TEST(FitObb, ContainsEveryVertexOfRandomMeshesBothFits) {
  testing::Rng rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const double scale = std::pow(10.0, trial % 8 - 4);  // 1e-4 .. 1e3 m
    const Vec3 offset = testing::uniform_vec3(rng, -1.0, 1.0) * scale * 1000;
    std::vector<Triangle> tris(1 + trial % 30);
    for (Triangle& t : tris) {
      for (Vec3& v : t.v) {
        v = offset + scale * testing::uniform_in_box(rng, Vec3(-1, -0.3, -0.1), Vec3(1, 0.3, 0.1));
      }
    }
    expect_valid_box(fit_obb(tris, ObbFit::kCovariance), tris);
    expect_valid_box(fit_obb(tris, ObbFit::kHullArea), tris);
  }
}

TEST(FitObb, DegenerateInputGivesAFrameAndNonNegativeExtents) {
  const Vec3 p(1, 2, 3);
  const std::vector<std::vector<Triangle>> cases = {
      {Triangle{{p, p, p}}},                                       // one point
      {Triangle{{p, p + Vec3(1, 1, 0), p + Vec3(2, 2, 0)}}},       // collinear
      {Triangle{{p, p + Vec3(1, 0, 0), p + Vec3(0, 1, 0)}}},       // one triangle
      {Triangle{{p, p + Vec3(1, 0, 0), p}}, Triangle{{p, p, p}}},  // repeated vertices
      {Triangle{{p, p + Vec3(1, 0, 0), p + Vec3(0, 1, 0)}},
       Triangle{{p + Vec3(1, 1, 0), p + Vec3(1, 0, 0), p + Vec3(0, 1, 0)}}},  // coplanar
  };
  for (const auto& tris : cases) {
    for (ObbFit fit : {ObbFit::kCovariance, ObbFit::kHullArea}) {
      const Obb box = fit_obb(tris, fit);
      expect_valid_box(box, tris);
    }
  }
  // A single point gives a box of (padded) zero size.
  EXPECT_LT(fit_obb({Triangle{{p, p, p}}}).half.maxCoeff(), 1e-12);
}

// A rotated 4 x 2 x 1 box surface whose vertices crowd along one face diagonal: the vertex
// covariance tilts, the hull-area covariance (Gottschalk 1996) does not, so the hull fit is the
// tight box and the vertex fit is looser.
TEST(FitObb, HullFitIgnoresVertexCrowding) {
  testing::Rng rng(5);
  const Mat3 R = testing::random_rotation(rng);
  const Vec3 half(2, 1, 0.5);
  const auto corner = [&](int k) -> Vec3 {
    return R * Vec3((k & 1 ? 1 : -1) * half.x(), (k & 2 ? 1 : -1) * half.y(),
                    (k & 4 ? 1 : -1) * half.z());
  };
  std::vector<Triangle> tris;
  // The 12 triangles of the box.
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& q : quads) {
    tris.push_back({{corner(q[0]), corner(q[1]), corner(q[2])}});
    tris.push_back({{corner(q[0]), corner(q[2]), corner(q[3])}});
  }
  // 200 slivers along the diagonal of the top face (z = +0.5), all on the surface.
  for (int i = 0; i < 200; ++i) {
    const double s = i / 200.0, e = 1.0 / 200.0;
    const Vec3 a = R * Vec3(-2 + 4 * s, -1 + 2 * s, 0.5);
    const Vec3 b = R * Vec3(-2 + 4 * (s + e), -1 + 2 * (s + e), 0.5);
    tris.push_back({{a, b, R * Vec3(-2 + 4 * s, -1 + 2 * s + 1e-3, 0.5)}});
  }
  const Obb hull = fit_obb(tris, ObbFit::kHullArea);
  const Obb cov = fit_obb(tris, ObbFit::kCovariance);
  expect_valid_box(hull, tris);
  expect_valid_box(cov, tris);
  EXPECT_NEAR(volume(hull), 8 * half.prod(), 1e-6);
  EXPECT_GT(volume(cov), 1.05 * volume(hull));
}

TEST(ObbCorners, SignBitOrderXFastest) {
  Obb box;
  box.center = Vec3(1, 2, 3);
  box.half = Vec3(1, 2, 3);
  const auto c = obb_corners(box);
  EXPECT_EQ(c[0], Vec3(0, 0, 0));
  EXPECT_EQ(c[1], Vec3(2, 0, 0));
  EXPECT_EQ(c[2], Vec3(0, 4, 0));
  EXPECT_EQ(c[4], Vec3(0, 0, 6));
  EXPECT_EQ(c[7], Vec3(2, 4, 6));
}

TEST(Transform, PlacesCentreAndAxes) {
  Obb box;
  box.center = Vec3(1, 0, 0);
  box.half = Vec3(1, 2, 3);
  Pose pose;
  pose.R = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
  pose.t = Vec3(0, 0, 5);
  const Obb moved = transform(pose, box);
  EXPECT_TRUE(moved.center.isApprox(Vec3(0, 1, 5)));
  EXPECT_TRUE(moved.axes.col(0).isApprox(Vec3(0, 1, 0)));
  EXPECT_EQ(moved.half, box.half);
}

}  // namespace
}  // namespace graspcd
