// Every separator gives CGAL's answers through the tree query, at random poses and along
// continuous trajectories, in both modes; the caches are bounded, hit, and reset.
#include "graspcd/core/separators.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>

#include "helpers/real_models.h"
#include "helpers/tree_agreement.h"

namespace graspcd {
namespace {

using testing::Agreement;
using testing::scaled;

// Small caps keep the perceptron methods fast; the cap changes cost, never the answer.
// perceptron-nodisp almost never proves separation away from the origin, so its queries descend
// to nearly every leaf (~80x SAT's box tests here); being stateless, it is checked on every tenth
// case only.
DetectorOptions small_caps() {
  DetectorOptions o;
  o.cap = 60;
  o.switch_passes = 20;
  return o;
}

std::vector<testing::PoseCase> subset_for(Method m, const std::vector<testing::PoseCase>& cases) {
  if (m != Method::kPerceptronNoDisp) return cases;
  std::vector<testing::PoseCase> every_tenth;
  for (std::size_t i = 0; i < cases.size(); i += 10) every_tenth.push_back(cases[i]);
  return every_tenth;
}

TEST(Separators, EveryMethodMatchesBruteForceAtRandomPoses) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 24, 12);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 10, 14);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  const std::vector<testing::PoseCase> cases = testing::cases_around(torus, sphere, scaled(40), 7);
  for (Method m : all_methods()) {
    Detector detector(m, small_caps());
    Agreement agreement;
    testing::check_cases(detector, ta, tb, subset_for(m, cases), agreement);
    EXPECT_EQ(agreement.poses, static_cast<int>(subset_for(m, cases).size())) << method_name(m);
    EXPECT_GT(agreement.intersecting, 0);
  }
}

// A grasp-like trajectory: b approaches a in small steps, touches, and penetrates. The warm and
// cached methods carry their caches from step to step.
TEST(Separators, EveryMethodMatchesBruteForceAlongATrajectory) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 24, 12);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 10, 14);
  const ObbTree ta = ObbTree::build(torus), tb = ObbTree::build(sphere);
  const int steps = scaled(120);
  std::vector<testing::PoseCase> cases;
  for (int step = 0; step < steps; ++step) {
    Pose pose;
    const double angle = 0.003 * step;  // the paper's grasp step, in radians
    pose.R = Eigen::AngleAxisd(angle, Vec3(0.3, 0.2, 1).normalized()).toRotationMatrix();
    // From 3.6 cm between the sphere's centre and the tube's axis (no contact) to 2 cm (contact).
    pose.t = Vec3(0.04 + 0.03 * (1 - static_cast<double>(step) / steps), 0.0, 0.02);
    cases.push_back(testing::make_case(torus, sphere, pose));
  }
  for (Method m : all_methods()) {
    Detector detector(m, small_caps());
    Agreement agreement;
    testing::check_cases(detector, ta, tb, subset_for(m, cases), agreement);
    if (HasFatalFailure()) return;
    EXPECT_GT(agreement.intersecting, 0) << method_name(m);
    EXPECT_LT(agreement.intersecting, steps) << method_name(m);
    if (m == Method::kSatCached || m == Method::kPerceptronWarm) {
      EXPECT_GT(agreement.counters.cache_hits, 0u) << method_name(m);
    }
    if (uses_perceptron(m)) {
      EXPECT_GT(agreement.counters.perceptron_passes, 0u);
    }
    if (m == Method::kNeuroSat || m == Method::kNeuroSatSticky) {
      EXPECT_GT(agreement.counters.sat_fallbacks, 0u);
    }
  }
}

// The paper's own caps (1,500 passes, switch at 300) give the same answers as the small ones.
TEST(Separators, DefaultCapsGiveTheSameAnswers) {
  const TriangleMesh torus = testing::make_torus(0.04, 0.012, 16, 8);
  const TriangleMesh sphere = testing::make_uv_sphere(0.015, 6, 8);
  const std::vector<testing::PoseCase> cases = testing::cases_around(torus, sphere, scaled(10), 8);
  for (Method m : {Method::kPerceptron, Method::kNeuroSat, Method::kNeuroSatSticky}) {
    Detector detector(m);
    Agreement agreement;
    testing::check_cases(detector, ObbTree::build(torus), ObbTree::build(sphere), cases, agreement);
    EXPECT_GT(agreement.intersecting, 0);
  }
}

