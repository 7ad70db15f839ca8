// SPDX-License-Identifier: GPL-3.0-or-later
// Discrete PID heading controller of the paper (section 4.2), forward Euler:
//   u_k = Kp e_k + Ki sum_{j=0..k} e_j dt + Kd (e_k - e_{k-1}) / dt,
//   e_k = atan2(sin(psi_d - psi), cos(psi_d - psi))   (wrap-safe: the short way round),
// with e_{-1} = e_0 so that the first step has no derivative kick. The derivative uses the wrapped
// difference of successive errors, so an error crossing +-180 deg gives no spike.
// Options, off by default to match the paper: conditional-integration anti-windup (the integral
// stops growing while the output is beyond output_limit in the direction of the error) and a
// first-order filter on the derivative term (time constant derivative_filter).
// The output u (rad) is the turn command: u > 0 asks to turn to starboard (increase psi).
#pragma once

#include <limits>
#include <optional>

#include "auvloop/engine/state_archive.hpp"

namespace auvloop::engine {

struct PidGains {
  double kp = 0;  // rad of command per rad of error
  double ki = 0;  // 1/s
  double kd = 0;  // s
};

struct PidOptions {
  bool anti_windup = false;
  double output_limit = std::numeric_limits<double>::infinity();  // rad, for anti-windup
  double derivative_filter = 0;                                   // s; 0: no filter
};

double heading_error(double psi_desired, double psi);  // rad, in (-pi, pi]

class HeadingPid {
 public:
  HeadingPid(PidGains gains, PidOptions options = {});
  double update(double psi_desired, double psi, double dt);
  [[nodiscard]] double error() const { return error_; }
  [[nodiscard]] double integral() const { return integral_; }
  // Exact checkpoint of the state (not the gains).
  void save(StateWriter& out) const;
  void load(StateReader& in);

 private:
  PidGains gains_;
  PidOptions options_;
  std::optional<double> previous_error_;
  double error_ = 0, integral_ = 0, derivative_ = 0;
};

}  // namespace auvloop::engine
