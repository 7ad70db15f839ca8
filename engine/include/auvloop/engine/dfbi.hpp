// SPDX-License-Identifier: GPL-3.0-or-later
// The body's six degrees of freedom coupled to the flow around it (DFBI, issue 18, item 3;
// docs/dfbi.md): Fossen's rigid-body equations about the body origin o,
//     M_RB nu' + C_RB(nu) nu = tau_flow + tau_gb(q),
// tau_flow the loads the flow solution gives (pressure and shear on the walls, the propeller's
// reaction), tau_gb weight and buoyancy, advanced over [t_n, t_n + dt] inside the flow's outer
// iterations:
//   1. begin_step(dt, second_order): the predictor a_0 = a^n (the last step's acceleration),
//      nu_0 from the time scheme and the pose from the kinematics (step 3's formulas);
//   2. correct(tau_flow), after each outer iteration, with the loads of the flow that moved
//      with the iterate k - 1: the free degrees of freedom F solve
//          (M_RB + M_A)_FF a* = (tau_flow + tau_gb(q_{k-1}) - C_RB(nu_{k-1}) nu_{k-1})_F
//                               + (M_A a_{k-1})_F,
//      the held ones keep a = 0 (their velocity and, for p and q, the attitude's roll and
//      pitch stay as they were); a_k = a_{k-1} + relax (a* - a_{k-1}). M_A is an estimate of
//      the fluid's added mass (Prestero's derivatives for a vehicle): the flow's pressure
//      answers the iterate's acceleration with about -M_A a_{k-1}, and adding M_A a on both
//      sides takes that answer implicitly. A fixed point (a_k = a_{k-1}) is the rigid body's
//      own equation whatever M_A: the estimate shapes the iteration, never the motion. Without
//      it (M_A = 0) the iteration's factor is -M_A,true / M_RB, beyond -1 in sway for REMUS
//      (added mass above the body's own), and diverges unless relax < 2 M_RB / (M_RB + M_A,true);
//   3. the time scheme, the flow's own (the fluid and the body see one acceleration of the
//      walls): BDF2, nu^{n+1} = (4 nu^n - nu^{n-1} + 2 dt a) / 3, or Euler,
//      nu^{n+1} = nu^n + dt a; the pose to second order with the mean rates
//      omega_m = (omega^n + omega^{n+1}) / 2, v_m likewise:
//          q^{n+1} = q^n exp(dt omega_m / 2),  x^{n+1} = x^n + dt R(q^n exp(dt omega_m / 4)) v_m;
//   4. accept(): the last iterate becomes the state at t_n + dt.
// reset(state) starts from a steady past (nu^{n-1} = nu^n, a^n = 0): BDF2 from the first step,
// as the flow restarted from a converged straight run.
// Invariants: relax in (0, 1]; M_RB + M_A symmetric positive definite on the free degrees of
// freedom (the constructor checks both and throws std::invalid_argument).
#pragma once

#include <array>

#include "auvloop/engine/rigid_body.hpp"

namespace auvloop::engine {

struct DfbiBody {
  Matrix6d mass = Matrix6d::Zero();        // M_RB about the body origin (rigid_body_mass)
  Matrix6d added_mass = Matrix6d::Zero();  // M_A, the coupling's estimate (step 2)
  double weight = 0, buoyancy = 0;         // W, B (N)
  Eigen::Vector3d r_g = Eigen::Vector3d::Zero(), r_b = Eigen::Vector3d::Zero();  // m, from o
  // u v w p q r; `horizontal` frees surge, sway and yaw only.
  std::array<bool, 6> free{true, true, true, true, true, true};
  double relax = 1.0;  // of the acceleration (step 2)
  static constexpr std::array<bool, 6> horizontal{true, true, false, false, false, true};
};

// What an exact restart needs (the accepted state and its history).
struct DfbiHistory {
  BodyState state;
  Vector6d nu_old = Vector6d::Zero();        // nu^{n-1}
  Vector6d acceleration = Vector6d::Zero();  // a^n
};

class Dfbi {
 public:
  explicit Dfbi(DfbiBody body);

  void reset(const BodyState& state);
  // Step 1; returns the first iterate. Throws std::invalid_argument unless dt > 0.
  const BodyState& begin_step(double dt, bool second_order);
  // Step 2 with the flow's loads (N, N m about the origin, body axes) at the current iterate;
  // returns the new iterate. Its change in acceleration is change().
  const BodyState& correct(const Vector6d& tau_flow);
  // Step 4.
  void accept();

  [[nodiscard]] const BodyState& state() const { return history_.state; }  // accepted
  [[nodiscard]] const BodyState& iterate() const { return iterate_; }
  // The iterate's acceleration nu' (body axes), and the last correction's change of it,
  // |a_k - a_{k-1}| over the free degrees of freedom (the coupling's residual).
  [[nodiscard]] const Vector6d& acceleration() const { return a_; }
  [[nodiscard]] double change() const { return change_; }
  [[nodiscard]] const DfbiHistory& history() const { return history_; }
  void restore(const DfbiHistory& h);
  [[nodiscard]] const DfbiBody& body() const { return body_; }
  // Frees or holds degrees of freedom from the next step on (a towed start, then released);
  // throws std::invalid_argument as the constructor, keeping the previous set.
  void set_free(const std::array<bool, 6>& free);

 private:
  void advance_iterate();  // step 3 from history_ with a_
  void validate() const;   // the invariants
  DfbiBody body_;
  DfbiHistory history_;
  BodyState iterate_;
  Vector6d a_ = Vector6d::Zero();
  double dt_ = 0, change_ = 0;
  bool second_order_ = true;
};

}  // namespace auvloop::engine
