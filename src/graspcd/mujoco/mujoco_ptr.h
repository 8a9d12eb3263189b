// Owning pointers for MuJoCo's model and data: mj_deleteModel / mj_deleteData on destruction.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>

namespace graspcd::mujoco {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

}  // namespace graspcd::mujoco
