// Joint controllers of the arm and the fingers (paper sections 7 and 8): computed-torque control,
// eq. (12)-(16), and the fuzzy controller of section 8, eq. (17)-(18), both on MuJoCo's dynamics.
//
// The plant is eq. (10): D(q) qdd + C(q, qd) qd + g(q) = tau. MuJoCo gives D as the joint-space
// inertia d->qM (armature included) and C qd + g as d->qfrc_bias (recursive Newton-Euler); both are
// current after mj_forward or mj_step1. Passive forces (joint springs and damping, d->qfrc_passive)
// are part of MuJoCo's eq. (10) too and are cancelled with the bias; with the Euler integrator and
// joint damping, D is qM + h diag(damping), the matrix MuJoCo's implicit-damping step solves with.
// Constraint forces (contacts, joint limits, equalities) are not cancelled: they are the
// disturbance the outer loop rejects.
//
// Use, once per physics step (the ordering makes the law exact for MuJoCo's Euler integrator):
//   mj_step1(m, d);  controller.apply(m, d);  mj_step2(m, d);
//
// Actuation assumption: each controlled joint (hinge or slide) is driven by exactly one motor
// actuator: transmission to that joint, no activation dynamics, fixed gain, no bias, so that the
// joint force is ctrl * gain * gear (gain = gainprm[0], 1 for <motor>; gear = gear[0]). Commands
// are clamped to ctrlrange (when ctrllimited) and to forcerange / gain (when forcelimited); the
// clamps are counted. Other actuators on the same joint (none expected) are left alone.
//
// Coupling: the law uses the rows and columns of D for the controlled dofs only; accelerations of
// other dofs (e.g. the fingers while a controller drives the arm) are taken as zero. Control every
// joint with one controller for an exact decoupling.
#pragma once

#include <mujoco/mujoco.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace graspcd::grasp {

// One controlled joint and the motor that drives it.
struct JointDrive {
  int joint = -1;              // joint id
  int qpos_adr = -1;           // index into qpos
  int dof_adr = -1;            // index into qvel, qfrc_*, and the rows of qM
  int actuator = -1;           // actuator id
  double force_per_ctrl = 1;   // joint force (N m or N) per unit of ctrl: gain * gear, non-zero
  double ctrl_lo = -mjMAXVAL;  // admissible ctrl interval (ctrlrange and forcerange combined)
  double ctrl_hi = mjMAXVAL;
};

// Resolves joint names to drives. Throws std::invalid_argument, naming the joint, for: an empty
// list, an unknown or repeated name, a joint that is neither hinge nor slide, a joint with no motor
// actuator or with more than one, and a motor with zero gain * gear.
std::vector<JointDrive> resolve_joint_drives(const mjModel* m,
                                             const std::vector<std::string>& joint_names);

// Eq. (12): tau = D(q) v + C(q, qd) qd + g(q) (minus passive forces) for the drives' dofs, with v
// the commanded acceleration of each drive (zero for other dofs), written to d->ctrl through the
// motors. Needs qM, qfrc_bias and qfrc_passive current (after mj_forward or mj_step1). `scratch`
// is resized to 2 * nv. Returns how many commands were clamped.
int apply_inverse_dynamics(const mjModel* m, mjData* d, const std::vector<JointDrive>& drives,
                           const std::vector<double>& v, std::vector<mjtNum>& scratch);

// Diagonal gains of eq. (13): Kp = kp I, Kv = kv I.
struct PdGains {
  double kp = 100;  // 1/s^2
  double kv = 20;   // 1/s
  // Eq. (15) critically damped at natural frequency omega (rad/s): kp = omega^2, kv = 2 omega;
  // the error of a step then decays as e0 (1 + omega t) exp(-omega t).
  static PdGains critically_damped(double omega) { return {omega * omega, 2 * omega}; }
};

// What both controllers share: the drives, the desired trajectory (targets default to the
// joints' positions in the model's reference configuration, qpos0, with zero velocity and
// acceleration), the error of eq. (16), and eq. (12) written through the motors with the clamps
// counted. A controller fills the commanded accelerations v_ and calls write_torques().
class JointController {
 public:
  std::size_t size() const { return drives_.size(); }
  const std::vector<JointDrive>& drives() const { return drives_; }

  // The desired trajectory at the current time: q_d, qd_d, qdd_d, each of size(); throws
  // std::invalid_argument on a size mismatch.
  void set_target(const std::vector<double>& q_d, const std::vector<double>& qd_d,
                  const std::vector<double>& qdd_d);
  // Position target only, with zero desired velocity and acceleration (a set point).
  void set_target(const std::vector<double>& q_d);

  // Eq. (16): e_q = q_d - q of each drive, in the state of d.
  std::vector<double> error(const mjData* d) const;
  // Commands clamped by the last apply() and since construction.
  int last_clamps() const { return last_clamps_; }
  std::uint64_t total_clamps() const { return total_clamps_; }