// The foundation's real meshes (tree_query_test): cube_cup_hi against the mug scaled to metres,
// on 200 of its kind of poses (40 directions x 5 distance classes). Caps of 8 and 4 keep the deep
// overlaps affordable (the cap changes cost, never the answer). perceptron-nodisp is left out
// here: away from the origin it proves almost no node pair disjoint, so a deep overlap of these
// 15k x 25k-triangle meshes descends towards every leaf pair; it is checked on the generated
// meshes above.
TEST(Separators, EveryMethodMatchesBruteForceOnRealMeshes) {
  std::string why_not;
  const std::optional<testing::CupAndMug> real = testing::load_cup_and_mug(why_not);
  if (!real) GTEST_SKIP() << why_not;
  const TriangleMesh& cup = real->cup;
  const TriangleMesh& mug = real->mug;
  const ObbTree ta = ObbTree::build(cup), tb = ObbTree::build(mug);
  const std::vector<testing::PoseCase> cases = testing::cases_around(cup, mug, scaled(40), 2);
  DetectorOptions tiny_caps;
  tiny_caps.cap = 8;
  tiny_caps.switch_passes = 4;
  for (Method m : all_methods()) {
    if (m == Method::kPerceptronNoDisp) continue;
    Detector detector(m, tiny_caps);
    Agreement agreement;
    testing::check_cases(detector, ta, tb, cases, agreement);
    if (HasFatalFailure()) return;
    EXPECT_GT(agreement.intersecting, 0) << method_name(m);
    std::printf("%-18s %4d poses agree, %8llu box tests\n", method_name(m), agreement.poses,
                static_cast<unsigned long long>(agreement.counters.box_tests));
  }
}

TEST(Separators, WarmCacheHitsAndResetForgets) {
  Obb a, b;
  a.half = b.half = Vec3(0.01, 0.01, 0.01);
  b.center = Vec3(0.03, 0.001, 0.0);
  for (Method m : {Method::kSatCached, Method::kPerceptronWarm}) {
    Detector detector(m);
    QueryCounters c;
    ASSERT_TRUE(detector.box_disjoint(a, b, c));
    EXPECT_EQ(c.cache_hits, 0u);
    ASSERT_TRUE(detector.box_disjoint(a, b, c));
    EXPECT_EQ(c.cache_hits, 1u) << method_name(m);
    detector.reset();
    ASSERT_TRUE(detector.box_disjoint(a, b, c));
    EXPECT_EQ(c.cache_hits, 1u) << method_name(m);  // nothing remembered after reset
  }
}

TEST(Separators, StickyNeuroSatSwitchesAPairToSat) {
  Obb a, b;
  a.half = b.half = Vec3(0.01, 0.01, 0.01);
  b.center = Vec3(0.015, 0.0, 0.0);  // overlapping: the perceptron runs to the switch
  DetectorOptions o;
  o.switch_passes = 5;
  Detector detector(Method::kNeuroSatSticky, o);
  QueryCounters c;
  EXPECT_FALSE(detector.box_disjoint(a, b, c));
  EXPECT_EQ(c.perceptron_passes, 5u);
  EXPECT_FALSE(detector.box_disjoint(a, b, c));
  EXPECT_EQ(c.perceptron_passes, 5u);  // the second test went straight to SAT
  EXPECT_EQ(c.sat_fallbacks, 2u);
}

TEST(PairCache, BoundedStoreFindEraseReplace) {
  PairCache<int> cache(100);  // rounded up to 128 slots
  const std::size_t bytes = cache.memory_bytes();
  for (int i = 0; i < 10000; ++i) cache.store(i, i + 1, i);
  EXPECT_EQ(cache.memory_bytes(), bytes);  // bounded whatever the number of pairs
  ASSERT_NE(cache.find(9999, 10000), nullptr);
  EXPECT_EQ(*cache.find(9999, 10000), 9999);
  EXPECT_EQ(cache.find(10000, 9999), nullptr);  // ordered pairs
  cache.erase(9999, 10000);
  EXPECT_EQ(cache.find(9999, 10000), nullptr);
  int found = 0;
  for (int i = 0; i < 10000; ++i) found += cache.find(i, i + 1) != nullptr;
  EXPECT_LE(found, 128);
  cache.reset();
  for (int i = 0; i < 10000; ++i) ASSERT_EQ(cache.find(i, i + 1), nullptr);
}

TEST(Methods, NamesRoundTrip) {
  for (Method m : all_methods()) EXPECT_EQ(parse_method(method_name(m)), m);
  EXPECT_FALSE(parse_method("SAT").has_value());
  EXPECT_THROW(Detector(Method::kPerceptron, DetectorOptions{0, 300, 16}), std::invalid_argument);
}

}  // namespace
}  // namespace graspcd
