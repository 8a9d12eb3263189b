// The joint controllers on a 3-joint spatial arm under gravity: computed-torque step response,
// trajectory tracking and the error dynamics of eq. (15); the fuzzy controller's inference table
// and step response; and the errors of bad input.
#include "graspcd/grasp/controllers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "helpers/scene_support.h"

namespace graspcd::grasp {
namespace {

using testing::load_scene;
using testing::TempDir;

// A 3-link arm reaching along +x (so gravity loads joints 2 and 3 at q = 0): a base yaw hinge,
// shoulder and elbow pitch hinges, each link a capsule of different mass, a motor with gear 1 per
// joint; the elbow has damping and armature. Beside it a vertical slide (a carriage under gravity,
// on a spring and a damper) whose motor has gear 2. Then, on their own bodies, the joints of the
// bad-input tests: a ball joint, a hinge
// with no actuator, a hinge driven by a position servo, and a hinge with two motors. Contacts are
// off (every geom has contype = conaffinity = 0).
const char* kArm = R"(
<mujoco>
  <option timestep="0.001" gravity="0 0 -9.81"/>
  <default><geom contype="0" conaffinity="0"/></default>
  <worldbody>
    <body name="base" pos="0 0 0.1">
      <joint name="yaw" type="hinge" axis="0 0 1"/>
      <geom type="cylinder" size="0.05 0.05" mass="2"/>
      <body name="upper" pos="0 0 0.05">
        <joint name="shoulder" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.4 0 0" size="0.03" mass="1.5"/>
        <body name="fore" pos="0.4 0 0">
          <joint name="elbow" type="hinge" axis="0 1 0" damping="0.5" armature="0.01"/>
          <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.025" mass="0.8"/>
          <geom type="box" pos="0.32 0 0" size="0.03 0.05 0.02" mass="0.4"/>
        </body>
      </body>
    </body>
    <body name="carriage" pos="1 0 0.5">
      <joint name="rail" type="slide" axis="0 0 1" damping="5" stiffness="20"/>
      <geom type="box" size="0.05 0.05 0.05" mass="3"/>
    </body>
    <body name="ball_body" pos="2 0 1">
      <joint name="ball" type="ball"/>
      <geom type="sphere" size="0.05" mass="1"/>
    </body>
    <body name="loose_body" pos="3 0 1">
      <joint name="loose" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.05" mass="1"/>
    </body>
    <body name="servo_body" pos="4 0 1">
      <joint name="servo" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.05" mass="1"/>
    </body>
    <body name="twice_body" pos="5 0 1">
      <joint name="twice" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.05" mass="1"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="m_yaw" joint="yaw" gear="1" ctrllimited="true" ctrlrange="-200 200"/>
    <motor name="m_shoulder" joint="shoulder" gear="1" ctrllimited="true" ctrlrange="-200 200"/>
    <motor name="m_elbow" joint="elbow" gear="1" ctrllimited="true" ctrlrange="-200 200"/>
    <motor name="m_rail" joint="rail" gear="2" ctrllimited="true" ctrlrange="-200 200"/>
    <position name="p_servo" joint="servo" kp="10"/>
    <motor name="m_twice_1" joint="twice" gear="1"/>
    <motor name="m_twice_2" joint="twice" gear="2"/>
  </actuator>
</mujoco>)";

const std::vector<std::string> kJoints = {"yaw", "shoulder", "elbow"};

class ControllersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = load_scene(dir_, kArm, {});
    ASSERT_TRUE(model_);
    data_.reset(mj_makeData(model_.get()));
    mj_forward(model_.get(), data_.get());
  }

  // One physics step with the controller's command computed on the step's own state.
  template <class Controller>
  void step(Controller& c) {
    mj_step1(model_.get(), data_.get());
    c.apply(model_.get(), data_.get());
    mj_step2(model_.get(), data_.get());
  }

  // Runs `seconds` of simulated time; after each step `after(t, errors)` sees the errors at the
  // new time.
  template <class Controller>
  void run(Controller& c, double seconds,
           const std::function<void(double, const std::vector<double>&)>& after) {
    const auto steps = std::lround(seconds / model_->opt.timestep);
    for (long k = 0; k < steps; ++k) {
      step(c);
      after(data_->time, c.error(data_.get()));
    }
  }

  static double max_abs(const std::vector<double>& x) {
    double m = 0;
    for (double v : x) m = std::max(m, std::abs(v));
    return m;
  }

  TempDir dir_;
  testing::ModelPtr model_;
  testing::DataPtr data_;
};

