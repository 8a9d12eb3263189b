#include "graspcd/grasp/controllers.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace graspcd::grasp {
namespace {

[[noreturn]] void fail(const std::string& message) { throw std::invalid_argument(message); }

bool is_motor(const mjModel* m, int a) {
  return m->actuator_dyntype[a] == mjDYN_NONE && m->actuator_gaintype[a] == mjGAIN_FIXED &&
         m->actuator_biastype[a] == mjBIAS_NONE;
}

bool finite_positive(double x) { return std::isfinite(x) && x > 0; }

void check_size(const std::vector<double>& x, std::size_t n, const char* what) {
  if (x.size() != n)
    fail(std::string("controller target: ") + what + " has " + std::to_string(x.size()) +
         " entries, expected " + std::to_string(n) + " (one per joint)");
}

// Eq. (16) / (17): e = q_d - q for every drive.
std::vector<double> joint_errors(const mjData* d, const std::vector<JointDrive>& drives,
                                 const std::vector<double>& q_d) {
  std::vector<double> e(drives.size());
  for (std::size_t i = 0; i < drives.size(); ++i) e[i] = q_d[i] - d->qpos[drives[i].qpos_adr];
  return e;
}

}  // namespace

std::vector<JointDrive> resolve_joint_drives(const mjModel* m,
                                             const std::vector<std::string>& joint_names) {
  if (joint_names.empty()) fail("controller: no joints given");
  std::vector<JointDrive> drives;
  std::set<int> seen;
  for (const std::string& name : joint_names) {
    const std::string where = "controller: joint '" + name + "'";
    // The joint: known, new, one dof.
    const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (j < 0) fail(where + " does not exist in the model");
    if (!seen.insert(j).second) fail(where + " is listed twice");
    if (m->jnt_type[j] != mjJNT_HINGE && m->jnt_type[j] != mjJNT_SLIDE)
      fail(where + " is not a hinge or slide joint (free and ball joints are not controlled)");

    // Its one motor: transmission to the joint, ctrl -> force without dynamics or bias.
    int motor = -1;
    for (int a = 0; a < m->nu; ++a) {
      if (m->actuator_trntype[a] != mjTRN_JOINT || m->actuator_trnid[2 * a] != j) continue;
      if (!is_motor(m, a)) continue;
      if (motor >= 0) fail(where + " is driven by more than one motor actuator");
      motor = a;
    }
    if (motor < 0)
      fail(where + " has no motor actuator (transmission to the joint, no dynamics, fixed gain, " +
           "no bias)");

    JointDrive drive;
    drive.joint = j;
    drive.qpos_adr = m->jnt_qposadr[j];
    drive.dof_adr = m->jnt_dofadr[j];
    drive.actuator = motor;
    const double gain = m->actuator_gainprm[mjNGAIN * motor];
    drive.force_per_ctrl = gain * m->actuator_gear[6 * motor];
    if (!finite_positive(std::abs(drive.force_per_ctrl)))
      fail(where + ": its motor has zero or non-finite gain * gear");

    // The admissible ctrl interval: ctrlrange, and forcerange (on gain * ctrl) mapped back.
    if (m->actuator_ctrllimited[motor]) {
      drive.ctrl_lo = m->actuator_ctrlrange[2 * motor];
      drive.ctrl_hi = m->actuator_ctrlrange[2 * motor + 1];
    }
    if (m->actuator_forcelimited[motor] && gain != 0) {
      double lo = m->actuator_forcerange[2 * motor] / gain;
      double hi = m->actuator_forcerange[2 * motor + 1] / gain;
      if (lo > hi) std::swap(lo, hi);
      drive.ctrl_lo = std::max(drive.ctrl_lo, lo);
      drive.ctrl_hi = std::min(drive.ctrl_hi, hi);
    }
    drives.push_back(drive);
  }
  return drives;
}

// Eq. (12): tau = D(q) v + C(q, qd) qd + g(q), with MuJoCo's D = qM (sparse product mj_mulM) and
// C qd + g = qfrc_bias; the passive forces are cancelled too, so that MuJoCo's forward dynamics
// qM qacc = qfrc_actuator + qfrc_passive - qfrc_bias (+ constraints) gives qacc = v.
// MuJoCo 2.2's Euler step integrates joint damping B implicitly when any dof has damping: it
// solves (qM + h B) qacc = qfrc_smooth + qfrc_constraint. Then D is taken as qM + h B, which keeps
// the step's acceleration exactly v.
int apply_inverse_dynamics(const mjModel* m, mjData* d, const std::vector<JointDrive>& drives,
                           const std::vector<double>& v, std::vector<mjtNum>& scratch) {
  const auto nv = static_cast<std::size_t>(m->nv);
  scratch.assign(2 * nv, 0);
  mjtNum* acc = scratch.data();
  mjtNum* inertial = scratch.data() + nv;

  // D v with v on the drives' dofs, zero elsewhere.
  for (std::size_t i = 0; i < drives.size(); ++i) acc[drives[i].dof_adr] = v[i];
  mj_mulM(m, d, inertial, acc);

  // The implicit-damping term of the Euler step, h B v.
  if (m->opt.integrator == mjINT_EULER) {
    const bool damped =
        std::any_of(m->dof_damping, m->dof_damping + m->nv, [](mjtNum b) { return b > 0; });
    if (damped) {
      for (int k = 0; k < m->nv; ++k) inertial[k] += m->opt.timestep * m->dof_damping[k] * acc[k];
    }
  }

  // tau per dof, then ctrl = tau / (gain * gear), clamped.
  int clamps = 0;
  for (const JointDrive& drive : drives) {
    const int k = drive.dof_adr;
    const double tau = inertial[k] + d->qfrc_bias[k] - d->qfrc_passive[k];
    const double ctrl = tau / drive.force_per_ctrl;
    const double clamped = std::clamp(ctrl, drive.ctrl_lo, drive.ctrl_hi);
    if (clamped != ctrl) ++clamps;
    d->ctrl[drive.actuator] = clamped;
  }
  return clamps;
}

