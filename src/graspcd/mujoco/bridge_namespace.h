// graspcd::bridge, the namespace of the MuJoCo seam up to 0.2, is an alias of graspcd::mujoco for
// one minor version (CHANGELOG.md), so that programs written against 0.2 still compile. The grasp
// experiment, which shared that namespace, is graspcd::grasp and is not installed.
#pragma once

namespace graspcd {
namespace mujoco {}
namespace bridge = mujoco;
}  // namespace graspcd
