// Whole grasps judged by the race's judge (grasp --judge; study/contact_judge.h), for the scene
// tests that set a served configuration beside another.
#pragma once

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp.h"
#include "graspcd/mujoco/pair_config.h"
#include "graspcd/study/contact_judge.h"

namespace graspcd::testing {

// Makes `options` judge every closing step of the scene's grasp into `judge` (made at the first
// step, from the model): the object and the support the object stands on of the pair config's
// "grasp" section (drive_config.h; the Robotiq's table, which is not the hand's), else the body
// "object" and the world, as `graspcd grasp --judge` does.
inline void judge_closing_steps(const std::string& scene, grasp::GraspOptions& options,
                                std::unique_ptr<study::ContactJudge>& judge) {
  const std::optional<grasp::DriveConfig> drive =
      grasp::load_drive_config(mujoco::pair_config_path(scene));
  options.on_grasp_step = [&judge, drive](const mjModel* m, const mjData* d, int step) {
    if (!judge) {
      judge = drive ? std::make_unique<study::ContactJudge>(m, drive->object, drive->support)
                    : std::make_unique<study::ContactJudge>(m);
    }
    judge->judge_step(m, d, step);
  };
}

// The judge saw contacts and found no phantom and no missed one.
inline void expect_no_contact_error(const study::ContactJudge& judge) {
  EXPECT_GT(judge.summary().contacts, 0u);
  EXPECT_EQ(judge.summary().phantom, 0u);
  EXPECT_EQ(judge.summary().missed, 0u);
}

// At most 10% above `reference`, or within 0.1 mm of it (report/reduction_check.py's criteria;
// 0.1 mm is below the measures' resolution: a drift
// or depth of a few micrometres differs by more than 10% from run to run).
inline double near_bound(double reference) { return std::max(reference * 1.10, reference + 1e-4); }

}  // namespace graspcd::testing
