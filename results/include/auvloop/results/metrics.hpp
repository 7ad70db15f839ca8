// SPDX-License-Identifier: GPL-3.0-or-later
// Performance indices of a heading response, each defined precisely in docs/indices.md.
// Inputs are sampled signals in degrees and seconds; every integral is the trapezoidal rule over
// the samples, so the indices converge at second order as dt falls.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace auvloop::results {

struct StepSettings {
  double rise_low = 0.10;       // rise time from this fraction of the step ...
  double rise_high = 0.90;      // ... to this one
  double settling_band = 0.02;  // settled: |y - target| <= band * |step| from then on
};

struct StepMetrics {
  double step = 0;                      // target - initial value (deg)
  std::optional<double> rise_time;      // s; empty: never reached rise_high
  std::optional<double> settling_time;  // s; empty: outside the band at the end of the run
  double peak = 0;                      // deg: the extreme value in the direction of the step
  double peak_time = 0;                 // s
  double overshoot_percent = 0;         // max(0, (peak - target) / step) * 100
  double itae = 0;                      // integral of t |e| dt (deg s^2), the paper's unit
  double iae = 0;                       // integral of |e| dt (deg s)
  double ise = 0;                       // integral of e^2 dt (deg^2 s)
  double final_error = 0;               // e at the end (deg)
};

// Indices of the response y(t) (deg) to a step from y0 to target at t = 0; e(t) is the
// controller's error (deg), wrap-safe; pass the same samples for all three.
StepMetrics step_metrics(std::span<const double> t, std::span<const double> y,
                         std::span<const double> e, double y0, double target,
                         const StepSettings& settings = {});

struct ActuatorMetrics {
  double total_variation = 0;     // sum |delta_{k+1} - delta_k| (deg)
  double time_at_saturation = 0;  // s with |delta| at its limit
  double max_abs = 0;             // deg
};

ActuatorMetrics actuator_metrics(std::span<const double> t, std::span<const double> delta,
                                 double limit);

// A continuous heading from samples wrapped to (-180, 180]: removes the 360 deg jumps.
std::vector<double> unwrap_degrees(std::span<const double> wrapped);

}  // namespace auvloop::results