JointController::JointController(const mjModel* m, const std::vector<std::string>& joint_names)
    : drives_(resolve_joint_drives(m, joint_names)) {
  const std::size_t n = drives_.size();
  q_d_.resize(n);
  for (std::size_t i = 0; i < n; ++i) q_d_[i] = m->qpos0[drives_[i].qpos_adr];
  qd_d_.assign(n, 0);
  qdd_d_.assign(n, 0);
  v_.assign(n, 0);
}

void JointController::set_target(const std::vector<double>& q_d, const std::vector<double>& qd_d,
                                 const std::vector<double>& qdd_d) {
  check_size(q_d, size(), "q_d");
  check_size(qd_d, size(), "qd_d");
  check_size(qdd_d, size(), "qdd_d");
  q_d_ = q_d;
  qd_d_ = qd_d;
  qdd_d_ = qdd_d;
}

void JointController::set_target(const std::vector<double>& q_d) {
  set_target(q_d, std::vector<double>(size(), 0), std::vector<double>(size(), 0));
}

std::vector<double> JointController::error(const mjData* d) const {
  return joint_errors(d, drives_, q_d_);
}

void JointController::write_torques(const mjModel* m, mjData* d) {
  last_clamps_ = apply_inverse_dynamics(m, d, drives_, v_, scratch_);
  total_clamps_ += static_cast<std::uint64_t>(last_clamps_);
}

ComputedTorqueController::ComputedTorqueController(const mjModel* m,
                                                   const std::vector<std::string>& joint_names,
                                                   PdGains gains)
    : JointController(m, joint_names), gains_(gains) {
  if (!finite_positive(gains.kp) || !finite_positive(gains.kv))
    fail("computed-torque controller: gains kp and kv must be finite and positive (got kp = " +
         std::to_string(gains.kp) + ", kv = " + std::to_string(gains.kv) + ")");
}

// Eq. (13): v = qdd_d + Kv (qd_d - qd) + Kp (q_d - q); then eq. (12). Substituted in eq. (10) this
// gives eq. (14) and the error dynamics eq. (15): e'' + Kv e' + Kp e = 0 with e = q_d - q (16).
void ComputedTorqueController::apply(const mjModel* m, mjData* d) {
  for (std::size_t i = 0; i < size(); ++i) {
    const JointDrive& drive = drives_[i];
    v_[i] = qdd_d_[i] + gains_.kv * (qd_d_[i] - d->qvel[drive.dof_adr]) +
            gains_.kp * (q_d_[i] - d->qpos[drive.qpos_adr]);
  }
  write_torques(m, d);
}

FuzzyController::FuzzyController(const mjModel* m, const std::vector<std::string>& joint_names,
                                 const FuzzyParams& params)
    : JointController(m, joint_names), params_(params), timestep_(m->opt.timestep) {
  if (!finite_positive(params.e_max) || !finite_positive(params.de_max) ||
      !finite_positive(params.u_max) || !finite_positive(params.period))
    fail("fuzzy controller: e_max, de_max, u_max and period must be finite and positive");
  period_steps_ = std::max(1L, std::lround(params.period / timestep_));
  e_previous_.assign(size(), 0);
  du_.assign(size(), 0);
}

// Section 8: normalisation and saturation, memberships N/P of e and de, the four rules with min as
// AND, weighted average of the output singletons N = -1, ZE = 0, P = +1 (see controllers.h).
double FuzzyController::infer(double e, double de) const {
  // Normalised, saturated inputs.
  const double x = std::clamp(e / params_.e_max, -1.0, 1.0);
  const double y = std::clamp(de / params_.de_max, -1.0, 1.0);
  // Memberships: complementary ramps on [-1, 1].
  const double e_n = 0.5 * (1 - x), e_p = 0.5 * (1 + x);
  const double de_n = 0.5 * (1 - y), de_p = 0.5 * (1 + y);
  // Rule strengths.
  const double w_pp = std::min(e_p, de_p);  // -> P
  const double w_nn = std::min(e_n, de_n);  // -> N
  const double w_pn = std::min(e_p, de_n);  // -> ZE
  const double w_np = std::min(e_n, de_p);  // -> ZE
  // Weighted average of the singletons. The weights sum to at least 1, so the division is safe:
  // for e_p <= de_p, w_pp + w_nn = 1 - (de_p - e_p) and w_np >= de_p - e_p (symmetric otherwise).
  return (w_pp - w_nn) / (w_pp + w_nn + w_pn + w_np);
}

// Eq. (17), (18) every T, the fuzzy output as v of eq. (12) held between samples, eq. (12) every
// physics step.
void FuzzyController::apply(const mjModel* m, mjData* d) {
  if (calls_++ % period_steps_ == 0) {
    const std::vector<double> e = joint_errors(d, drives_, q_d_);
    const double t = period();
    for (std::size_t i = 0; i < size(); ++i) {
      const double de = have_previous_ ? (e[i] - e_previous_[i]) / t : 0.0;
      du_[i] = infer(e[i], de);
    }
    e_previous_ = e;
    have_previous_ = true;
  }
  for (std::size_t i = 0; i < size(); ++i) v_[i] = qdd_d_[i] + params_.u_max * du_[i];
  write_torques(m, d);
}

}  // namespace graspcd::grasp
