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

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/pair_config.h"
#include "graspcd/study/contact_judge.h"

namespace graspcd::grasp {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;

constexpr double kRelative = 0.10;
constexpr double kResolution = 1e-4;  // metres: below it a drift or depth differs by noise

double bound(double exact) { return std::max(exact * (1 + kRelative), exact + kResolution); }

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
  // The race's judge (grasp --judge): the object and the support the object stands on of the
  // config's "grasp" section (the Robotiq's table, which is not the hand's), else the body
  // "object" and the world.
  const std::optional<DriveConfig> drive = load_drive_config(mujoco::pair_config_path(scene));
  std::unique_ptr<study::ContactJudge> judge;
  options.on_grasp_step = [&judge, &drive](const mjModel* m, const mjData* d, int step) {
    if (!judge) {
      judge = drive ? std::make_unique<study::ContactJudge>(m, drive->object, drive->support)
                    : std::make_unique<study::ContactJudge>(m);
    }
    judge->judge_step(m, d, step);
  };
  const GraspResult ours = run_grasp(scene, options);
  ASSERT_TRUE(judge);
  EXPECT_GT(ours.reused_calls, 0u);
  EXPECT_EQ(ours.gripped, exact.gripped);
  EXPECT_TRUE(ours.held) << ours.reason;
  EXPECT_GT(judge->summary().contacts, 0u);
  EXPECT_EQ(judge->summary().phantom, 0u);
  EXPECT_EQ(judge->summary().missed, 0u);
  EXPECT_GT(ours.true_penetration.measures, 0);
  EXPECT_LE(ours.true_penetration.max, bound(exact.true_penetration.max))
      << "exact " << exact.true_penetration.max * 1e3 << " mm";
  EXPECT_LE(ours.hold_drift, bound(exact.hold_drift))
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
}  // namespace graspcd::grasp
