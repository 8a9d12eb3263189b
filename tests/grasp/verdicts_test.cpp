// The verdicts that watch the object (grasp.h): a held object that hangs tilted is "held, tilted
// N°" and its grip point rose with the hand (the cup of example 1, our hand; the glass in the
// Shadow hand, mjcf/real_shadow_glass.xml, when ../shared/models is there), and an object that
// passes below its support or is faster than kEjectSpeed is "ejected at t = ...", never "no
// segment reached the object" (the can of example 2 made to collide with nothing: it falls
// through the floor out of the hand's reach).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "graspcd/grasp/grasp.h"
#include "support/temp_dir.h"
#include "support/test_scale.h"

namespace graspcd::grasp {
namespace {

namespace fs = std::filesystem;

const std::string kMjcf = GRASPCD_MJCF_DIR;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Replaces the one occurrence of `from` in `text`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The whole grasps below (about 30 s each under the sanitizers) run in the Release pass; the
// sanitizer pass watches the object in the short grasps of EjectionVerdict.
TEST(TiltVerdict, TheCupHangsTiltedInTheHandAndIsHeldWithItsTilt) {
  if (testing::test_scale() < 1) GTEST_SKIP() << "GRASPCD_TEST_SCALE < 1: Release pass only";
  const GraspResult r = run_grasp(kMjcf + "/example1.xml");
  EXPECT_TRUE(r.held) << r.reason;
  EXPECT_TRUE(r.reason.empty());
  EXPECT_FALSE(r.ejected.has_value());
  // About 4.4 degrees about the grip, steady: the largest tilt is hardly more than the final.
  EXPECT_GT(r.tilt_final_deg, 3.0);
  EXPECT_LT(r.tilt_final_deg, 10.0);
  EXPECT_GE(r.tilt_deg, r.tilt_final_deg);
  EXPECT_LT(r.tilt_deg, r.tilt_final_deg + 1.0);
  EXPECT_EQ(tilt_note(r), "tilted 4\xc2\xb0");
  EXPECT_GE(r.grip_rise, kHeldRiseShare * r.hand_travel);
  EXPECT_LT(r.max_speed, kEjectSpeed / 10);
}

class RealScene : public testing::TempDirTest {
 protected:
  // A copy of mjcf/NAME.xml and its pair config in DIR/tree/mjcf, with DIR/shared the folder
  // of the models,
  // so that the scene's ../../shared/models paths hold wherever the source tree lies.
  std::string scene(const std::string& name) {
    const fs::path models(GRASPCD_MODELS_DIR);
    if (!fs::exists(models / "hands")) return "";
    const fs::path mjcf = dir_ / "tree" / "mjcf";
    fs::create_directories(mjcf);
    fs::create_directory_symlink(fs::absolute(models).parent_path(), dir_ / "shared");
    for (const char* ext : {".xml", ".pairs.json"}) {
      fs::copy_file(kMjcf + "/" + name + ext, mjcf / (name + ext));
    }
    return (mjcf / (name + ".xml")).string();
  }
};

TEST_F(RealScene, TheShadowHandHoldsTheGlassTilted) {
  if (testing::test_scale() < 1) GTEST_SKIP() << "GRASPCD_TEST_SCALE < 1: Release pass only";
  const std::string path = scene("real_shadow_glass");
  if (path.empty()) GTEST_SKIP() << "real models not found in " << GRASPCD_MODELS_DIR;
  const GraspResult r = run_grasp(path);
  EXPECT_TRUE(r.held) << r.reason;
  EXPECT_GT(r.tilt_final_deg, 10.0);  // about 14 degrees
  EXPECT_EQ(tilt_note(r).rfind("tilted ", 0), 0u) << tilt_note(r);
  EXPECT_LT(r.max_speed, kEjectSpeed);
}

class EjectionVerdict : public testing::TempDirTest {
 protected:
  // Example 2 with the can colliding with nothing (contype = conaffinity = 0), scaled by `scale`,
  // its meshes read from the source tree: nothing holds it up and no finger can reach it. A short
  // closing (20 grasp steps), a lift and a hold of 0.2 s each, native.
  GraspResult falling_can(const std::string& scale) {
    std::string xml = read_text(kMjcf + "/example2.xml");
    xml = replaced(xml, "meshdir=\"meshes\"", "meshdir=\"" + kMjcf + "/meshes\"");
    xml = replaced(xml, "<mesh name=\"can\" file=\"can.obj\"/>",
                   "<mesh name=\"can\" file=\"can.obj\" scale=\"" + scale + "\"/>");
    xml = replaced(xml, "mesh=\"can\" contype=\"1\" conaffinity=\"3\"",
                   "mesh=\"can\" contype=\"0\" conaffinity=\"0\"");
    GraspOptions options;
    options.native = true;
    options.max_steps = 20;
    options.lift_time = 0.2;
    options.hold_time = 0.2;
    return run_grasp(write("falls.xml", xml), options);
  }

  // Ejected, never held, and the reason is the ejection's, not "no segment reached the object".
  static void expect_ejected_verdict(const GraspResult& r) {
    ASSERT_TRUE(r.ejected.has_value());
    EXPECT_FALSE(r.held);
    EXPECT_FALSE(r.gripped);
    EXPECT_EQ(r.reason.find("no segment reached"), std::string::npos);
    char expected[80];
    std::snprintf(expected, sizeof expected, "ejected at t = %.3f s (%.1f m/s)", r.ejected->time,
                  r.ejected->speed);
    EXPECT_EQ(r.reason, expected);
  }
};

TEST_F(EjectionVerdict, ACanFallingFromRestIsEjectedWhenItReachesTheEjectionSpeed) {
  // The can reaches from its origin about R = 9 cm: it would pass 2 R + 1 cm below its start after
  // 0.21 s, but it is faster than kEjectSpeed = 2 m/s at t = 2 / 9.81 = 0.204 s.
  const GraspResult r = falling_can("1 1 1");
  expect_ejected_verdict(r);
  ASSERT_TRUE(r.ejected.has_value());
  EXPECT_EQ(r.ejected->cause, "speed");
  EXPECT_NEAR(r.ejected->time, kEjectSpeed / 9.81, 0.004);
  EXPECT_GT(r.ejected->speed, kEjectSpeed);
  EXPECT_LT(r.ejected->speed, kEjectSpeed + 0.05);
}

TEST_F(EjectionVerdict, ASmallCanPassesBelowItsSupportFirst) {
  // At 0.3 the can reaches about 2.8 cm: below its start by 6.6 cm after 0.12 s, at 1.1 m/s.
  const GraspResult r = falling_can("0.3 0.3 0.3");
  expect_ejected_verdict(r);
  ASSERT_TRUE(r.ejected.has_value());
  EXPECT_EQ(r.ejected->cause, "below");
  EXPECT_GT(r.ejected->time, 0.08);
  EXPECT_LT(r.ejected->time, 0.16);
  EXPECT_NEAR(r.ejected->speed, 9.81 * r.ejected->time, 0.05);
}

}  // namespace
}  // namespace graspcd::grasp
