// The served pairs' default (pair_config.h, "contact_reuse": contacts reused within 20 um) on
// whole grasps (grasp.h), each beside exact contacts every step ("contact_reuse" 0, grasp
// --exact): calls answered by reused contacts, the same gripped and held verdicts, no phantom and
// no missed contact by the race's judge (CGAL, contact_judge.h) over the closing, and the true
// meshes' deepest penetration (true_penetration.h) and the hold's drift at most 10% above the
// exact run's or within kResolution of it. (The hard scenes' bounds hold for both:
// hard_scenes_test; the concave grasps' verdicts: concave_*_test.)
//
// Release pass only (ctest label "slow"): ten whole grasps with the true meshes measured.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <memory>
#include <string>

#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/pair_config.h"
#include "graspcd/study/contact_judge.h"
#include "helpers/judged_grasp.h"

namespace graspcd::grasp::default_contacts_test {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;

using testing::expect_no_contact_error;
using testing::judge_closing_steps;
using testing::near_bound;

// One scene's grasp exact and at the default, checked as the file's header says.
void expect_default_as_exact(const std::string& name) {
  SCOPED_TRACE(name);
  const std::string scene = kMjcf + "/" + name + ".xml";
  GraspOptions options;
  options.true_penetration = true;
  options.contact_reuse = 0.0;
  const GraspResult exact = run_grasp(scene, options);
  ASSERT_TRUE(exact.held) << exact.reason;
  EXPECT_EQ(exact.reused_calls, 0u);

  options.contact_reuse.reset();  // the scene's config: the default
  std::unique_ptr<study::ContactJudge> judge;
  judge_closing_steps(scene, options, judge);
  const GraspResult ours = run_grasp(scene, options);
  ASSERT_TRUE(judge);
  EXPECT_GT(ours.reused_calls, 0u);
  EXPECT_EQ(ours.gripped, exact.gripped);
  EXPECT_TRUE(ours.held) << ours.reason;
  expect_no_contact_error(*judge);
  EXPECT_GT(ours.true_penetration.measures, 0);
  EXPECT_LE(ours.true_penetration.max, near_bound(exact.true_penetration.max))
      << "exact " << exact.true_penetration.max * 1e3 << " mm";
  EXPECT_LE(ours.hold_drift, near_bound(exact.hold_drift))
      << "exact " << exact.hold_drift * 1e3 << " mm";
}

TEST(DefaultContacts, TheProjectsHandsKeepTheirVerdictsAndTheJudgeFindsNoError) {
  EXPECT_EQ(mujoco::RegistryConfig{}.contact_reuse, mujoco::RegistryConfig::kDefaultContactReuse);
  for (const char* name : {"example1", "example2", "example3", "hand_triangles"}) {
    expect_default_as_exact(name);
  }
}

// The Robotiq 2F-85 of ../shared/models (the scene's ../../shared/models path; skipped with a
// message without it).
TEST(DefaultContacts, TheRobotiqGripperKeepsItsVerdictAndTheJudgeFindsNoError) {
  if (!std::filesystem::exists(kMjcf + "/../../shared/models/hands/robotiq_2f85/2f85.xml")) {
    GTEST_SKIP() << "the Robotiq hand's models are not at " << kMjcf << "/../../shared/models";
  }
  expect_default_as_exact("real_robotiq_cup");
}

}  // namespace
}  // namespace graspcd::grasp::default_contacts_test
