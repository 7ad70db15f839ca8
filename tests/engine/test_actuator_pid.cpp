// SPDX-License-Identifier: GPL-3.0-or-later
// Actuators against the analytic first-order step response and their limits; the PID's discrete law
// and its wrap-safe error.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "auvloop/engine/actuator.hpp"
#include "auvloop/engine/pid.hpp"

using namespace auvloop::engine;
constexpr double kDeg = std::numbers::pi / 180;

TEST(Actuator, MatchesTheAnalyticStepResponseForAnyStep) {
  for (double dt : {0.001, 0.01, 0.3}) {
    FirstOrderActuator a({.time_constant = 0.5}, 0.0);
    for (int k = 1; k <= static_cast<int>(2.0 / dt); ++k) {
      a.step(1.0, dt);
      EXPECT_NEAR(a.value(), 1 - std::exp(-k * dt / 0.5), 1e-14) << "dt " << dt << " step " << k;
    }
  }
}

TEST(Actuator, AmplitudeLimitHolds) {
  FirstOrderActuator a({.time_constant = 0.1, .min = -30, .max = 30}, 0.0);
  for (int k = 0; k < 200; ++k) {
    a.step(k < 100 ? 100.0 : -100.0, 0.01);
    EXPECT_LE(std::abs(a.value()), 30.0);
  }
  EXPECT_EQ(a.value(), -30.0);
  EXPECT_TRUE(a.limited());
}

TEST(Actuator, RateLimitHolds) {
  FirstOrderActuator a({.time_constant = 0.0, .max_rate = 10.0}, 0.0);
  double previous = 0;
  for (int k = 1; k <= 40; ++k) {
    a.step(30.0, 0.1);
    EXPECT_LE(a.value() - previous, 10.0 * 0.1 + 1e-12);
    EXPECT_NEAR(a.value(), std::min(30.0, k * 1.0), 1e-12);
    previous = a.value();
  }
}

TEST(Pid, ErrorTakesTheShortWayAcrossTheWrap) {
  EXPECT_NEAR(heading_error(170 * kDeg, -170 * kDeg), -20 * kDeg, 1e-12);
  EXPECT_NEAR(heading_error(-170 * kDeg, 170 * kDeg), 20 * kDeg, 1e-12);
  EXPECT_NEAR(heading_error(90 * kDeg, 0.0), 90 * kDeg, 1e-12);
  EXPECT_NEAR(heading_error(0.0, 2.5 * std::numbers::pi), -std::numbers::pi / 2, 1e-12);
}

TEST(Pid, FollowsThePapersDiscreteLaw) {
  // u_k = Kp e_k + Ki sum_{j<=k} e_j dt + Kd (e_k - e_{k-1}) / dt with e_{-1} = e_0.
  HeadingPid pid({1.5, 0.6, 1.0});
  const double dt = 0.1;
  const double psi[] = {0.0, 0.1, 0.25, 0.4};
  const double target = 1.0;
  double sum = 0, previous = target - psi[0];
  for (double p : psi) {
    const double e = target - p;
    sum += e * dt;
    const double expected = 1.5 * e + 0.6 * sum + 1.0 * (e - previous) / dt;
    EXPECT_NEAR(pid.update(target, p, dt), expected, 1e-12);
    previous = e;
  }
}

TEST(Pid, NoDerivativeSpikeWhenTheErrorWraps) {
  HeadingPid pid({0.0, 0.0, 1.0});
  pid.update(0.0, 179 * kDeg, 0.1);                    // e = -179 deg
  const double u = pid.update(0.0, -179 * kDeg, 0.1);  // e = +179 deg: 2 deg later, not 358
  EXPECT_NEAR(u, -2 * kDeg / 0.1, 1e-9);
}

TEST(Pid, AntiWindupStopsTheIntegralWhileSaturated) {
  HeadingPid plain({1.0, 1.0, 0.0});
  HeadingPid guarded({1.0, 1.0, 0.0}, {.anti_windup = true, .output_limit = 0.5});
  for (int k = 0; k < 100; ++k) {
    plain.update(1.0, 0.0, 0.1);
    guarded.update(1.0, 0.0, 0.1);
  }
  EXPECT_NEAR(plain.integral(), 10.0, 1e-9);
  EXPECT_EQ(guarded.integral(), 0.0);  // kp e alone already exceeds the limit
}
