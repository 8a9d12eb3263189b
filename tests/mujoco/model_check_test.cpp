// A model with a non-finite number: MuJoCo compiles `pos="nan 0 0"` with only a
// warning; find_non_finite names it, and NonconvexContacts refuses it from its constructor, before
// anything is installed, never from inside mj_step.
#include "graspcd/mujoco/model_check.h"

#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "graspcd/mujoco/collision.h"
#include "graspcd/mujoco/mujoco_messages.h"
#include "graspcd/mujoco/nonconvex_contacts.h"
#include "graspcd/support/meshes.h"
#include "helpers/scene_support.h"

namespace graspcd::mujoco {
namespace {

using graspcd::testing::TempDir;

// `b_pos` is the position of geom b in its body (MuJoCo keeps a NaN there; a free body's own NaN
// position is lost on the way to qpos0).
std::string scene(const std::string& b_pos) {
  return R"(<mujoco><asset><mesh name="tet" file="tet.obj"/></asset><worldbody>
  <body name="a"><freejoint/><geom name="a" type="mesh" mesh="tet"/></body>
  <body name="b"><freejoint/><geom name="b" type="box" size="0.1 0.1 0.1" pos=")" +
         b_pos + R"("/></body>
</worldbody></mujoco>)";
}

class ModelCheckTest : public ::testing::Test {
 protected:
  // MuJoCo's "XML contains a 'NaN'" goes to the sink, not to stdout and MUJOCO_LOG.TXT.
  void SetUp() override {
    previous_ = mju_user_warning;
    route_mujoco_warnings();
  }
  void TearDown() override { mju_user_warning = previous_; }

  ModelPtr load(const std::string& b_pos) {
    return graspcd::testing::load_scene(
        dir_, scene(b_pos), {{"tet", graspcd::testing::make_box_mesh(0.05, 0.05, 0.05)}});
  }
  std::string config() {
    const std::string path = (dir_.path() / "scene.pairs.json").string();
    std::ofstream(path) << R"({"pairs": [{"a": "a", "b": "b"}]})";
    return path;
  }

  TempDir dir_;
  void (*previous_)(const char*) = nullptr;
};

TEST_F(ModelCheckTest, AFiniteModelPasses) {
  const ModelPtr m = load("0.3 0 0");
  ASSERT_TRUE(m);
  EXPECT_EQ(find_non_finite(m.get()), "");
  NonconvexContacts contacts(m.get(), config());
  EXPECT_EQ(contacts.served_pairs(), 1u);
}

TEST_F(ModelCheckTest, NonconvexContactsRefusesANanFromItsConstructor) {
  const ModelPtr m = load("nan 0 0");
  ASSERT_TRUE(m);
  EXPECT_EQ(find_non_finite(m.get()),
            "the model holds a non-finite number: geom_pos of geom 1 'b' is nan");
  const std::string path = config();
  try {
    NonconvexContacts contacts(m.get(), path);
    ADD_FAILURE() << "a model holding NaN was served";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": the model holds a non-finite number: geom_pos of geom 1 'b' is nan");
  }
  EXPECT_FALSE(installed());
  EXPECT_EQ(find_registry(m.get()), nullptr);
}

}  // namespace
}  // namespace graspcd::mujoco