 protected:
  // Throws std::invalid_argument (see resolve_joint_drives).
  JointController(const mjModel* m, const std::vector<std::string>& joint_names);
  // Eq. (12) with the commanded accelerations v_, written to d->ctrl (apply_inverse_dynamics).
  void write_torques(const mjModel* m, mjData* d);

  std::vector<JointDrive> drives_;
  std::vector<double> q_d_, qd_d_, qdd_d_, v_;

 private:
  std::vector<mjtNum> scratch_;
  int last_clamps_ = 0;
  std::uint64_t total_clamps_ = 0;
};

// Computed-torque control (inverse dynamics), eq. (12)-(16).
class ComputedTorqueController : public JointController {
 public:
  // Throws std::invalid_argument (see resolve_joint_drives) and for gains that are not finite and
  // positive (eq. (15) is stable exactly when kp > 0 and kv > 0).
  ComputedTorqueController(const mjModel* m, const std::vector<std::string>& joint_names,
                           PdGains gains);

  const PdGains& gains() const { return gains_; }

  // Eq. (13) and (12): computes v and writes d->ctrl for the drives.
  void apply(const mjModel* m, mjData* d);

 private:
  PdGains gains_;
};

// Parameters of the fuzzy controller. Inputs are normalised by their range and saturated to
// [-1, 1]; the output is normalised to [-1, 1] and scaled by u_max. Near zero error the inference
// below is the PD law du = (e / e_max + de / de_max) / 4 to first order, i.e. eq. (13) with
// Kp = u_max / (4 e_max) and Kv = u_max / (4 de_max). The defaults give Kp = 100 / s^2 and
// Kv = 20 / s there (eq. (15) critically damped at 10 rad/s), with the acceleration command
// bounded by u_max away from zero.
struct FuzzyParams {
  double e_max = 0.25;    // error at which e is fully P (or N), rad (m for slides)
  double de_max = 1.25;   // error rate at which de is fully P (or N), rad/s (m/s)
  double u_max = 100.0;   // acceleration command v at output P, rad/s^2 (m/s^2)
  double period = 0.002;  // sample period T of eq. (18), s; rounded to a whole number of steps
};

// The fuzzy controller of section 8, one independent fuzzy system per joint.
//
// Inputs: e = q_d - q (eq. 17) and de = (e(t) - e(t - T)) / T (eq. 18, with the paper's typo fixed:
// the difference quotient divides by the sample period T). At the first sample de = 0.
//
// Memberships (paper Figure 8 is not available; our choice): on the normalised inputs
// x = sat(e / e_max) and y = sat(de / de_max) in [-1, 1], two complementary linear ramps
//   mu_N(x) = (1 - x) / 2,  mu_P(x) = (1 + x) / 2,
// i.e. triangles with feet at -1 and +1 and peaks at the opposite end; with the saturation they
// are trapezoids on the raw input (fully N below -e_max, fully P above e_max, 0.5/0.5 at zero).
// Output sets: singletons N = -1, ZE = 0, P = +1 (zero-order Takagi-Sugeno).
//
// Rule base (a PD-like phase-plane table):
//   e P and de P -> P;  e N and de N -> N;  e P and de N -> ZE;  e N and de P -> ZE.
// Inference: AND is min; defuzzification the weighted average of the singletons,
//   du = (w_PP - w_NN) / (w_PP + w_NN + w_PN + w_NP),
// which with these memberships is exactly du = (x + y) / (4 - 2 max(|x|, |y|)): an odd, monotone
// map of (x, y) onto [-1, 1], zero on x = -y, +1 only at x = y = 1, and (x + y) / 4 near zero.
//
// Output use: the paper's "another choice of the command: v = fuzzy control" (section 8). The
// fuzzy output replaces v in eq. (12): v = qdd_d + u_max * du, held for T, while D, C qd and g are
// refreshed every physics step: the fuzzy system shapes a decoupled double integrator with a
// bounded acceleration command. (An incremental torque u(t) = u(t - T) + du would make it a PI law
// on a double integrator, unstable without damping in the plant.)
class FuzzyController : public JointController {
 public:
  // Throws std::invalid_argument (see resolve_joint_drives) and for parameters that are not finite
  // and positive.
  FuzzyController(const mjModel* m, const std::vector<std::string>& joint_names,
                  const FuzzyParams& params);

  const FuzzyParams& params() const { return params_; }
  // T as used: a whole number of physics steps (at least one).
  double period() const { return static_cast<double>(period_steps_) * timestep_; }

  // The normalised fuzzy output du in [-1, 1] for the raw inputs e (rad) and de (rad/s): the
  // normalisation, memberships, rule base and defuzzification above.
  double infer(double e, double de) const;

  // Call once per physics step: on every T-th call samples e and de and runs the fuzzy systems;
  // on every call writes eq. (12) with the held command to d->ctrl.
  void apply(const mjModel* m, mjData* d);

 private:
  FuzzyParams params_;
  double timestep_;
  long period_steps_;
  long calls_ = 0;
  bool have_previous_ = false;
  std::vector<double> e_previous_, du_;
};

}  // namespace graspcd::grasp
