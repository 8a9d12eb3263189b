#include "graspcd/mujoco/mujoco_messages.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <string>
#include <thread>

#include "helpers/scene_support.h"

namespace graspcd::mujoco {
namespace {

// Two boxes resting on each other with room for one contact: MuJoCo warns that the contact buffer
// is full, once per mjData.
constexpr const char* kTwoBoxes = R"(<mujoco>
  <size nconmax="1"/>
  <worldbody>
    <geom type="plane" size="1 1 0.1"/>
    <body pos="0 0 0.1"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body>
  </worldbody>
</mujoco>)";

bool has_buffer_warning(const graspcd::WarningSink& sink) {
  for (const Warning& w : sink.list()) {
    if (w.code == "mujoco_warning" && w.message.find("contact buffer is full") != std::string::npos)
      return true;
  }
  return false;
}

void step_until_full(const mjModel* m) {
  const DataPtr d(mj_makeData(m));
  for (int i = 0; i < 20; ++i) mj_step(m, d.get());
  EXPECT_GT(d->warning[mjWARN_CONTACTFULL].number, 0);
}

TEST(MujocoMessages, WarningsReachTheSinkAndTheCapturingThreadOnly) {
  const testing::TempDir dir;
  const ModelPtr m = testing::load_scene(dir, kTwoBoxes, {});
  ASSERT_TRUE(m);
  void (*const before)(const char*) = mju_user_warning;
  route_mujoco_warnings();
  warnings().clear();
  graspcd::WarningSink mine, other;
  {
    const ScopedMujocoWarnings capture(mine);
    step_until_full(m.get());
  }
  std::thread([&] {
    const ScopedMujocoWarnings capture(other);
    // This thread steps nothing: what another thread raises is not its warning.
  }).join();
  step_until_full(m.get());  // after the capture ended: the process's sink only
  EXPECT_TRUE(has_buffer_warning(mine));
  long mine_total = 0;
  for (const Warning& w : mine.list()) mine_total += w.count;
  EXPECT_EQ(mine_total, 1) << "the capture ended before the second simulation";
  EXPECT_TRUE(other.empty());
  EXPECT_TRUE(has_buffer_warning(warnings()));
  mju_user_warning = before;
  warnings().clear();
}

}  // namespace
}  // namespace graspcd::mujoco
