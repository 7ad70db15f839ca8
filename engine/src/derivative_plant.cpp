// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/derivative_plant.hpp"

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

namespace auvloop::engine {
namespace {

std::optional<PlantFailure> check(const BodyState& s, const DerivativePlantOptions& o) {
  if (!s.nu.allFinite() || !s.position.allFinite() || !s.attitude.coeffs().allFinite()) {
    return PlantFailure{"the state is no longer finite (NaN or infinity)"};
  }
  const double speed = s.nu.head<3>().norm();
  if (speed > o.runaway_speed) {
    return PlantFailure{fmt::format("speed {:.3g} m/s exceeds the runaway limit of {:g} m/s", speed,
                                    o.runaway_speed)};
  }
  const double rate = s.nu.tail<3>().cwiseAbs().maxCoeff();
  if (rate > o.runaway_rate) {
    return PlantFailure{fmt::format(
        "angular rate {:.3g} rad/s exceeds the runaway limit of {:g} rad/s", rate, o.runaway_rate)};
  }
  return std::nullopt;
}

// Integrates over dt in equal RK4 substeps no longer than max_substep.
template <class Acceleration>
PlantResult integrate(BodyState& state, double dt, const DerivativePlantOptions& o,
                      Acceleration&& f) {
  const int n = std::max(1, static_cast<int>(std::ceil(dt / o.max_substep - 1e-9)));
  BodyState s = state;
  for (int i = 0; i < n; ++i) {
    s = rk4_step(s, dt / n, f);
    if (auto failure = check(s, o)) return *failure;
  }
  state = s;
  return PlantStep{s, f(s)};
}

}  // namespace

DerivativePlant::DerivativePlant(PresteroModel model, DerivativePlantOptions options)
    : model_(std::move(model)), options_(options) {}

PlantResult DerivativePlant::advance(const ActuatorValues& a, double dt) {
  return integrate(state_, dt, options_, [&](const BodyState& s) {
    const EulerAngles e = s.euler();
    return model_.acceleration(s.nu, e.phi, e.theta, a.delta_r, a.delta_s, a.rpm);
  });
}

Linearization linearize_straight_running(const PresteroModel& model, double rpm, bool horizontal) {
  Linearization lin;
  lin.horizontal = horizontal;
  lin.x0.setZero();
  lin.x0[0] = model.equilibrium_speed(rpm);
  lin.c0 = Eigen::Vector3d(0, 0, rpm);
  auto f = [&](const Eigen::Matrix<double, 8, 1>& x, const Eigen::Vector3d& c) {
    return model.acceleration(x.head<6>(), x[6], x[7], c[0], c[1], c[2]);
  };
  lin.f0 = f(lin.x0, lin.c0);
  // Central differences: the model is polynomial in the states (v|v| has a continuous
  // derivative), so the truncation error is O(h^2) with h = 1e-6.
  for (int j = 0; j < 8; ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(lin.x0[j]));
    Eigen::Matrix<double, 8, 1> xp = lin.x0, xm = lin.x0;
    xp[j] += h;
    xm[j] -= h;
    lin.A.col(j) = (f(xp, lin.c0) - f(xm, lin.c0)) / (2 * h);
  }
  for (int j = 0; j < 3; ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(lin.c0[j]));
    Eigen::Vector3d cp = lin.c0, cm = lin.c0;
    cp[j] += h;
    cm[j] -= h;
    lin.B.col(j) = (f(lin.x0, cp) - f(lin.x0, cm)) / (2 * h);
  }
  if (horizontal) {
    // Keep surge, sway and yaw; heave, roll, pitch rows and the couplings into them vanish.
    for (int i : {2, 3, 4}) {
      lin.A.row(i).setZero();
      lin.B.row(i).setZero();
      lin.f0[i] = 0;
    }
    for (int j : {2, 3, 4, 6, 7}) lin.A.col(j).setZero();
  }
  return lin;
}

std::vector<std::complex<double>> Linearization::eigenvalues() const {
  if (horizontal) {
    Eigen::Matrix3d planar;
    const int k[] = {0, 1, 5};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) planar(i, j) = A(k[i], k[j]);
    }
    const Eigen::EigenSolver<Eigen::Matrix3d> solver(planar);
    std::vector<std::complex<double>> out(solver.eigenvalues().begin(), solver.eigenvalues().end());
    std::sort(out.begin(), out.end(), [](auto a, auto b) { return a.real() > b.real(); });
    return out;
  }
  Eigen::Matrix<double, 8, 8> system = Eigen::Matrix<double, 8, 8>::Zero();
  system.topRows<6>() = A;
  system(6, 3) = 1;  // phi' = p at zero roll and pitch
  system(7, 4) = 1;  // theta' = q
  const Eigen::EigenSolver<Eigen::Matrix<double, 8, 8>> solver(system);
  std::vector<std::complex<double>> out(solver.eigenvalues().begin(), solver.eigenvalues().end());
  std::sort(out.begin(), out.end(), [](auto a, auto b) { return a.real() > b.real(); });
  return out;
}

LinearizedPlant::LinearizedPlant(Linearization lin, DerivativePlantOptions options)
    : lin_(std::move(lin)), options_(options) {}

Vector6d LinearizedPlant::acceleration(const BodyState& s, const ActuatorValues& a) const {
  const EulerAngles e = s.euler();
  Eigen::Matrix<double, 8, 1> x;
  x << s.nu, e.phi, e.theta;
  const Eigen::Vector3d c(a.delta_r, a.delta_s, a.rpm);
  return lin_.f0 + lin_.A * (x - lin_.x0) + lin_.B * (c - lin_.c0);
}

PlantResult LinearizedPlant::advance(const ActuatorValues& a, double dt) {
  return integrate(state_, dt, options_, [&](const BodyState& s) { return acceleration(s, a); });
}

void DerivativePlant::save(StateWriter& out) const {
  save_body_state(out, "derivative plant", state_);
}

void DerivativePlant::load(StateReader& in) {
  state_ = load_body_state(in, "derivative plant");
}

void LinearizedPlant::save(StateWriter& out) const {
  save_body_state(out, "linearized plant", state_);
}

void LinearizedPlant::load(StateReader& in) {
  state_ = load_body_state(in, "linearized plant");
}

}  // namespace auvloop::engine
