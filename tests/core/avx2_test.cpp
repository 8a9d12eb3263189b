// The tree query's AVX2 kernels (src/graspcd/core/avx2.h) against their scalar twins, the 15-axis
// box test of sat.h and apply_pose of geometry.h, and their run-time choice (use_avx2).
//
// What is asserted:
//  - on random frames (rotations and arbitrary matrices), on grid frames whose gaps tie their
//    bounds exactly (small dyadic numbers: every product and sum exact), and on frames holding
//    zeros of both signs, infinities and NaNs, the box test's kernel returns the scalar test's
//    axis;
//  - the posing kernel gives apply_pose's doubles bit for bit (random poses and points at scales
//    from 1e-6 to 1e6, and zeros of both signs, infinities and NaNs among them);
//  - use_avx2 turns the kernels on exactly where the processor has AVX2, and a tree query
//    (descent from the roots and along a front) visits the same node pairs, counts the same work,
//    finds the same triangle pairs and keeps the same front, gaps included, either way.
// On a processor without AVX2 the kernel tests are skipped and the dispatch test checks that the
// scalar test stays on.
//
// GRASPCD_TEST_SCALE (a positive double, default 1) multiplies the number of random frames (never
// below 1000), so that the sanitizer build can run a subset.
#include "graspcd/core/avx2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <vector>

#include "graspcd/core/sat.h"
#include "graspcd/core/tree_query.h"
#include "graspcd/support/meshes.h"
#include "graspcd/support/seeded.h"
#include "helpers/test_scale.h"

