// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/pid.hpp"

#include <cmath>

#include "auvloop/engine/rigid_body.hpp"

namespace auvloop::engine {

double heading_error(double psi_desired, double psi) {
  return std::atan2(std::sin(psi_desired - psi), std::cos(psi_desired - psi));
}

HeadingPid::HeadingPid(PidGains gains, PidOptions options) : gains_(gains), options_(options) {}

double HeadingPid::update(double psi_desired, double psi, double dt) {
  error_ = heading_error(psi_desired, psi);
  const double de = wrap_angle(error_ - previous_error_.value_or(error_));
  previous_error_ = error_;
  const double raw_derivative = gains_.kd * de / dt;
  const double tf = options_.derivative_filter;
  derivative_ = tf > 0 ? (tf * derivative_ + gains_.kd * de) / (tf + dt) : raw_derivative;

  const double candidate = integral_ + error_ * dt;
  const double output = gains_.kp * error_ + gains_.ki * candidate + derivative_;
  // Conditional integration: keep the new integral unless the output is already beyond the
  // actuator's reach in the direction the error pushes it.
  const bool winding = options_.anti_windup && std::abs(output) > options_.output_limit &&
                       std::signbit(output) == std::signbit(error_);
  if (!winding) integral_ = candidate;
  return gains_.kp * error_ + gains_.ki * integral_ + derivative_;
}

void HeadingPid::save(StateWriter& out) const {
  out.put(previous_error_.has_value());
  out.put(previous_error_.value_or(0.0));
  out.put(error_);
  out.put(integral_);
  out.put(derivative_);
}

void HeadingPid::load(StateReader& in) {
  const bool previous = in.get<bool>();
  const auto e = in.get<double>();
  previous_error_ = previous ? std::optional<double>(e) : std::nullopt;
  error_ = in.get<double>();
  integral_ = in.get<double>();
  derivative_ = in.get<double>();
}

}  // namespace auvloop::engine
