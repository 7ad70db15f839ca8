// SPDX-License-Identifier: GPL-3.0-or-later
// Plants built on Prestero's model: the nonlinear one his simulator runs, and its linearisation
// about straight running (the paper's "linear model").
#pragma once

#include <complex>
#include <vector>

#include "auvloop/engine/plant.hpp"
#include "auvloop/engine/prestero.hpp"

namespace auvloop::engine {

struct DerivativePlantOptions {
  double max_substep = 0.005;  // s; RK4 substeps per loop step so that dt can be larger
  double runaway_speed = 20;   // m/s; beyond it the run stops as diverged
  double runaway_rate = 20;    // rad/s for p, q, r
};

class DerivativePlant final : public Plant {
 public:
  DerivativePlant(PresteroModel model, DerivativePlantOptions options = {});
  [[nodiscard]] std::string name() const override { return "derivative"; }
  void reset(const BodyState& initial) override { state_ = initial; }
  PlantResult advance(const ActuatorValues& a, double dt) override;
  [[nodiscard]] const BodyState& state() const override { return state_; }
  [[nodiscard]] const PresteroModel& model() const { return model_; }
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

 private:
  PresteroModel model_;
  DerivativePlantOptions options_;
  BodyState state_;
};

// nu' = f0 + A (x - x0) + B (c - c0), x = (u v w p q r phi theta), c = (delta_r, delta_s, rpm),
// the Jacobians of Prestero's model at straight running with rudders at zero. f0 keeps the trim
// residual (REMUS is 7 N buoyant), so the linear and nonlinear models agree at the trim point.
// Kinematics stay exact: heading and position are meaningful through any turn.
// `horizontal` keeps only the horizontal-plane part (u, v, r): heave, roll and pitch stay at
// trim. That is the usual linear model for yaw manoeuvres; the full one carries the unstable
// heave-pitch pair of a body with no depth control.
struct Linearization {
  bool horizontal = false;
  Eigen::Matrix<double, 8, 1> x0;
  Eigen::Vector3d c0;
  Vector6d f0;
  Eigen::Matrix<double, 6, 8> A;
  Eigen::Matrix<double, 6, 3> B;
  // Eigenvalues (1/s) of the 8-state system (nu, phi, theta) with phi' = p, theta' = q, or of the
  // 3-state (u, v, r) system when horizontal.
  [[nodiscard]] std::vector<std::complex<double>> eigenvalues() const;
};

Linearization linearize_straight_running(const PresteroModel& model, double rpm,
                                         bool horizontal = false);

class LinearizedPlant final : public Plant {
 public:
  LinearizedPlant(Linearization lin, DerivativePlantOptions options = {});
  [[nodiscard]] std::string name() const override { return "linearized"; }
  void reset(const BodyState& initial) override { state_ = initial; }
  PlantResult advance(const ActuatorValues& a, double dt) override;
  [[nodiscard]] const BodyState& state() const override { return state_; }
  [[nodiscard]] const Linearization& linearization() const { return lin_; }
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

 private:
  [[nodiscard]] Vector6d acceleration(const BodyState& s, const ActuatorValues& a) const;
  Linearization lin_;
  DerivativePlantOptions options_;
  BodyState state_;
};

}  // namespace auvloop::engine
