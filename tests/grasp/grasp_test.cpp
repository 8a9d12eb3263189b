// The grasp of paper section 9 (grasp/grasp.h) on the generated scenes: with our collision
// callback the fingers reach the object in grasp steps of 0.003 rad, the arm lifts it, and it stays
// in the hand for 2 s of simulated time, on the non-convex cup (example 1) and the can (example 2);
// the per-step detection time is recorded; MuJoCo's native collision runs the same grasp, and on
// the C-block (example 3) finger 2 meets the convex hull at the slot's mouth before our detector
// meets the real surface. Also the errors: a missing or bad MJCF, a missing config, a simulation
// that goes non-finite.
#include "graspcd/grasp/grasp.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "graspcd/mujoco/model_loading.h"
#include "helpers/test_scale.h"

namespace graspcd::grasp {
namespace {

const std::string kMjcf = GRASPCD_MJCF_DIR;

std::string scene(const std::string& name) { return kMjcf + "/" + name + ".xml"; }

// Each run once per process (they take seconds): scene + "/native" or scene + "/ours".
const GraspResult& grasp(const std::string& name, bool native) {
  static std::map<std::string, GraspResult> cache;
  const std::string key = name + (native ? "/native" : "/ours");
  auto it = cache.find(key);
  if (it == cache.end()) {
    GraspOptions options;
    options.native = native;
    it = cache.emplace(key, run_grasp(scene(name), options)).first;
    const GraspResult& r = it->second;
    std::printf("%s %s: %zu grasp steps, gripped %d, first contact", name.c_str(), r.method.c_str(),
                r.steps.size(), r.gripped ? 1 : 0);
    for (int s = 0; s < kFingerSegments; ++s)
      std::printf(" %d", r.first_contact[static_cast<std::size_t>(s)]);
    std::printf(
        "\n  z %.4f -> gripped %.4f -> final %.4f (hold min %.4f, drift %.4f), held %d, "
        "%.4f ms per physics step, detection %.0f ns per grasp step, max contacts %d\n",
        r.object_z_initial, r.object_z_gripped, r.object_z_final, r.hold_min_z, r.hold_drift,
        r.held ? 1 : 0, r.step_wall_ms,
        r.steps.empty()
            ? 0.0
            : static_cast<double>(r.detection_ns_close) / static_cast<double>(r.steps.size()),
        r.max_contacts);
  }
  return it->second;
}

int first_contact_of_finger(const GraspResult& r, int finger) {
  int first = -1;
  for (int s = 0; s < 3; ++s) {
    const int k = r.first_contact[static_cast<std::size_t>(3 * finger + s)];
    if (k > 0 && (first < 0 || k < first)) first = k;
  }
  return first;
}

class OursLiftsAndHolds : public ::testing::TestWithParam<std::string> {};

// One test per scene, not one per property: ctest runs each test in its own process, so each
// test pays for its own grasp (about 30 s under the sanitizers).
TEST_P(OursLiftsAndHolds, FingersTouchThenTheObjectIsLiftedAndHeldAndDetectionTimeIsRecorded) {
  const GraspResult& r = grasp(GetParam(), false);
  EXPECT_EQ(r.method, "sat");
  // Gripped: two hand geoms touching from opposing sides on the true meshes (docs/design.md,
  // "Semantics"); example 3's fingers carry the cup from one side.
  EXPECT_EQ(r.gripped, GetParam() != "example3");
  for (int f = 0; f < 4; ++f) {
    const int k = first_contact_of_finger(r, f);
    EXPECT_GT(k, 5) << "finger " << f + 1;  // open at the start: contact only after closing
  }
  EXPECT_TRUE(r.held);
  EXPECT_GT(r.object_z_final, r.object_z_initial + 0.03);
  EXPECT_GT(r.hold_min_z, r.object_z_initial + 0.03);
  EXPECT_GE(r.sim_time, 2.0 + 1.0);  // the lift and the 2 s hold at least
  // The solver's buffers (nconmax 300, njmax 900 as shipped) never overflowed, and at rest in the
  // hand (the hold's last second) the object touches with at most 1 mm of penetration.
  EXPECT_EQ(r.contact_buffer_full, 0);
  EXPECT_EQ(r.constraint_buffer_full, 0);
  EXPECT_GT(r.rest_max_penetration, 0.0);
  EXPECT_LT(r.rest_max_penetration, 0.001);
  EXPECT_GT(r.rest_energy_early, 0.0);

  // The step cost in wall and CPU time (the thread's: at most the wall time it took, up to the
  // clocks' ticks).
  EXPECT_GT(r.step_cpu_ms, 0.0);
  EXPECT_LE(r.step_cpu_ms, r.step_wall_ms * 1.001 + 1e-6);

  // Detection time per grasp step.
  ASSERT_FALSE(r.steps.empty());
  int served_steps = 0;
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const GraspStepRecord& s = r.steps[i];
    EXPECT_EQ(s.step, static_cast<int>(i) + 1);
    if (s.served_calls > 0) {
      ++served_steps;
      EXPECT_GT(s.detection_ns, 0u) << "step " << s.step;
      // Box tests, or front pairs kept untested because B moved less than their gap.
      EXPECT_GT(s.box_tests + s.front_skips, 0u) << "step " << s.step;
    } else {
      EXPECT_EQ(s.detection_ns, 0u) << "step " << s.step;
    }
  }
  EXPECT_GT(served_steps, 0);
  // The last grasp step has the grip: contacts and triangle tests.
  EXPECT_GT(r.steps.back().contacts, 0);
  EXPECT_GT(r.steps.back().triangle_tests, 0u);
  EXPECT_GE(r.detection_ns_total, r.detection_ns_close);
}

INSTANTIATE_TEST_SUITE_P(Scenes, OursLiftsAndHolds,
                         ::testing::Values("example1", "example2", "example3"));

// The NativeGrasp tests compare whole grasps, ours and MuJoCo's (about 30 s each under the
// sanitizers): the Release pass checks their outcomes; the sanitizer pass runs the same served
// grasps in OursLiftsAndHolds (docs/testing.md, "What runs where").
TEST(NativeGrasp, RunsWithoutTheBridge) {
  if (graspcd::testing::test_scale() < 1)
    GTEST_SKIP() << "GRASPCD_TEST_SCALE < 1: Release pass only";
  const GraspResult& r = grasp("example1", true);
  EXPECT_EQ(r.method, "native");
  ASSERT_FALSE(r.steps.empty());
  for (const GraspStepRecord& s : r.steps) {
    EXPECT_EQ(s.detection_ns, 0u);
    EXPECT_EQ(s.served_calls, 0u);
  }
  EXPECT_GT(r.physics_steps, 0);
  EXPECT_GT(r.sim_time, 3.0);
  // MuJoCo 2.2's convex-hull collision gives one contact per touching geom pair; ours spreads
  // several over each contact region.
  const GraspResult& ours = grasp("example1", false);
  EXPECT_LE(r.max_contacts, 12);
  EXPECT_GT(ours.max_contacts, r.max_contacts);
  // Measured: with those few contacts the cup slides down in the hand during the hold (1.3 cm
  // natively, 0.2 cm with ours): natively it is not held by our criterion.
  EXPECT_GT(r.hold_drift, ours.hold_drift);
  EXPECT_TRUE(ours.held);
}

// Example 3: finger 2 closes into the C-block's slot. MuJoCo's convex hull is solid there, so
// natively finger 2 touches at the slot's mouth; our detector answers on the real surface and
// finger 2 closes further before it touches.
TEST(NativeGrasp, OnTheCBlockFinger2TouchesLaterWithOurDetector) {
  if (graspcd::testing::test_scale() < 1)
    GTEST_SKIP() << "GRASPCD_TEST_SCALE < 1: Release pass only";
  const GraspResult& ours = grasp("example3", false);
  const GraspResult& native = grasp("example3", true);
  const int k_ours = first_contact_of_finger(ours, 1);
  const int k_native = first_contact_of_finger(native, 1);
  std::printf("example3 finger 2: first contact at grasp step %d with ours, %d natively\n", k_ours,
              k_native);
  EXPECT_GT(k_native, 0);
  EXPECT_GT(k_ours, k_native + 5);
  // The opening stays open with the contact manifold: the hull says 55.
  EXPECT_GE(k_ours, 150);
}

TEST(GraspErrors, MissingSceneNamesTheFile) {
  try {
    run_grasp(kMjcf + "/no_such_scene.xml");
    FAIL() << "no exception";
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(kMjcf + "/no_such_scene.xml: ", 0), 0u) << message;
  }
}

