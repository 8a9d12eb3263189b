// The verdicts (verdicts.h; docs/design.md, "Semantics"): a held object that hangs tilted is
// "held, tilted N°" and its grip point rose with the hand (the cup of example 1, our hand; the
// glass in the Shadow hand, mjcf/real_shadow_glass.xml, when ../shared/models is there); an object
// carried with the hand is held whatever touched it (a ring hooked on one finger); a held run has
// no reason, and a closing cut short by --max-steps is said beside it; an object turned past
// kPushedOverDeg before the lift is pushed over; an object that falls under gravity is dropped,
// with where it went, never ejected (the can of example 2 made to collide with nothing falls
// through the floor); only a speed gravity and the hand cannot give is an ejection. The squeeze's
// push and the drop on made-up measures, and a slippery can the hand loses as it lifts.
#include "graspcd/grasp/verdicts.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "graspcd/grasp/grasp.h"
#include "helpers/scene_text.h"
#include "helpers/temp_dir.h"
#include "helpers/test_scale.h"

namespace graspcd::grasp::verdicts_test {
namespace {

namespace fs = std::filesystem;

const std::string kMjcf = GRASPCD_MJCF_DIR;

using testing::read_text;
using testing::replaced;

// The whole grasps below (about 30 s each under the sanitizers) run in the Release pass; the
// sanitizer pass watches the object in the short grasps of FallVerdict.
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
  EXPECT_LT(r.max_speed, 0.2);
  // The squeeze moves the cup about 6 mm: measured, not a push; the hand never lets it go.
  EXPECT_GT(r.squeeze_push, 0.001);
  EXPECT_LT(r.squeeze_push, kSqueezePush);
  EXPECT_FALSE(r.pushed_during_squeeze);
  EXPECT_EQ(push_note(r), "");
  EXPECT_LT(r.release_time, 0);
  EXPECT_FALSE(r.dropped_at.has_value());
}

// The measures of a grasp whose object was gripped (two hand geoms touching it from opposing
// sides at the start of the lift), rose with the hand (6 cm) and stayed in it: held, until a
// test changes a measure.
GraspResult gripped_and_lifted() {
  GraspResult r;
  r.hand_travel = 0.06;
  r.object_rise = 0.059;
  r.grip_rise = 0.059;
  r.hold_drift = 0.002;
  r.touching_at_lift = 2;
  r.gripped = true;
  r.closing = "touched";
  return r;
}

TEST(PushVerdict, AnObjectTheSqueezeMovedMoreThanKSqueezePushIsHeldButSaysItWasPushed) {
  GraspResult r = gripped_and_lifted();
  r.squeeze_push = 0.009;
  judge_grasp(r);
  EXPECT_TRUE(r.held);
  EXPECT_FALSE(r.pushed_during_squeeze);
  EXPECT_EQ(push_note(r), "");
  // The L-shape the Robotiq threw 12 cm up before the lift: still held (the later rules hold),
  // but the verdict says so.
  r.squeeze_push = 0.12;
  judge_grasp(r);
  EXPECT_TRUE(r.held);
  EXPECT_TRUE(r.reason.empty()) << r.reason;
  EXPECT_TRUE(r.pushed_during_squeeze);
  EXPECT_EQ(push_note(r), "pushed 12.0 cm during the squeeze");
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0], "pushed 12.0 cm during the squeeze");
  EXPECT_EQ(r.outcome, "held");
  // Not held: the reason says why, the flag stays in the result, the note is a held object's.
  r.hold_drift = 0.03;
  r.slip_time = 2.5;
  judge_grasp(r);
  EXPECT_FALSE(r.held);
  EXPECT_TRUE(r.pushed_during_squeeze);
  EXPECT_EQ(push_note(r), "");
  EXPECT_EQ(r.outcome, "dropped");
}

