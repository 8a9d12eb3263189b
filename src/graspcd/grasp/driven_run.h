// A hand that is not ours in a grasp run (hand_run.h), driven through its own actuators by the
// config's "grasp" section (drive_config.h; grasp.h, run_grasp). Grasp step k adds each closing
// actuator's step to its control (clamped to its ctrlrange) and runs physics_steps_per_grasp_step
// physics steps (mj_step: the hand's own position servos track the controls); an actuator stops
// when a geom of each of its touch patterns has touched the object, or at the end of its
// ctrlrange. Then the squeeze (each actuator's squeeze over squeeze_time, then settle_time), the
// lift (the lift actuator's control moves by `by` along a cosine ramp over lift_time) and the
// hold, judged as on our hands with heights along -gravity measured from the support body.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

#include "graspcd/grasp/drive_config.h"
#include "graspcd/grasp/grasp_result.h"
#include "graspcd/grasp/hand_run.h"
#include "graspcd/mujoco/registry.h"

namespace graspcd::grasp {

class DrivenRun : public HandRun {
 public:
  // Throws a io::InputError naming `config` for a body, actuator or touch pattern the scene
  // does not have.
  DrivenRun(const mjModel* m, mjData* d, mujoco::Registry* registry, const DriveConfig& drive,
            const std::string& scene, const std::string& config);

 private:
  void advance() override;
  double object_height() const override { return height_of(object_); }
  int support_body() const override { return support_; }
  void begin_grasp_step(int k) override;
  void grasp_step_targets(int, int) override {}
  bool closing_done(int k, const std::vector<bool>& touched, const GraspResult& result) override;
  void begin_squeeze() override;
  void squeeze_targets(long i, long steps) override;
  void begin_lift() override;
  void lift_targets(long i, long steps) override;

  // The height of a body along -gravity above the support body.
  double height_of(int body) const;
  // The control of actuator a clamped to its ctrlrange.
  double clamp_ctrl(int a, double u) const;

  const DriveConfig& drive_;
  int support_ = 0, lift_ = -1;
  std::array<double, 3> up_{};
  std::vector<int> close_;                           // actuator ids, by drive
  std::vector<std::vector<int>> segments_of_drive_;  // segment ids, by drive
  std::vector<bool> stopped_;                        // by drive
  std::vector<double> closed_;                       // controls at the squeeze's start, by drive
  double lift_start_ = 0;
};

}  // namespace graspcd::grasp
