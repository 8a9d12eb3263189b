// Our four-finger hand (grasp.h, "Scene contract") in a grasp run (hand_run.h): every joint under
// one ComputedTorqueController (eq. (12)-(16)); the phases move its targets.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

#include "graspcd/grasp/controllers.h"
#include "graspcd/grasp/grasp_result.h"
#include "graspcd/grasp/hand_run.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

class GraspRun : public HandRun {
 public:
  GraspRun(const mjModel* m, mjData* d, mujoco::Registry* registry, const GraspOptions& options,
           const std::string& scene);

 private:
  void advance() override;
  double object_height() const override;
  void begin_grasp_step(int k) override;
  void grasp_step_targets(int p, int n) override;
  bool closing_done(int k, const std::vector<bool>& touched, const GraspResult& result) override;
  void end_closing() override;
  void begin_squeeze() override;
  void squeeze_targets(long i, long steps) override;
  void begin_lift() override;
  void lift_targets(long i, long steps) override;
  void end_lift() override;

  const GraspOptions& options_;
  std::string scene_;
  ComputedTorqueController controller_;
  std::vector<double> q_d_, qd_d_, qdd_d_;  // the controller's targets, by joint
  std::array<double, kFingerSegments> upper_{};
  // The closing: the segments that stopped, and the current grasp step's ramp of each.
  std::array<bool, kFingerSegments> stopped_{};
  std::array<double, kFingerSegments> step_start_{}, step_end_{};
  // The squeeze starts from the closed targets; the lift moves arm2 and arm3 by lift_angle_.
  std::vector<double> closed_;
  double lift_angle_ = 0, arm2_start_ = 0, arm3_start_ = 0;
};

}  // namespace graspcd::grasp
