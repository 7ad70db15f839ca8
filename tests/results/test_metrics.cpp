// SPDX-License-Identifier: GPL-3.0-or-later
// Indices against closed forms: a first-order response (ITAE, IAE, ISE in closed form) and an
// underdamped second-order one (overshoot exp(-pi z / sqrt(1 - z^2)), peak time pi / w_d; rise and
// settling times by bisection on the analytic response, independent of the sampled data).
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "auvloop/results/metrics.hpp"

using namespace auvloop::results;
constexpr double kPi = std::numbers::pi;

namespace {
struct Sampled {
  std::vector<double> t, y, e;
};
Sampled sample(const std::function<double(double)>& y, double T, double dt, double scale) {
  Sampled s;
  for (int k = 0; k <= static_cast<int>(std::lround(T / dt)); ++k) {
    const double t = k * dt;
    s.t.push_back(t);
    s.y.push_back(scale * y(t));
    s.e.push_back(scale * (1 - y(t)));
  }
  return s;
}
double bisect(const std::function<double(double)>& f, double a, double b) {
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    ((f(a) < 0) == (f(m) < 0) ? a : b) = m;
  }
  return 0.5 * (a + b);
}
}  // namespace

TEST(Metrics, FirstOrderIntegralsMatchClosedForms) {
  const double T = 2.0, tau = 20.0;
  const auto s = sample([&](double t) { return 1 - std::exp(-t / T); }, tau, 1e-3, 90.0);
  const StepMetrics m = step_metrics(s.t, s.y, s.e, 0.0, 90.0);
  const double x = tau / T;
  EXPECT_NEAR(m.itae / (90 * T * T * (1 - std::exp(-x) * (1 + x))), 1.0, 1e-6);
  EXPECT_NEAR(m.iae / (90 * T * (1 - std::exp(-x))), 1.0, 1e-6);
  EXPECT_NEAR(m.ise / (90 * 90 * T / 2 * (1 - std::exp(-2 * x))), 1.0, 1e-6);
  EXPECT_NEAR(*m.rise_time, T * std::log(9.0), 1e-6);           // 10 % to 90 %
  EXPECT_NEAR(*m.settling_time, T * std::log(1 / 0.02), 1e-6);  // 2 % band
  EXPECT_EQ(m.overshoot_percent, 0.0);
}

TEST(Metrics, SecondOrderStepMatchesTheAnalyticResponse) {
  const double z = 0.3, w = 1.2, wd = w * std::sqrt(1 - z * z);
  const std::function<double(double)> y = [&](double t) {
    return 1 -
           std::exp(-z * w * t) * (std::cos(wd * t) + z / std::sqrt(1 - z * z) * std::sin(wd * t));
  };
  const auto s = sample(y, 30.0, 1e-3, 90.0);
  const StepMetrics m = step_metrics(s.t, s.y, s.e, 0.0, 90.0);
  EXPECT_NEAR(m.overshoot_percent, 100 * std::exp(-kPi * z / std::sqrt(1 - z * z)), 1e-4);
  EXPECT_NEAR(m.peak_time, kPi / wd, 1e-3);  // within a sample
  const double t10 = bisect([&](double t) { return y(t) - 0.1; }, 0, kPi / wd);
  const double t90 = bisect([&](double t) { return y(t) - 0.9; }, 0, kPi / wd);
  EXPECT_NEAR(*m.rise_time, t90 - t10, 1e-5);
  // Settling: the last time |y - 1| = 0.02, searched backwards over half periods.
  double ts = 0;
  for (double t = 30.0; t > 0; t -= 0.01) {
    if (std::abs(y(t) - 1) > 0.02) {
      ts = bisect([&](double u) { return std::abs(y(u) - 1) - 0.02; }, t, t + 0.01);
      break;
    }
  }
  EXPECT_NEAR(*m.settling_time, ts, 1e-5);
  // ITAE by a much finer composite Simpson rule on the analytic error.
  double itae = 0;
  const int n = 300000;
  const double h = 30.0 / n;
  for (int i = 0; i <= n; ++i) {
    const double t = i * h, f = t * std::abs(1 - y(t));
    itae += (i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2)) * f;
  }
  itae *= 90 * h / 3;
  EXPECT_NEAR(m.itae / itae, 1.0, 1e-5);
}

TEST(Metrics, NegativeStepsAndNeverSettling) {
  const auto s = sample([](double t) { return 1 - std::cos(t); }, 20.0, 1e-2, -45.0);  // undamped
  const StepMetrics m = step_metrics(s.t, s.y, s.e, 0.0, -45.0);
  EXPECT_FALSE(m.settling_time.has_value());
  EXPECT_NEAR(m.peak, -90.0, 1e-2);  // the extreme in the direction of the step
  EXPECT_NEAR(m.overshoot_percent, 100.0, 1e-2);
  const auto flat = sample([](double) { return 0.0; }, 5.0, 1e-2, 10.0);
  EXPECT_FALSE(step_metrics(flat.t, flat.y, flat.e, 0.0, 10.0).rise_time.has_value());
}

TEST(Metrics, ActuatorActivity) {
  const std::vector<double> t{0, 1, 2, 3, 4}, d{0, 30, 30, -30, -10};
  const ActuatorMetrics a = actuator_metrics(t, d, 30.0);
  EXPECT_DOUBLE_EQ(a.total_variation, 30 + 0 + 60 + 20);
  EXPECT_DOUBLE_EQ(a.time_at_saturation, 2.0);  // [1, 2] at +30 and [2, 3] from +30 to -30
  EXPECT_DOUBLE_EQ(a.max_abs, 30.0);
}

TEST(Metrics, UnwrapRemovesTheJumpsAt180) {
  const std::vector<double> wrapped{170, 179, -179, -170, 175, 160};
  const auto u = unwrap_degrees(wrapped);
  EXPECT_EQ(u, (std::vector<double>{170, 179, 181, 190, 175, 160}));
}