// Eq. (15) critically damped at 10 rad/s: kp = 100, kv = 20. A 0.3 rad step then decays as
// 0.3 (1 + 10 t) exp(-10 t), below 1e-3 rad from t = 0.85 s (0.79 s in the simulation, whose
// Euler recurrence decays slightly faster).
const PdGains kGains = PdGains::critically_damped(10.0);

TEST_F(ControllersTest, ComputedTorqueStepSettlesBelowOneMilliradianWithinOneSecond) {
  ComputedTorqueController c(model_.get(), kJoints, kGains);
  c.set_target({0.3, 0.3, 0.3});
  // The last time any joint's error was at or above 1e-3 rad.
  double last_outside = 0, worst_after_settling = 0;
  run(c, 3.0, [&](double t, const std::vector<double>& e) {
    if (max_abs(e) >= 1e-3) last_outside = t;
    if (t > 1.0) worst_after_settling = std::max(worst_after_settling, max_abs(e));
  });
  std::printf(
      "computed torque, 0.3 rad step: settled below 1e-3 rad at t = %.3f s; "
      "max error over [1, 3] s = %.2e rad; clamps %llu\n",
      last_outside, worst_after_settling, static_cast<unsigned long long>(c.total_clamps()));
  EXPECT_LT(last_outside, 1.0);
  EXPECT_LT(worst_after_settling, 1e-3);
  // Gravity is fully cancelled: the error keeps decaying instead of stalling at an offset
  // (0.3 (1 + 10 t) exp(-10 t) is 9e-13 rad at 3 s).
  EXPECT_LT(max_abs(c.error(data_.get())), 1e-9);
  EXPECT_EQ(c.total_clamps(), 0u);
}

// The largest tracking error over 4 s of q_d = A sin(w t + phase_i), 0.5 rad at 0.5 Hz, starting on
// the trajectory (q = q_d(0), qd = qd_d(0)). With `feed_forward`, qd_d and qdd_d are the exact
// derivatives; without, the target is the position alone (qd_d = qdd_d = 0).
double sinusoid_tracking_error(const mjModel* m, mjData* d, bool feed_forward) {
  const double amp = 0.5, w = 2 * M_PI * 0.5;
  const std::vector<double> phase = {0.0, 1.0, 2.0};
  ComputedTorqueController c(m, kJoints, kGains);
  auto set_target = [&](double t) {
    std::vector<double> q(3), qd(3), qdd(3);
    for (std::size_t i = 0; i < 3; ++i) {
      q[i] = amp * std::sin(w * t + phase[i]);
      qd[i] = amp * w * std::cos(w * t + phase[i]);
      qdd[i] = -amp * w * w * std::sin(w * t + phase[i]);
    }
    if (feed_forward) {
      c.set_target(q, qd, qdd);
    } else {
      c.set_target(q);
    }
  };
  mj_resetData(m, d);
  for (std::size_t i = 0; i < 3; ++i) {
    const JointDrive& drive = c.drives()[i];
    d->qpos[drive.qpos_adr] = amp * std::sin(phase[i]);
    d->qvel[drive.dof_adr] = amp * w * std::cos(phase[i]);
  }
  mj_forward(m, d);
  double worst = 0;
  const auto steps = std::lround(4.0 / m->opt.timestep);
  for (long k = 0; k < steps; ++k) {
    set_target(d->time);
    mj_step1(m, d);
    c.apply(m, d);
    mj_step2(m, d);
    set_target(d->time);  // the error at the new time against the target at that time
    for (double e : c.error(d)) worst = std::max(worst, std::abs(e));
  }
  return worst;
}

TEST_F(ControllersTest, ComputedTorqueTracksASinusoid) {
  const double at_1ms = sinusoid_tracking_error(model_.get(), data_.get(), true);
  const double without_feed_forward = sinusoid_tracking_error(model_.get(), data_.get(), false);
  model_->opt.timestep = 0.0005;
  const double at_half_ms = sinusoid_tracking_error(model_.get(), data_.get(), true);
  std::printf(
      "computed torque, 0.5 rad 0.5 Hz sinusoids: max tracking error %.2e rad (h = 1 ms), "
      "%.2e rad (h = 0.5 ms), %.2e rad without feed-forward\n",
      at_1ms, at_half_ms, without_feed_forward);
  // Small: under 0.2 % of the amplitude.
  EXPECT_LT(at_1ms, 1e-3);
  // What remains is the integrator's first-order error: it halves with the step.
  EXPECT_NEAR(at_half_ms / at_1ms, 0.5, 0.05);
  // The feed-forward terms of eq. (13) matter: without them the loop lags by tenths of a radian.
  EXPECT_GT(without_feed_forward, 20 * at_1ms);
}