TEST(HeldVerdict, AnObjectCarriedWithTheHandIsHeldWhateverTouchedIt) {
  // A ring hooked on the Shadow hand's fingers: two hand geoms touch it, neither pair from
  // opposing sides, and it rose 6.00 of the hand's 6.00 cm: held, not "no two touching segments
  // push from opposing sides".
  GraspResult ring = gripped_and_lifted();
  ring.gripped = false;
  ring.grip_rise = 0.06;
  ring.object_rise = 0.06;
  ring.hold_drift = 0.0005;
  judge_grasp(ring);
  EXPECT_TRUE(ring.held);
  EXPECT_TRUE(ring.reason.empty()) << ring.reason;
  EXPECT_EQ(ring.outcome, "held");
  EXPECT_EQ(ring.evidence,
            "its grip point rose 0.0600 m of the hand's 0.0600 m, drift 0.0005 m in the hold; 2 "
            "hand geoms touched it at the start of the lift, none from opposing sides");
  // Carried by one geom: held as well.
  ring.touching_at_lift = 1;
  judge_grasp(ring);
  EXPECT_TRUE(ring.held);
  EXPECT_EQ(ring.evidence.substr(ring.evidence.find("; ")),
            "; 1 hand geom touched it at the start of the lift");
  // Not touched at the lift, and left on the table: why.
  GraspResult untouched = gripped_and_lifted();
  untouched.touching_at_lift = 0;
  untouched.gripped = false;
  untouched.grip_rise = 0;
  untouched.object_rise = 0;
  judge_grasp(untouched);
  EXPECT_FALSE(untouched.held);
  EXPECT_EQ(untouched.reason, "the hand did not touch it at the start of the lift");
}

TEST(HeldVerdict, AClosingCutShortBesideAHeldVerdictHasNoReason) {
  // The mug of concave_robotiq_mug_rim with --max-steps 1: the squeeze still closed the pads and
  // carried it (0.0572 of 0.0575 m), tilted 11 degrees.
  GraspResult r = gripped_and_lifted();
  r.grip_rise = 0.0572;
  r.hand_travel = 0.0575;
  r.tilt_final_deg = 11.2;
  r.closing = "max_steps";
  r.max_steps = 1;
  judge_grasp(r);
  EXPECT_TRUE(r.held);
  EXPECT_TRUE(r.reason.empty()) << r.reason;
  EXPECT_EQ(r.outcome, "held tilted");
  ASSERT_EQ(r.notes.size(), 2u);
  EXPECT_EQ(r.notes[0], "tilted 11\xc2\xb0");
  EXPECT_EQ(r.notes[1], "the closing was cut short at grasp step 1 (--max-steps)");
  // Not held: the reason, and the note beside it.
  r.hold_drift = 0.02;
  r.slip_time = 3.1;
  judge_grasp(r);
  EXPECT_FALSE(r.held);
  EXPECT_EQ(r.reason, "slipped at t = 3.100 s (moved 2.0 cm in the hand)");
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0], "the closing was cut short at grasp step 1 (--max-steps)");
}

TEST(PushedOverVerdict, AnObjectTurnedPastTheLimitBeforeTheLiftIsPushedOver) {
  // A drill knocked over by 28 degrees as the fingers closed, then not lifted with the hand.
  GraspResult r = gripped_and_lifted();
  r.tilt_before_lift_deg = 28.4;
  r.grip_rise = 0.002;
  r.object_rise = 0.002;
  judge_grasp(r);
  EXPECT_FALSE(r.held);
  EXPECT_TRUE(r.pushed_over);
  EXPECT_EQ(r.reason, "pushed over: tipped 28\xc2\xb0 before the lift");
  // Within the limit: not pushed over.
  r.tilt_before_lift_deg = kPushedOverDeg - 1;
  judge_grasp(r);
  EXPECT_FALSE(r.pushed_over);
  // Pushed over but carried all the same: held, with a note.
  r.tilt_before_lift_deg = 31;
  r.grip_rise = 0.059;
  judge_grasp(r);
  EXPECT_TRUE(r.held);
  EXPECT_TRUE(r.reason.empty()) << r.reason;
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0], "pushed over 31\xc2\xb0 before the lift");
}

