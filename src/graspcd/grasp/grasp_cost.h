// Where a grasp's time goes (`graspcd grasp --json`, "cost"; docs/performance.md, "What a grasp
// costs"): the CPU seconds of the thread that ran it and the wall seconds, per part of the work.
//
// The parts, in the order a grasp meets them (kCostPartKeys are their JSON keys):
//   scene             reading the object's mesh and writing its scene (grasp --object)
//   compile           MuJoCo's reading and compiling of the scene (mj_loadXML, with graspcd's
//                     checks before and after: mujoco/model_loading.h)
//   trees             graspcd's trees: the pair registry's (mujoco/registry.h) and the true
//                     meshes' surfaces the penetration is measured on (true_penetration.h)
//   placement         a batch grasp's placing of the object in the compiled model
//                     (object_batch.h) and the reset of the state
//   start_check       the start state on the true meshes and, under native collision, the hulls
//                     (start_check.h)
//   physics           the physics steps (MuJoCo's step with graspcd's served contacts) and the
//                     run's watch of the object and its contacts after each
//   true_penetration  the true meshes' penetration, once per grasp step (true_penetration.h)
//   judge             the caller's per-grasp-step callback (GraspOptions::on_grasp_step: the
//                     race's judge, a study's recording)
//   write             building the grasp's output document (JSON or text)
// A part that did not run is zero. In a batch (object_batch.h) the parts done once for the
// batch (scene, compile, trees) are the first grasp's.
#pragma once

#include <array>
#include <cstddef>
#include <ctime>

namespace graspcd::grasp {

enum class CostPart : std::size_t {
  kScene,
  kCompile,
  kTrees,
  kPlacement,
  kStartCheck,
  kPhysics,
  kTruePenetration,
  kJudge,
  kWrite,
  kCount
};

inline constexpr std::size_t kCostParts = static_cast<std::size_t>(CostPart::kCount);
inline constexpr std::array<const char*, kCostParts> kCostPartKeys = {
    "scene",   "compile",          "trees", "placement", "start_check",
    "physics", "true_penetration", "judge", "write"};

// CPU seconds (of the thread) and wall seconds.
struct PartTime {
  double cpu_s = 0;
  double wall_s = 0;
  PartTime& operator+=(const PartTime& o) {
    cpu_s += o.cpu_s;
    wall_s += o.wall_s;
    return *this;
  }
  PartTime& operator-=(const PartTime& o) {
    cpu_s -= o.cpu_s;
    wall_s -= o.wall_s;
    return *this;
  }
};

struct GraspCost {
  std::array<PartTime, kCostParts> parts{};
  PartTime& operator[](CostPart p) { return parts[static_cast<std::size_t>(p)]; }
  const PartTime& operator[](CostPart p) const { return parts[static_cast<std::size_t>(p)]; }
  // Every part.
  PartTime total() const;
  // The parts before the first physics step: scene, compile, trees, placement, start check.
  PartTime before_first_step() const;
  GraspCost& operator+=(const GraspCost& o);
};

// A point in time on both clocks: the calling thread's CPU clock (CLOCK_THREAD_CPUTIME_ID) and
// the steady clock.
struct CostInstant {
  timespec cpu{};
  timespec wall{};
  static CostInstant now();
  // From `from` to this instant.
  PartTime since(const CostInstant& from) const;
};

// Adds the time from its construction to its destruction (or to stop()) to one part of `cost`;
// does nothing when `cost` is null.
class CostTimer {
 public:
  CostTimer(GraspCost* cost, CostPart part);
  ~CostTimer() { stop(); }
  CostTimer(const CostTimer&) = delete;
  CostTimer& operator=(const CostTimer&) = delete;
  // Adds the time so far (once); returns it.
  PartTime stop();

 private:
  GraspCost* cost_;
  CostPart part_;
  CostInstant start_;
  bool stopped_ = false;
};

}  // namespace graspcd::grasp
