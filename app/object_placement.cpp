#include "object_placement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "command.h"

namespace graspcd::cli {

namespace {

const char* name_of(Placement p) {
  switch (p) {
    case Placement::kScale:
      return "--scale";
    case Placement::kFit:
      return "--fit";
    case Placement::kHand:
      return "--hand";
    case Placement::kUp:
      return "--up";
    case Placement::kYaw:
      return "--yaw";
    case Placement::kPose:
      return "--pose";
    case Placement::kOffset:
      return "--offset";
    case Placement::kWriteScene:
      return "--write-scene";
  }
  return "";
}

bool is_placement(const std::string& name) {
  for (Placement p :
       {Placement::kScale, Placement::kFit, Placement::kHand, Placement::kUp, Placement::kYaw,
        Placement::kPose, Placement::kOffset, Placement::kWriteScene}) {
    if (name == name_of(p)) return true;
  }
  return false;
}

}  // namespace

void add_placement_options(CLI::App& app, PlacementOptions& options,
                           const std::vector<PlacementOption>& added) {
  for (const PlacementOption& a : added) {
    const char* name = name_of(a.option);
    switch (a.option) {
      case Placement::kScale:
        app.add_option(name, options.scale, a.help)->check(number_in_range(kMinScale, kMaxScale));
        break;
      case Placement::kFit:
        app.add_flag(name, options.fit, a.help);
        break;
      case Placement::kHand:
        app.add_option(name, options.hand, a.help)->capture_default_str();
        break;
      case Placement::kUp:
        app.add_option(name, options.up, a.help)->capture_default_str();
        break;
      case Placement::kYaw:
        app.add_option(name, options.yaw, a.help)->check(number_in_range(-360.0, 360.0));
        break;
      case Placement::kPose:
        app.add_option(name, options.pose, a.help)
            ->expected(4)
            ->check(number_in_range(-1e300, 1e300));
        break;
      case Placement::kOffset:
        app.add_option(name, options.offset, a.help)
            ->expected(2)
            ->check(number_in_range(-1.0, 1.0));
        break;
      case Placement::kWriteScene:
        app.add_option(name, options.write_scene, a.help);
        break;
    }
  }
}

void check_placement_options(const CLI::App& app, const std::string& command,
                             const std::string& owner, bool owner_given) {
  const auto given = [&](const char* name) {
    return app.get_option_no_throw(name) != nullptr && app.count(name) > 0;
  };
  for (const CLI::Option* o : app.get_options()) {
    const std::string name = o->get_name();
    if (!owner_given && is_placement(name) && o->count() > 0) {
      throw UsageError(command + ": " + name + " goes with " + owner);
    }
  }
  if (given("--fit") && given("--scale")) {
    throw UsageError(command + ": --scale and --fit exclude each other");
  }
  if (given("--pose") && (given("--up") || given("--yaw"))) {
    throw UsageError(command + ": --pose and --up/--yaw exclude each other");
  }
}

grasp::ObjectPlacement object_placement(const PlacementOptions& options, const std::string& file) {
  grasp::ObjectPlacement placement;
  placement.file = file;
  placement.scale = options.scale;
  placement.fit = options.fit;
  placement.up = options.up;
  placement.yaw_degrees = options.yaw;
  if (options.offset.size() == 2) placement.offset = {options.offset[0], options.offset[1]};
  if (!options.pose.empty()) {
    // Scaled by its largest component first, so that a tiny quaternion (1e-300 0 0 0) normalises
    // rather than underflow to zero.
    std::array<double, 4> q{options.pose[0], options.pose[1], options.pose[2], options.pose[3]};
    double largest = 0;
    for (double x : q) largest = std::max(largest, std::fabs(x));
    if (!std::isfinite(largest) || !(largest > 0)) {
      throw UsageError("--pose: not a finite unit quaternion (W X Y Z, finite and not all zero)");
    }
    double norm = 0;
    for (double& x : q) {
      x /= largest;
      norm += x * x;
    }
    norm = std::sqrt(norm);
    for (double& x : q) x /= norm;
    placement.pose = q;
  }
  return placement;
}

grasp::HandTemplate hand_template(const std::string& hand, const std::string& command) {
  try {
    return grasp::hand_template(hand);
  } catch (const grasp::HandModelsNotFound& e) {
    throw UsageError(e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(command + ": " + e.what());
  }
}

}  // namespace graspcd::cli
