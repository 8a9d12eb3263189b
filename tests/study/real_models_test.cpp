// The real hands of ../shared/models in our scenes (mjcf/real_*.xml): the Robotiq 2F-85, driven
// by its pair config's "grasp" section, closes on cube_cup_hi, its pads touch the real surface,
// it lifts the cup, and every served pair agrees with CGAL at every closing grasp step; the
// Shadow hand does the same with the glass.
// Skipped with a message when ../shared/models is absent, and under the sanitizer scale
// (GRASPCD_TEST_SCALE < 1): the gripper's meshes hold 63,706 faces and CGAL's brute force over
// the 45 grasp steps takes seconds in Release, minutes under ASan.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "graspcd/core/separators.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/study/validate.h"
#include "helpers/test_scale.h"

namespace graspcd::study {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(GRASPCD_SOURCE_DIR) + "/mjcf/real_robotiq_cup.xml";
const std::string kShadowScene = std::string(GRASPCD_SOURCE_DIR) + "/mjcf/real_shadow_glass.xml";

bool skip_reason(std::string& why) {
  if (!fs::exists(fs::path(GRASPCD_MODELS_DIR) / "hands" / "robotiq_2f85" / "2f85.xml")) {
    why = "real models not found in " + std::string(GRASPCD_MODELS_DIR);
    return true;
  }
  if (testing::test_scale() < 1.0) {
    why = "heavy real-model grasp skipped at GRASPCD_TEST_SCALE < 1 (sanitizer pass)";
    return true;
  }
  return false;
}

// The one method's rows: every pair checked at every state (the closing's grasp steps and the
// squeeze's states) agrees with CGAL, none missed or false. Returns CGAL's hits over the pairs.
int expect_every_check_agrees(const ValidationReport& report) {
  EXPECT_EQ(report.methods.size(), 1u);
  int states = 0;
  for (const auto& phase : report.phases) states += phase.states;
  EXPECT_GT(states, report.steps) << "the squeeze is checked";
  int hits = 0;
  for (const auto& table : report.methods) {
    for (const PairRow& row : table.rows) {
      EXPECT_EQ(row.agree, row.steps) << row.pair;
      EXPECT_EQ(row.steps, states) << row.pair;
      EXPECT_EQ(row.missed, 0) << row.pair;
      EXPECT_EQ(row.false_contacts, 0) << row.pair;
      hits += row.truth_hits;
    }
  }
  return hits;
}

// Validates the scene's grasp (at most max_steps closing steps) with SAT against CGAL.
ValidationReport validate_with_sat(const std::string& scene, int max_steps) {
  ValidateOptions options;
  options.max_steps = max_steps;
  return validate_scene(scene, {detector_tester(Method::kSat, DetectorOptions{})}, options);
}

TEST(RealModels, RobotiqGraspsTheCupAndLiftsIt) {
  std::string why;
  if (skip_reason(why)) GTEST_SKIP() << why;
  grasp::GraspOptions options;
  options.max_steps = 80;
  const grasp::GraspResult r = grasp::run_grasp(kScene, options);
  ASSERT_EQ(r.segments, (std::vector<std::string>{"body:left_pad", "body:right_pad"}));
  // Both pads touch the cup's real surface within the closing, then it is lifted and held.
  EXPECT_TRUE(r.gripped);
  EXPECT_GT(r.first_contact[0], 5);
  EXPECT_GT(r.first_contact[1], 5);
  EXPECT_LT(r.steps.size(), 80u);
  EXPECT_GT(r.max_contacts, 0);
  EXPECT_TRUE(r.held) << "height " << r.object_z_initial << " -> " << r.object_z_final;
  EXPECT_GT(r.object_z_final, r.object_z_initial + 0.05);  // the lift is 6 cm
  EXPECT_GT(r.detection_ns_close, 0u);
}

TEST(RealModels, RobotiqGraspAgreesWithCgalAtEveryStep) {
  std::string why;
  if (skip_reason(why)) GTEST_SKIP() << why;
  const ValidationReport report = validate_with_sat(kScene, 80);
  EXPECT_TRUE(report.gripped);
  EXPECT_FALSE(report.missed_any());
  // CGAL saw the pads touch: the check covered contact, not only misses.
  EXPECT_GT(expect_every_check_agrees(report), 0);
}

// The Shadow hand's four fingers, each closed by two of its own actuators, hook over the glass
// (mesh distal phalanges, capsule middles) and hold it in the lift; every served pair agrees with
// CGAL at every closing grasp step.
TEST(RealModels, ShadowHandHooksTheGlassAndAgreesWithCgal) {
  std::string why;
  if (skip_reason(why)) GTEST_SKIP() << why;
  const ValidationReport report = validate_with_sat(kShadowScene, 200);
  EXPECT_TRUE(report.gripped);  // every finger's distal phalanx touched
  EXPECT_LT(report.steps, 200);
  EXPECT_FALSE(report.missed_any());
  EXPECT_GT(expect_every_check_agrees(report), 0);  // CGAL saw the fingers touch
  grasp::GraspOptions grasp;
  grasp.max_steps = 200;
  const grasp::GraspResult r = grasp::run_grasp(kShadowScene, grasp);
  EXPECT_TRUE(r.gripped);
  EXPECT_TRUE(r.held) << "height " << r.object_z_initial << " -> " << r.object_z_final;
  EXPECT_GT(r.object_z_final, r.object_z_initial + 0.05);  // the lift is 6 cm
}

}  // namespace
}  // namespace graspcd::study