TEST_F(ControllersTest, ComputedTorqueErrorFollowsEquation15) {
  // After a step e0 from rest, eq. (15) with kp = omega^2, kv = 2 omega gives
  // e(t) = e0 (1 + omega t) exp(-omega t) in every joint, whatever the arm's inertia and gravity.
  // The slide's gear, spring and damper are covered too.
  const double e0 = 0.3, omega = 10.0, h = model_->opt.timestep;
  ComputedTorqueController c(model_.get(), {"yaw", "shoulder", "elbow", "rail"},
                             PdGains::critically_damped(omega));
  c.set_target({e0, e0, e0, e0});

  // MuJoCo's semi-implicit Euler makes the loop a linear recurrence; the law is exact when
  // qacc = v, so the simulated errors equal this recurrence up to rounding:
  //   a_k = kp e_k - kv w_k,  w_{k+1} = w_k + h a_k,  e_{k+1} = e_k - h w_{k+1}   (w = qd).
  double e_rec = e0, w_rec = 0, worst_rec = 0, worst_analytic = 0;
  run(c, 1.0, [&](double t, const std::vector<double>& e) {
    const double a = omega * omega * e_rec - 2 * omega * w_rec;
    w_rec += h * a;
    e_rec -= h * w_rec;
    const double analytic = e0 * (1 + omega * t) * std::exp(-omega * t);
    for (double ej : e) {
      worst_rec = std::max(worst_rec, std::abs(ej - e_rec));
      worst_analytic = std::max(worst_analytic, std::abs(ej - analytic));
    }
  });
  std::printf("eq. (15): max |e - recurrence| = %.2e rad, max |e - analytic| = %.2e rad\n",
              worst_rec, worst_analytic);
  EXPECT_LT(worst_rec, 1e-9);
  // The recurrence is a first-order method: its global error is O(h omega) of the amplitude.
  // e0 * h * omega = 3e-3 rad is the scale; the bound below is that scale with room for the
  // constant.
  EXPECT_LT(worst_analytic, e0 * h * omega);
}

