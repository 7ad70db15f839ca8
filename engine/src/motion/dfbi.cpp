// SPDX-License-Identifier: GPL-3.0-or-later
// The DFBI coupling's steps 1-4 (engine/dfbi.hpp states them).
#include "auvloop/engine/dfbi.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/Cholesky>

namespace auvloop::engine {

namespace {
// exp of a rotation vector as a unit quaternion.
Eigen::Quaterniond rotation(const Eigen::Vector3d& angle) {
  const double a = angle.norm();
  if (a == 0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(a, angle / a));
}
}  // namespace

Dfbi::Dfbi(DfbiBody body) : body_(std::move(body)) {
  validate();
}

void Dfbi::set_free(const std::array<bool, 6>& free) {
  const auto before = body_.free;
  body_.free = free;
  try {
    validate();
  } catch (...) {
    body_.free = before;
    throw;
  }
}

void Dfbi::validate() const {
  if (!(body_.relax > 0 && body_.relax <= 1))
    throw std::invalid_argument(fmt::format(
        "DFBI: the relaxation of the acceleration must be in (0, 1], got {}", body_.relax));
  const Matrix6d M = body_.mass + body_.added_mass;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (std::abs(M(i, j) - M(j, i)) > 1e-12 * (std::abs(M(i, j)) + std::abs(M(j, i)) + 1e-300))
        throw std::invalid_argument(fmt::format(
            "DFBI: the mass matrix (rigid body and added mass) is not symmetric at ({}, {}): {} "
            "against {}",
            i, j, M(i, j), M(j, i)));
  Eigen::MatrixXd free_part(0, 0);
  int n = 0;
  for (bool f : body_.free) n += f ? 1 : 0;
  free_part.resize(n, n);
  for (int i = 0, fi = 0; i < 6; ++i) {
    if (!body_.free[static_cast<std::size_t>(i)]) continue;
    for (int j = 0, fj = 0; j < 6; ++j) {
      if (!body_.free[static_cast<std::size_t>(j)]) continue;
      free_part(fi, fj++) = M(i, j);
    }
    ++fi;
  }
  if (n > 0 && Eigen::LLT<Eigen::MatrixXd>(free_part).info() != Eigen::Success)
    throw std::invalid_argument(
        "DFBI: the mass matrix (rigid body and added mass) is not positive definite on the free "
        "degrees of freedom");
}

void Dfbi::reset(const BodyState& state) {
  history_.state = state;
  history_.nu_old = state.nu;
  history_.acceleration.setZero();
  iterate_ = state;
  a_.setZero();
  change_ = 0;
}

void Dfbi::restore(const DfbiHistory& h) {
  history_ = h;
  iterate_ = h.state;
  a_ = h.acceleration;
  change_ = 0;
}

void Dfbi::advance_iterate() {
  // 3.
  const auto& s = history_.state;
  iterate_.nu = second_order_ ? Vector6d((4 * s.nu - history_.nu_old + 2 * dt_ * a_) / 3)
                              : Vector6d(s.nu + dt_ * a_);
  const Eigen::Vector3d omega = 0.5 * (s.nu.tail<3>() + iterate_.nu.tail<3>());
  const Eigen::Vector3d v = 0.5 * (s.nu.head<3>() + iterate_.nu.head<3>());
  iterate_.attitude = (s.attitude * rotation(dt_ * omega)).normalized();
  iterate_.position = s.position + dt_ * ((s.attitude * rotation(0.5 * dt_ * omega)) * v);
}

const BodyState& Dfbi::begin_step(double dt, bool second_order) {
  if (!(dt > 0 && std::isfinite(dt)))
    throw std::invalid_argument(fmt::format("DFBI: time step must be positive, got {}", dt));
  dt_ = dt;
  second_order_ = second_order;
  a_ = history_.acceleration;  // 1.
  change_ = 0;
  advance_iterate();
  return iterate_;
}

const BodyState& Dfbi::correct(const Vector6d& tau_flow) {
  // 2.
  const Vector6d tau =
      tau_flow +
      gravity_and_buoyancy(body_.weight, body_.buoyancy, body_.r_g, body_.r_b, iterate_.attitude) -
      coriolis(body_.mass, iterate_.nu) + body_.added_mass * a_;
  const Matrix6d M = body_.mass + body_.added_mass;
  int n = 0;
  std::array<int, 6> index{};
  for (int i = 0; i < 6; ++i)
    if (body_.free[static_cast<std::size_t>(i)]) index[static_cast<std::size_t>(n++)] = i;
  Eigen::MatrixXd A(n, n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    b[i] = tau[index[static_cast<std::size_t>(i)]];
    for (int j = 0; j < n; ++j)
      A(i, j) = M(index[static_cast<std::size_t>(i)], index[static_cast<std::size_t>(j)]);
  }
  const Eigen::VectorXd x = A.llt().solve(b);
  Vector6d a = Vector6d::Zero();
  for (int i = 0; i < n; ++i) a[index[static_cast<std::size_t>(i)]] = x[i];
  const Vector6d next = a_ + body_.relax * (a - a_);
  change_ = (next - a_).norm();
  a_ = next;
  advance_iterate();
  return iterate_;
}

void Dfbi::accept() {
  // 4.
  history_.nu_old = history_.state.nu;
  history_.state = iterate_;
  history_.acceleration = a_;
}

}  // namespace auvloop::engine