TEST(DropVerdict, AGrippedObjectThatLeftTheHandAndFellIsDroppedNotSlipped) {
  // The plate that fell 40 m off its support: no hand contact from t = 2.2 s on; it passed below
  // where it could rest at t = 2.3 s.
  GraspResult r = gripped_and_lifted();
  r.release_time = 2.2;
  r.object_z_initial = 0.02;
  r.object_rise = -40;
  r.object_z_final = -39.98;
  r.grip_rise = -40;
  r.hold_drift = 36.7;
  r.slip_time = 2.25;
  r.fell = Fall{2.3, 0.9};
  judge_grasp(r);
  EXPECT_FALSE(r.held);
  ASSERT_TRUE(r.dropped_at.has_value());
  EXPECT_EQ(*r.dropped_at, 2.3);
  EXPECT_EQ(r.drop, "it fell off its support, 40.000 m below its start at the end");
  EXPECT_EQ(r.reason,
            "dropped at t = 2.300 s: it fell off its support, 40.000 m below its start "
            "at the end");
  EXPECT_EQ(r.outcome, "dropped");

  // Left the hand and lay on its support below the hand's path: dropped when it let go.
  GraspResult left = gripped_and_lifted();
  left.release_time = 2.2;
  left.object_rise = 0.01;
  left.grip_rise = 0.01;
  judge_grasp(left);
  ASSERT_TRUE(left.dropped_at.has_value());
  EXPECT_EQ(*left.dropped_at, 2.2);
  EXPECT_EQ(left.reason,
            "dropped at t = 2.200 s: it left the hand and ended 0.050 m below the "
            "hand's path, on its support");

  // Ejected keeps precedence.
  GraspResult ejected = r;
  ejected.ejected = Ejection{2.6, 42.0, "speed", 4.1};
  judge_grasp(ejected);
  EXPECT_FALSE(ejected.dropped_at.has_value());
  EXPECT_EQ(ejected.reason,
            "ejected at t = 2.600 s (42.0 m/s, faster than the 4.1 m/s gravity and the hand "
            "could give)");
  EXPECT_EQ(ejected.outcome, "ejected");

  // Still touched at the end: it slipped in the hand.
  GraspResult touched = left;
  touched.release_time = -1;
  touched.hold_drift = 0.03;
  touched.slip_time = 2.25;
  touched.object_rise = 0.03;
  touched.grip_rise = 0.03;
  judge_grasp(touched);
  EXPECT_FALSE(touched.dropped_at.has_value());
  EXPECT_EQ(touched.reason, "slipped at t = 2.250 s (moved 3.0 cm in the hand)");

  // Let go but not fallen behind the hand (within kHeldSlip of its path): not dropped, held.
  GraspResult resting = gripped_and_lifted();
  resting.release_time = 3.9;
  judge_grasp(resting);
  EXPECT_FALSE(resting.dropped_at.has_value());
  EXPECT_TRUE(resting.held) << resting.reason;

  // Never touched at the lift: that reason, never dropped by the hand.
  GraspResult loose = left;
  loose.touching_at_lift = 0;
  judge_grasp(loose);
  EXPECT_FALSE(loose.dropped_at.has_value());
  EXPECT_EQ(loose.reason, "the hand did not touch it at the start of the lift");
}

class DropRun : public testing::TempDirTest {};

// Example 2's can made five times as dense and slippery (friction 0.05), native: the fingers grip
// it but lose it, and it stays on the floor while the hand rises 6 cm. Dropped
// when it lost the hand, not "its grip rose -0.0 cm of the hand's 6.0 cm travel".
TEST_F(DropRun, ASlipperyHeavyCanLeavesTheHandAtTheLiftAndIsDropped) {
  std::string xml = read_text(kMjcf + "/example2.xml");
  xml = replaced(xml, "meshdir=\"meshes\"", "meshdir=\"" + kMjcf + "/meshes\"");
  xml = replaced(xml, "mesh=\"can\" contype=\"1\" conaffinity=\"3\"",
                 "mesh=\"can\" contype=\"1\" conaffinity=\"3\" friction=\"0.05 0.005 0.0001\" "
                 "density=\"5000\"");
  GraspOptions options;
  options.native = true;
  const GraspResult r = run_grasp(write("slippery.xml", xml), options);
  EXPECT_TRUE(r.gripped);
  EXPECT_FALSE(r.held);
  EXPECT_FALSE(r.ejected.has_value());
  ASSERT_TRUE(r.dropped_at.has_value()) << r.reason;
  EXPECT_EQ(*r.dropped_at, r.release_time);
  EXPECT_GT(r.hand_travel - r.object_rise, kHeldSlip);
  char expected[48];
  std::snprintf(expected, sizeof expected, "dropped at t = %.3f s: it left the hand",
                *r.dropped_at);
  EXPECT_EQ(r.reason.rfind(expected, 0), 0u) << r.reason;
  EXPECT_GT(*r.dropped_at, 0);
  EXPECT_LT(*r.dropped_at, r.sim_time);
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
  EXPECT_LT(r.max_speed, 1.0);
}

