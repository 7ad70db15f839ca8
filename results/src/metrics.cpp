// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/results/metrics.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace auvloop::results {
namespace {

// Time at which the normalised response x crosses `level` between samples i-1 and i (linear).
double crossing(std::span<const double> t, const std::vector<double>& x, std::size_t i,
                double level) {
  const double w = (level - x[i - 1]) / (x[i] - x[i - 1]);
  return t[i - 1] + w * (t[i] - t[i - 1]);
}

std::optional<double> first_reach(std::span<const double> t, const std::vector<double>& x,
                                  double level) {
  if (x[0] >= level) return t[0];
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (x[i] >= level) return crossing(t, x, i, level);
  }
  return std::nullopt;
}

// Trapezoidal integral of f(t_k, e_k).
template <class F>
double trapezoid(std::span<const double> t, std::span<const double> e, F&& f) {
  double sum = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    sum += 0.5 * (t[i] - t[i - 1]) * (f(t[i - 1], e[i - 1]) + f(t[i], e[i]));
  }
  return sum;
}

}  // namespace

StepMetrics step_metrics(std::span<const double> t, std::span<const double> y,
                         std::span<const double> e, double y0, double target,
                         const StepSettings& s) {
  if (t.size() < 2 || y.size() != t.size() || e.size() != t.size()) {
    throw std::invalid_argument("step_metrics: need at least two samples of t, y and e alike");
  }
  StepMetrics m;
  m.step = target - y0;
  if (m.step == 0) throw std::invalid_argument("step_metrics: the step is zero");
  // Normalised response: 0 at the start, 1 at the target, whatever the step's sign.
  std::vector<double> x(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) x[i] = (y[i] - y0) / m.step;

  const auto lo = first_reach(t, x, s.rise_low), hi = first_reach(t, x, s.rise_high);
  if (lo && hi) m.rise_time = *hi - *lo;

  std::size_t ipeak = 0;
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (x[i] > x[ipeak]) ipeak = i;
  }
  m.peak = y[ipeak];
  m.peak_time = t[ipeak];
  m.overshoot_percent = std::max(0.0, x[ipeak] - 1) * 100;

  // Settling: the last time the response enters the band for good.
  const auto outside = [&](std::size_t i) { return std::abs(x[i] - 1) > s.settling_band; };
  if (!outside(x.size() - 1)) {
    std::size_t i = x.size() - 1;
    while (i > 0 && !outside(i - 1)) --i;
    if (i == 0) {
      m.settling_time = t[0];
    } else {
      const double edge = x[i - 1] > 1 ? 1 + s.settling_band : 1 - s.settling_band;
      m.settling_time = crossing(t, x, i, edge);
    }
  }
  m.itae = trapezoid(t, e, [](double tk, double ek) { return tk * std::abs(ek); });
  m.iae = trapezoid(t, e, [](double, double ek) { return std::abs(ek); });
  m.ise = trapezoid(t, e, [](double, double ek) { return ek * ek; });
  m.final_error = e.back();
  return m;
}

ActuatorMetrics actuator_metrics(std::span<const double> t, std::span<const double> delta,
                                 double limit) {
  ActuatorMetrics a;
  const double tol = 1e-9 * std::max(1.0, limit);
  for (std::size_t i = 0; i < delta.size(); ++i) {
    a.max_abs = std::max(a.max_abs, std::abs(delta[i]));
    if (i == 0) continue;
    a.total_variation += std::abs(delta[i] - delta[i - 1]);
    // A step counts as saturated when the actuator sits at its limit at both ends.
    if (std::abs(delta[i]) >= limit - tol && std::abs(delta[i - 1]) >= limit - tol) {
      a.time_at_saturation += t[i] - t[i - 1];
    }
  }
  return a;
}

std::vector<double> unwrap_degrees(std::span<const double> wrapped) {
  std::vector<double> out(wrapped.begin(), wrapped.end());
  double offset = 0;
  for (std::size_t i = 1; i < out.size(); ++i) {
    const double jump = wrapped[i] - wrapped[i - 1];
    if (jump > 180) offset -= 360;
    if (jump < -180) offset += 360;
    out[i] = wrapped[i] + offset;
  }
  return out;
}

}  // namespace auvloop::results