TEST_F(ControllersTest, FuzzyInferenceIsAnOddMonotoneMapOntoTheUnitInterval) {
  FuzzyController f(model_.get(), kJoints, FuzzyParams{});
  const FuzzyParams& p = f.params();
  // T is a whole number of 1 ms steps.
  EXPECT_DOUBLE_EQ(f.period(), 0.002);
  EXPECT_DOUBLE_EQ(FuzzyController(model_.get(), kJoints, {0.25, 1.25, 100, 0.0023}).period(),
                   0.002);
  EXPECT_DOUBLE_EQ(FuzzyController(model_.get(), kJoints, {0.25, 1.25, 100, 1e-5}).period(), 0.001);
  // The rule base at the corners and the origin.
  EXPECT_DOUBLE_EQ(f.infer(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(f.infer(p.e_max, p.de_max), 1.0);     // e P, de P -> P
  EXPECT_DOUBLE_EQ(f.infer(-p.e_max, -p.de_max), -1.0);  // e N, de N -> N
  EXPECT_DOUBLE_EQ(f.infer(p.e_max, -p.de_max), 0.0);    // mixed -> ZE
  EXPECT_DOUBLE_EQ(f.infer(-p.e_max, p.de_max), 0.0);
  // Saturation: beyond the ranges nothing changes.
  EXPECT_DOUBLE_EQ(f.infer(10 * p.e_max, 0), f.infer(p.e_max, 0));
  // Near the origin it is the PD law du = (x + y) / 4 of the normalised inputs, to first order.
  EXPECT_NEAR(f.infer(0.01 * p.e_max, 0.01 * p.de_max), 0.005, 3e-5);
  EXPECT_NEAR(f.infer(0.02 * p.e_max, -0.01 * p.de_max), 0.0025, 3e-5);
  // On a grid over twice the ranges: the closed form (x + y) / (4 - 2 max(|x|, |y|)) of the min
  // rules with complementary ramps (x, y the saturated normalised inputs); odd; monotone.
  for (int i = -10; i <= 10; ++i) {
    for (int j = -10; j <= 10; ++j) {
      const double e = 0.2 * i * p.e_max, de = 0.2 * j * p.de_max;
      const double x = std::clamp(0.2 * i, -1.0, 1.0), y = std::clamp(0.2 * j, -1.0, 1.0);
      const double u = f.infer(e, de);
      EXPECT_NEAR(u, (x + y) / (4 - 2 * std::max(std::abs(x), std::abs(y))), 1e-15);
      EXPECT_LE(std::abs(u), 1.0);
      EXPECT_DOUBLE_EQ(f.infer(-e, -de), -u);
      EXPECT_LE(u, f.infer(e + 0.05 * p.e_max, de) + 1e-15);
      EXPECT_LE(u, f.infer(e, de + 0.05 * p.de_max) + 1e-15);
    }
  }
}

TEST_F(ControllersTest, FuzzyStepStaysBoundedAndConverges) {
  FuzzyController f(model_.get(), kJoints, FuzzyParams{});
  const double step = 0.3;
  f.set_target({step, step, -step});
  double worst = 0, last_outside = 0, final_error = 0;
  run(f, 4.0, [&](double t, const std::vector<double>& e) {
    worst = std::max(worst, max_abs(e));
    if (max_abs(e) >= 1e-3) last_outside = t;
    final_error = max_abs(e);
  });
  std::printf(
      "fuzzy, 0.3 rad step: max |e| %.3f rad, below 1e-3 rad from t = %.3f s, "
      "|e| at 4 s = %.2e rad, clamps %llu\n",
      worst, last_outside, final_error, static_cast<unsigned long long>(f.total_clamps()));
  // Bounded (at most twice the step, and in fact no overshoot past the initial error here),
  // settled well within 1 s (0.84 s measured), and converged to rounding: a sign error anywhere
  // in e, de, the rules or the output would diverge instead.
  EXPECT_LE(worst, 2 * step);
  EXPECT_LT(last_outside, 1.0);
  EXPECT_LT(final_error, 1e-9);
}

TEST_F(ControllersTest, BadInputRaisesInvalidArgumentNamingTheProblem) {
  auto message = [&](const std::vector<std::string>& joints, PdGains g = kGains) -> std::string {
    try {
      ComputedTorqueController c(model_.get(), joints, g);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message({}).find("no joints"), std::string::npos);
  EXPECT_NE(message({"yaw", "wrist"}).find("'wrist' does not exist"), std::string::npos);
  EXPECT_NE(message({"yaw", "yaw"}).find("'yaw' is listed twice"), std::string::npos);
  EXPECT_NE(message({"ball"}).find("'ball' is not a hinge or slide"), std::string::npos);
  EXPECT_NE(message({"loose"}).find("'loose' has no motor actuator"), std::string::npos);
  EXPECT_NE(message({"servo"}).find("'servo' has no motor actuator"), std::string::npos);
  EXPECT_NE(message({"twice"}).find("more than one motor"), std::string::npos);
  EXPECT_NE(message(kJoints, {100, 0}).find("finite and positive"), std::string::npos);
  EXPECT_NE(message(kJoints, {NAN, 20}).find("finite and positive"), std::string::npos);
  EXPECT_EQ(message(kJoints), "");

  ComputedTorqueController c(model_.get(), kJoints, kGains);
  EXPECT_THROW(c.set_target({0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(c.set_target({0, 0, 0}, {0, 0, 0}, {0}), std::invalid_argument);
  EXPECT_THROW(FuzzyController(model_.get(), kJoints, FuzzyParams{0.3, 1.0, 100, 0}),
               std::invalid_argument);
  EXPECT_THROW(FuzzyController(model_.get(), {"ball"}, FuzzyParams{}), std::invalid_argument);
}

TEST_F(ControllersTest, CommandsAreClampedToTheControlRangeAndCounted) {
  // A 3 rad step with kp = 1e4 asks for far more than 200 N m at the first step.
  ComputedTorqueController c(model_.get(), kJoints, PdGains::critically_damped(100.0));
  c.set_target({3.0, 3.0, 3.0});
  step(c);
  EXPECT_EQ(c.last_clamps(), 3);
  for (const JointDrive& drive : c.drives()) EXPECT_EQ(std::abs(data_->ctrl[drive.actuator]), 200);
}

}  // namespace
}  // namespace graspcd::grasp
