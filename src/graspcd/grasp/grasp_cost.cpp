#include "graspcd/grasp/grasp_cost.h"

namespace graspcd::grasp {

namespace {

double seconds_between(const timespec& from, const timespec& to) {
  return static_cast<double>(to.tv_sec - from.tv_sec) +
         1e-9 * static_cast<double>(to.tv_nsec - from.tv_nsec);
}

}  // namespace

PartTime GraspCost::total() const {
  PartTime t;
  for (const PartTime& p : parts) t += p;
  return t;
}

PartTime GraspCost::before_first_step() const {
  PartTime t;
  for (CostPart p : {CostPart::kScene, CostPart::kCompile, CostPart::kTrees, CostPart::kPlacement,
                     CostPart::kStartCheck}) {
    t += (*this)[p];
  }
  return t;
}

GraspCost& GraspCost::operator+=(const GraspCost& o) {
  for (std::size_t i = 0; i < kCostParts; ++i) parts[i] += o.parts[i];
  return *this;
}

CostInstant CostInstant::now() {
  CostInstant i;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &i.cpu);
  clock_gettime(CLOCK_MONOTONIC, &i.wall);
  return i;
}

PartTime CostInstant::since(const CostInstant& from) const {
  return {seconds_between(from.cpu, cpu), seconds_between(from.wall, wall)};
}

CostTimer::CostTimer(GraspCost* cost, CostPart part) : cost_(cost), part_(part) {
  if (cost_) start_ = CostInstant::now();
}

PartTime CostTimer::stop() {
  if (!cost_ || stopped_) return {};
  stopped_ = true;
  const PartTime t = CostInstant::now().since(start_);
  (*cost_)[part_] += t;
  return t;
}

}  // namespace graspcd::grasp
