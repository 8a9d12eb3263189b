// The six-direction test of a grasp (docs/run-record.md, "The six-direction test"): after the
// hold, six runs each start from the held state (mjData copied whole, and the registry's
// per-pair state), with the support taken away (its body tree's geoms collide with nothing),
// gravity off, the hand held where it is (a driven hand's controls, our hand's targets, as at the
// end of the hold) and the object alone pulled by its weight (the mass of its body tree times
// |g|, xfrc_applied at its centre of mass) along +x, -x, +y, -y, +z, -z of the hand body's frame
// at the end of the hold, for kSixDirectionsDuration. A direction passes when at its end the
// object still touches the hand (true meshes, true_touch.h) and has moved less than
// kSixDirectionsDistance relative to the hand.
//
// After DexGraspNet's validator (grasp_generation/utils/isaac_validator.py in
// PKU-EPIC/DexGraspNet): six copies of the grasped state, gravity along +-x, +-y, +-z of the
// hand, the hand fixed and without gravity, 100 steps of 1/60 s with 2 substeps, friction 3.0; a
// direction passes when a hand-object contact remains at the end (PhysX's contact offset: within
// 1 cm). The project keeps the scene's friction and time step, runs 1 s, and asks the object to
// stay touching (1 mm) and within 1 cm of where the hand held it.
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

namespace graspcd::grasp {

inline constexpr double kSixDirectionsDuration = 1.0;   // s
inline constexpr double kSixDirectionsDistance = 0.01;  // m
inline constexpr int kSixDirections = 6;

// "+x", "-x", "+y", "-y", "+z", "-z" for k = 0 .. 5.
std::string six_direction_name(int k);

// Direction k as a world unit vector: column k / 2 of the hand body's rotation, negated for odd k.
std::array<double, 3> six_direction(const mjData* d, int hand, int k);

// The model as the six runs need it, restored when this goes: gravity off, and every geom of the
// support's body tree (support 0: the world body's own geoms) with contype = conaffinity = 0.
// `weight()` is the object's weight, the mass of its body tree times |g| as the model had it.
class SixDirectionsModel {
 public:
  SixDirectionsModel(mjModel* m, int object, int support);
  ~SixDirectionsModel();
  SixDirectionsModel(const SixDirectionsModel&) = delete;
  SixDirectionsModel& operator=(const SixDirectionsModel&) = delete;
  double weight() const { return weight_; }

 private:
  mjModel* m_;
  std::array<mjtNum, 3> gravity_{};
  std::vector<std::array<int, 3>> geoms_;  // geom, contype, conaffinity as they were
  double weight_ = 0;
};

}  // namespace graspcd::grasp