namespace graspcd {
namespace {

using seeded::Rng;

// Restores the process-wide choice at the end of a test.
struct KeepChoice {
  bool was = detail::avx2_active();
  ~KeepChoice() { use_avx2(was); }
};

SatAxis scalar(const Mat3& R, const Vec3& T, const Vec3& a, const Vec3& b, double slack) {
  return sat_separating_axis_in_a_scalar(R, R.cwiseAbs(), T, a, b, slack);
}

SatAxis batched(const Mat3& R, const Vec3& T, const Vec3& a, const Vec3& b, double slack) {
  return sat_separating_axis_in_a_avx2(R.data(), T.data(), a.data(), b.data(), slack);
}

// Counts the frames where the two disagree (printing the first few) and, per axis, how often the
// scalar test reported it (so that the inputs are seen to reach every axis and "none").
struct Compare {
  std::int64_t frames = 0, mismatches = 0;
  std::int64_t by_axis[16] = {};
  void operator()(const Mat3& R, const Vec3& T, const Vec3& a, const Vec3& b, double slack) {
    const SatAxis s = scalar(R, T, a, b, slack), v = batched(R, T, a, b, slack);
    ++frames;
    ++by_axis[s];
    if (s == v) return;
    if (++mismatches <= 5) {
      ADD_FAILURE() << "scalar " << s << ", AVX2 " << v << "\nR =\n"
                    << R << "\nT = " << T.transpose() << "\na = " << a.transpose()
                    << "\nb = " << b.transpose() << "\nslack = " << slack;
    }
  }
};

TEST(Avx2, BoxTestKernelMatchesScalarOnRandomFrames) {
  if (!avx2_supported()) GTEST_SKIP() << "no AVX2 on this processor";
  const std::int64_t n = testing::scaled(200000, 1000);
  Rng rng(0xa5a2);
  Compare compare;
  for (std::int64_t i = 0; i < n; ++i) {
    // A rotation (the descent's frames), or any matrix (the kernel assumes nothing of R).
    const Mat3 R = i % 4 == 3 ? Mat3(Mat3::Random()) : seeded::random_rotation(rng);
    const double size = seeded::log_uniform(rng, 1e-3, 10.0);
    const Vec3 a = seeded::uniform_vec3(rng, 0, size), b = seeded::uniform_vec3(rng, 0, size);
    // Centres from deep overlap to well apart, so that every axis and "none" occur.
    const Vec3 T = seeded::uniform_vec3(rng, -3 * size, 3 * size);
    const double slack = i % 8 == 0 ? 0.0 : 1e-8 * size;
    compare(R, T, a, b, slack);
  }
  EXPECT_EQ(compare.mismatches, 0);
  for (int axis = 0; axis <= 15; ++axis) {
    EXPECT_GT(compare.by_axis[axis], 0) << "axis " << axis << " never reported";
  }
}

TEST(Avx2, BoxTestKernelMatchesScalarOnExactTiesAndSpecialValues) {
  if (!avx2_supported()) GTEST_SKIP() << "no AVX2 on this processor";
  Rng rng(0x71e5);
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Small dyadic values: every product and sum below is exact, so a gap equals its bound exactly
  // as often as it exceeds it, and the strict comparison decides.
  const double grid[] = {-1.0, -0.5, -0.0, 0.0, 0.25, 0.5, 1.0};
  const double halves[] = {0.0, 0.25, 0.5, 1.0};
  const double special[] = {0.0, -0.0, inf, -inf, nan, 1e-300, -1e300};
  const auto pick = [&rng](const auto& values) {
    return values[seeded::uniform_int(rng, 0, static_cast<int>(std::size(values)) - 1)];
  };
  Compare ties, odd;
  const std::int64_t n = testing::scaled(100000, 1000);
  for (std::int64_t i = 0; i < n; ++i) {
    Mat3 R;
    Vec3 T, a, b;
    for (int k = 0; k < 9; ++k) R.data()[k] = pick(grid);
    for (int k = 0; k < 3; ++k) {
      T[k] = 0.25 * static_cast<double>(seeded::uniform_int(rng, -8, 8));
      a[k] = pick(halves);
      b[k] = pick(halves);
    }
    const double slack = i % 2 ? 0.0 : 0.25;
    ties(R, T, a, b, slack);
    // The same frame with a few entries replaced by zeros of either sign, infinities, NaNs and
    // extreme magnitudes.
    for (int m = 0; m < 3; ++m) {
      const int which = seeded::uniform_int(rng, 0, 17);
      const double x = pick(special);
      if (which < 9) {
        R.data()[which] = x;
      } else if (which < 12) {
        T[which - 9] = x;
      } else if (which < 15) {
        a[which - 12] = std::fabs(x);
      } else {
        b[which - 15] = std::fabs(x);
      }
    }
    odd(R, T, a, b, slack);
  }
  EXPECT_EQ(ties.mismatches, 0);
  EXPECT_EQ(odd.mismatches, 0);
  for (int axis = 0; axis <= 15; ++axis) {
    EXPECT_GT(ties.by_axis[axis], 0) << "axis " << axis << " never reported on the grid";
  }
  EXPECT_GT(odd.by_axis[0], 0);
}

// The nine doubles of a triangle, compared as bits (a NaN equals itself, 0 and -0 differ).
bool same_bits(const Triangle& x, const Triangle& y) { return std::memcmp(&x, &y, sizeof x) == 0; }

TEST(Avx2, PosingKernelMatchesApplyPose) {
  if (!avx2_supported()) GTEST_SKIP() << "no AVX2 on this processor";
  const std::int64_t n = testing::scaled(100000, 1000);
  Rng rng(0x905e);
  const double special[] = {0.0,
                            -0.0,
                            std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::quiet_NaN(),
                            1e-310};
  std::int64_t mismatches = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    Pose pose;
    pose.R = i % 4 == 3 ? Mat3(Mat3::Random()) : seeded::random_rotation(rng);
    const double scale = seeded::log_uniform(rng, 1e-6, 1e6);
    pose.t = seeded::uniform_vec3(rng, -scale, scale);
    Triangle t;
    for (Vec3& v : t.v) v = seeded::uniform_vec3(rng, -scale, scale);
    if (i % 16 == 0) {
      // A special value in a random place of the pose or the triangle.
      const double x = special[seeded::uniform_int(rng, 0, 5)];
      const int where = seeded::uniform_int(rng, 0, 20);
      if (where < 9) {
        pose.R.data()[where] = x;
      } else if (where < 12) {
        pose.t[where - 9] = x;
      } else {
        t.v[(where - 12) / 3][(where - 12) % 3] = x;
      }
    }
    Triangle batched;
    apply_pose_avx2(pose.R.data(), pose.t.data(), t.v[0].data(), batched.v[0].data());
    const Triangle scalar = apply_pose(pose, t);
    if (!same_bits(batched, scalar) && ++mismatches <= 5) {
      ADD_FAILURE() << "pose " << i << ": AVX2 " << batched.v[0].transpose() << " / "
                    << batched.v[1].transpose() << " / " << batched.v[2].transpose() << ", scalar "
                    << scalar.v[0].transpose() << " / " << scalar.v[1].transpose() << " / "
                    << scalar.v[2].transpose();
    }
    // And through the tree query's entry, with the kernels on.
    if (!same_bits(detail::posed_triangle(pose, t), scalar)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(Avx2, DispatchEitherWayGivesTheSameQueries) {
  KeepChoice keep;
  EXPECT_FALSE(use_avx2(false));
  EXPECT_FALSE(detail::avx2_active());
  EXPECT_EQ(use_avx2(true), avx2_supported());
  EXPECT_EQ(detail::avx2_active(), avx2_supported());

  const ObbTree ta = ObbTree::build(testing::make_torus(0.04, 0.012, 30, 16));
  const ObbTree tb = ObbTree::build(testing::make_uv_sphere(0.015, 12, 16));
  // One path of poses along the torus's rim, in and out of contact, with a front followed along
  // it; each query run with the scalar test and with the kernel.
  struct Run {
    QueryCounters roots, coherent;
    std::vector<TrianglePair> pairs_roots, pairs_coherent;
    QueryFront front;
  };
  Run runs[2];
  std::uint64_t hits = 0;
  for (int i = 0; i < 150; ++i) {
    Pose pose;
    pose.R = seeded::rotation_about(Vec3(0.3, 0.5, 0.8).normalized(), 0.004 * i);
    const double r = 0.066 + 0.004 * std::sin(0.05 * i), angle = 0.004 * i;
    pose.t = Vec3(r * std::cos(angle), r * std::sin(angle), 0.002);
    for (int k = 0; k < 2; ++k) {
      use_avx2(k == 1);
      Run& run = runs[k];
      SatSeparator sat;
      run.pairs_roots.clear();
      run.pairs_coherent.clear();
      collide(ta, tb, pose, QueryMode::kAllContacts, sat, run.roots, &run.pairs_roots);
      collide_coherent(ta, tb, pose, sat, run.coherent, &run.pairs_coherent, run.front);
    }
    hits += !runs[0].pairs_roots.empty();
    ASSERT_EQ(runs[0].pairs_roots, runs[1].pairs_roots) << "pose " << i;
    ASSERT_EQ(runs[0].pairs_coherent, runs[1].pairs_coherent) << "pose " << i;
    ASSERT_EQ(runs[0].front.valid, runs[1].front.valid) << "pose " << i;
    ASSERT_EQ(runs[0].front.pairs.size(), runs[1].front.pairs.size()) << "pose " << i;
    for (std::size_t p = 0; p < runs[0].front.pairs.size(); ++p) {
      const NodePair& x = runs[0].front.pairs[p];
      const NodePair& y = runs[1].front.pairs[p];
      ASSERT_TRUE(x.a == y.a && x.b == y.b && x.disjoint == y.disjoint && x.gap == y.gap)
          << "pose " << i << " front pair " << p;
    }
  }
  for (const auto member : {&QueryCounters::box_tests, &QueryCounters::front_skips,
                            &QueryCounters::tri_tests, &QueryCounters::tri_pairs}) {
    EXPECT_EQ(runs[0].roots.*member, runs[1].roots.*member);
    EXPECT_EQ(runs[0].coherent.*member, runs[1].coherent.*member);
  }
  // The path meets the sphere and leaves it again.
  EXPECT_GT(hits, 20u);
  EXPECT_LT(hits, 140u);
  std::printf("AVX2 %s; %llu box tests from the roots, %llu along the front\n",
              avx2_supported() ? "supported" : "not supported",
              static_cast<unsigned long long>(runs[0].roots.box_tests),
              static_cast<unsigned long long>(runs[0].coherent.box_tests));
}

}  // namespace
}  // namespace graspcd
