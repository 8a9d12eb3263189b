// The race's protocol measures of a grasp run (grasp_result.h, true_penetration.h): the true
// meshes' penetration, measured whatever the run collided, the object's largest kinetic energy
// and MuJoCo's noslip iterations. The case that must not read as perfect: an object lost through
// its support, here the can of example 2 that MuJoCo is told not to collide with the floor
// (<exclude> of the world body and the object: its contype and conaffinity, which the true
// meshes' pairs follow, still say the floor holds it), so that it falls through the floor: a
// drop, not an ejection, since gravity alone moves it. No hand contact is left to judge, and the
// true meshes say how deep the can went below the floor.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "graspcd/grasp/grasp.h"
#include "helpers/scene_text.h"
#include "helpers/temp_dir.h"

namespace graspcd::grasp::protocol_test {
namespace {

namespace fs = std::filesystem;

const std::string kMjcf = GRASPCD_MJCF_DIR;

using testing::read_text;
using testing::replaced;

class Protocol : public testing::TempDirTest {
 protected:
  // Example 2, its meshes read from the source tree, with `extra` added after the worldbody. A
  // short run, native: a closing of 20 grasp steps (0.2 s), a squeeze of 0.02 s, a settling of
  // 0.05 s, a lift and a hold of 0.1 s each.
  GraspResult example2(const std::string& extra, GraspOptions options = {}) {
    std::string xml = read_text(kMjcf + "/example2.xml");
    xml = replaced(xml, "meshdir=\"meshes\"", "meshdir=\"" + kMjcf + "/meshes\"");
    xml = replaced(xml, "</worldbody>", "</worldbody>\n" + extra);
    options.native = true;
    options.true_penetration = true;
    options.max_steps = 20;
    options.squeeze_time = 0.02;
    options.settle_time = 0.05;
    options.lift_time = 0.1;
    options.hold_time = 0.1;
    return run_grasp(write("scene.xml", xml), options);
  }
};

TEST_F(Protocol, ACanFallingThroughTheFloorIsDroppedWithItsTruePenetrationMeasured) {
  GraspOptions options;
  options.noslip_iterations = 7;
  options.multiccd = true;
  const GraspResult r =
      example2("<contact><exclude body1=\"world\" body2=\"object\"/></contact>", options);
  // A fall under gravity, never an ejection.
  EXPECT_FALSE(r.ejected.has_value()) << r.reason;
  ASSERT_TRUE(r.fell.has_value());
  EXPECT_EQ(r.outcome, "dropped");
  EXPECT_FALSE(r.held);
  EXPECT_EQ(r.noslip_iterations, 7);
  EXPECT_TRUE(r.multiccd);  // asked for, on MuJoCo's native collision
  // The start and every fifth state after it measured (a grasp step), every one after the can
  // started to fall found it below the floor: the deepest at the last, the can's free fall over
  // the whole run less the height of its lowest point (it started 0.5 mm or less above the floor).
  const TruePenetration& p = r.true_penetration;
  EXPECT_EQ(p.measures, r.physics_steps / 5 + 1);  // the start, then every fifth state
  EXPECT_GT(p.pairs, 0);
  EXPECT_EQ(p.step, p.measures);
  EXPECT_EQ(p.side, "support");
  EXPECT_EQ(p.geom, "geom 'floor'");
  EXPECT_EQ(p.phase, "the hold");
  EXPECT_DOUBLE_EQ(p.max, p.support_max);
  const double fall = 0.5 * 9.81 * r.sim_time * r.sim_time;
  EXPECT_NEAR(p.max, fall, 0.02 * fall);
  EXPECT_DOUBLE_EQ(p.hand_max, 0.0);  // no finger reached it
  // A falling can does not turn: its largest kinetic energy is that of its top speed, at the end.
  EXPECT_GT(r.kinetic_energy_max, 0.0);
  const double mass = r.kinetic_energy_max / (0.5 * r.max_speed * r.max_speed);
  EXPECT_GT(mass, 0.0);
  EXPECT_NEAR(r.kinetic_energy_max, 0.5 * mass * 9.81 * 9.81 * r.sim_time * r.sim_time,
              0.02 * r.kinetic_energy_max);
}

TEST_F(Protocol, ACanStandingOnTheFloorIsMeasuredAtRestWithoutNoslip) {
  const GraspResult r = example2("");
  EXPECT_FALSE(r.ejected.has_value());
  EXPECT_EQ(r.noslip_iterations, 0);  // the scene's
  EXPECT_FALSE(r.multiccd);           // the scene's: MuJoCo's default, off
  const TruePenetration& p = r.true_penetration;
  EXPECT_EQ(p.measures, r.physics_steps / 5 + 1);  // the start, then every fifth state
  // MuJoCo's soft contact lets the can sink into the floor about a millimetre as the fingers
  // close on it (1.06 mm here), never by centimetres.
  EXPECT_GT(p.support_max, 0.0);
  EXPECT_LT(p.support_max, 3e-3);
  EXPECT_TRUE(p.unmeasured.empty());
  EXPECT_LT(r.max_speed, 1.0);           // a hand's pace, not a throw
  EXPECT_GT(r.kinetic_energy_max, 0.0);  // the fingers' closing moves it
}

}  // namespace
}  // namespace graspcd::grasp::protocol_test