class FallVerdict : public testing::TempDirTest {
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

  // Dropped, never ejected nor held, and the reason says where it went.
  static void expect_fall_verdict(const GraspResult& r) {
    EXPECT_FALSE(r.ejected.has_value()) << r.reason;
    EXPECT_FALSE(r.held);
    EXPECT_FALSE(r.gripped);
    EXPECT_EQ(r.outcome, "dropped");
    ASSERT_TRUE(r.fell.has_value());
    ASSERT_TRUE(r.dropped_at.has_value());
    EXPECT_EQ(*r.dropped_at, r.fell->time);
    char expected[80];
    std::snprintf(expected, sizeof expected, "dropped at t = %.3f s: it fell off its support, ",
                  r.fell->time);
    EXPECT_EQ(r.reason.rfind(expected, 0), 0u) << r.reason;
  }
};

TEST_F(FallVerdict, ACanFallingFromRestIsDroppedNeverEjected) {
  // The can reaches from its origin about R = 9 cm: it passes 2 R + 1 cm below its start after
  // sqrt(2 * 0.19 / 9.81) = 0.2 s, at about 2 m/s, then falls on (0.6 s in all, 6 m/s): always
  // slower than sqrt(2 g d) + kEjectMargin.
  const GraspResult r = falling_can("1 1 1");
  expect_fall_verdict(r);
  EXPECT_GT(r.fell->time, 0.17);
  EXPECT_LT(r.fell->time, 0.23);
  EXPECT_GT(r.max_speed, 4.0);
}

TEST_F(FallVerdict, ASmallCanPassesBelowItsSupportSooner) {
  // At 0.3 the can reaches about 2.8 cm: below its start by 6.6 cm after 0.12 s, at 1.1 m/s.
  const GraspResult r = falling_can("0.3 0.3 0.3");
  expect_fall_verdict(r);
  EXPECT_GT(r.fell->time, 0.08);
  EXPECT_LT(r.fell->time, 0.16);
  EXPECT_NEAR(r.fell->speed, 9.81 * r.fell->time, 0.05);
}

// grasp --manifold's choices (grasp_result.h): a reduction, optionally with the contacts per pair
// 1 .. mjMAXCONPAIR; nothing else.
TEST(ManifoldChoice, ParsesAReductionAndAnOptionalBudget) {
  const auto moment4 = parse_manifold_choice("moment4");
  ASSERT_TRUE(moment4);
  EXPECT_EQ(moment4->reduction, ManifoldReduction::kMoment);
  EXPECT_EQ(moment4->max_contacts, 4);
  const auto support = parse_manifold_choice("support");
  ASSERT_TRUE(support);
  EXPECT_EQ(support->reduction, ManifoldReduction::kSupport);
  EXPECT_FALSE(support->max_contacts);
  EXPECT_EQ(parse_manifold_choice("moment50")->max_contacts, 50);
  const auto force4 = parse_manifold_choice("force4");
  ASSERT_TRUE(force4);
  EXPECT_EQ(force4->reduction, ManifoldReduction::kForce);
  EXPECT_EQ(force4->max_contacts, 4);
  EXPECT_EQ(parse_manifold_choice("force")->reduction, ManifoldReduction::kForce);
  for (const char* bad : {"", "moment0", "moment51", "moment04", "moment-4", "moment4x", "fewest",
                          "support123", "Moment", "force0", "forces4", "Force4"}) {
    EXPECT_FALSE(parse_manifold_choice(bad)) << bad;
  }
}

}  // namespace
}  // namespace graspcd::grasp::verdicts_test