TEST(GraspErrors, BadMjcfGivesMujocosMessageOnOneLineAfterTheFile) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string file =
      (dir / ("graspcd_grasp_test_bad_" + std::to_string(::getpid()) + ".xml")).string();
  std::ofstream(file) << "<mujoco>\n  <worldbody>\n    <bogus/>\n  </worldbody>\n</mujoco>\n";
  try {
    run_grasp(file);
    FAIL() << "no exception";
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find("bogus"), std::string::npos) << message;
  }
  std::filesystem::remove(file);
}

TEST(GraspErrors, MissingConfigNamesTheConfig) {
  GraspOptions options;
  options.config_path = kMjcf + "/no_such.pairs.json";
  try {
    run_grasp(scene("example1"), options);
    FAIL() << "no exception";
  } catch (const io::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(options.config_path + ": ", 0), 0u) << message;
  }
}

// Non-finite state (grasp.h): a NaN written into qvel after grasp step 2 makes MuJoCo reset the
// state in the next physics step (mj_checkVel); the grasp stops with one line naming the scene,
// the grasp step and the warning instead of starting over silently.
TEST(GraspErrors, NonFiniteStateStopsTheGrasp) {
  for (const bool native : {false, true}) {
    GraspOptions options;
    options.native = native;
    options.max_steps = 5;
    int steps_seen = 0;
    options.on_grasp_step = [&](const mjModel*, const mjData* d, int step) {
      steps_seen = step;
      // The test plays a diverging solver: run_grasp's mjData is not const.
      if (step == 2) const_cast<mjData*>(d)->qvel[0] = std::nan("");
    };
    try {
      run_grasp(scene("example2"), options);
      FAIL() << "no exception";
    } catch (const io::InputError&) {
      FAIL() << "not an input error";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message, scene("example2") +
                             ": the simulation went non-finite in grasp step 3 of the closing "
                             "(physics step 11): MuJoCo found a bad number (NaN or beyond 1e10) "
                             "in qvel at index 0 and reset the state; the grasp stops");
    }
    EXPECT_EQ(steps_seen, 2);
  }
}

// A grasp that stays finite skips nothing.
TEST(GraspErrors, FiniteGraspsSkipNothing) {
  const GraspResult& r = grasp("example1", false);
  EXPECT_EQ(r.nonfinite_skips, 0u);
  for (const GraspStepRecord& s : r.steps) EXPECT_EQ(s.nonfinite_skips, 0u);
  EXPECT_TRUE(r.warnings.empty());
}

}  // namespace
}  // namespace graspcd::grasp
