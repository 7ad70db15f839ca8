// SPDX-License-Identifier: GPL-3.0-or-later
// Speed control (closed_loop.hpp, SpeedControl; docs/case-file.md, [speed_control]):
//   - the command follows the stated discrete law step by step (hand-computed values), keeps the
//     inner manoeuvre's other commands, and stops integrating while the clamp holds it;
//   - in a case file: read and checked, defaults filled in, in the key only when present;
//   - on the derivative plant, the paper's heading step (0 -> 90 deg): at constant rpm the turn's
//     drag takes the speed from 1.544 to about 1.17 m/s; with the default speed control it stays
//     within 10 % of the desired speed throughout and ends within 2 %.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>

#include "auvloop/engine/case.hpp"
#include "auvloop/engine/closed_loop.hpp"

using namespace auvloop::engine;
using ::testing::HasSubstr;

namespace {
constexpr double kDeg = std::numbers::pi / 180;

std::string example(const std::string& name) {
  std::ifstream in(std::string(AUVLOOP_SOURCE_DIR) + "/examples/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Measurements surge(double u) {
  Measurements m;
  m.nu[0] = u;
  return m;
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_case(text, "case.toml", AUVLOOP_SOURCE_DIR);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(SpeedControl, FollowsItsDiscreteLawAndKeepsTheOtherCommands) {
  SpeedControl sc(
      std::make_unique<RudderRamp>(RudderRamp::Surface::rudder, 4 * kDeg, 10 * kDeg, 0.0, 1500.0),
      {.speed = 1.6, .kp = 1000, .ki = 500, .feed_forward = 1500, .max_rpm = 3000});
  const double dt = 0.1;
  // e = 0.1: I = 0.01, n = 1500 + 100 + 5.
  auto c = sc.command(0.2, surge(1.5), dt);
  EXPECT_NEAR(c.rpm, 1605.0, 1e-9);
  EXPECT_NEAR(sc.integral(), 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(c.delta_r, 2 * kDeg);  // the ramp's own command at t = 0.2 s
  // e = 0.05: I = 0.015, n = 1500 + 50 + 7.5.
  c = sc.command(0.3, surge(1.55), dt);
  EXPECT_NEAR(c.rpm, 1557.5, 1e-9);
  // e = -0.2: I = -0.005, n = 1500 - 200 - 2.5.
  c = sc.command(0.4, surge(1.8), dt);
  EXPECT_NEAR(c.rpm, 1297.5, 1e-9);
  EXPECT_NEAR(sc.integral(), -0.005, 1e-15);
}

TEST(SpeedControl, ASaturatedPropellerDoesNotWindTheIntegralUp) {
  SpeedControl sc(std::make_unique<RudderRamp>(RudderRamp::Surface::rudder, 0.0, 1.0, 0.0, 2900.0),
                  {.speed = 2.0, .kp = 1000, .ki = 500, .feed_forward = 2900, .max_rpm = 3000});
  for (int k = 0; k < 50; ++k) {  // e = 0.5: 2900 + 500 + ... is beyond 3000
    const auto c = sc.command(0.1 * k, surge(1.5), 0.1);
    EXPECT_DOUBLE_EQ(c.rpm, 3000.0);
  }
  EXPECT_EQ(sc.integral(), 0.0);
  // Faster than desired: below the clamp, it integrates again at once.
  const auto c = sc.command(5.0, surge(2.1), 0.1);
  EXPECT_NEAR(sc.integral(), -0.01, 1e-15);
  EXPECT_NEAR(c.rpm, 2900 - 100 - 5.0, 1e-9);
  // And the lower bound: never a negative command, and no wind-up below it.
  SpeedControl slow(std::make_unique<RudderRamp>(RudderRamp::Surface::rudder, 0.0, 1.0, 0.0, 100.0),
                    {.speed = 0.5, .kp = 1000, .ki = 500, .feed_forward = 100, .max_rpm = 3000});
  EXPECT_DOUBLE_EQ(slow.command(0, surge(1.5), 0.1).rpm, 0.0);
  EXPECT_EQ(slow.integral(), 0.0);
}

TEST(SpeedControl, CaseTableIsReadCheckedAndHashedOnlyWhenPresent) {
  const std::string base = example("heading-step.toml");
  const CaseSpec plain = parse_case(base, "a", AUVLOOP_SOURCE_DIR);
  EXPECT_FALSE(plain.speed_control);
  EXPECT_FALSE(canonical_json(plain).contains("speed_control"));
  const CaseSpec c = parse_case(base + "\n[speed_control]\n", "b", AUVLOOP_SOURCE_DIR);
  ASSERT_TRUE(c.speed_control);
  EXPECT_DOUBLE_EQ(c.speed_control->speed, c.initial_speed);
  EXPECT_DOUBLE_EQ(c.speed_control->kp, 2000.0);
  EXPECT_DOUBLE_EQ(c.speed_control->ki, 500.0);
  EXPECT_DOUBLE_EQ(c.speed_control->feed_forward, c.rpm);
  EXPECT_DOUBLE_EQ(c.speed_control->max_rpm, c.propeller.max);
  EXPECT_NE(canonical_json(plain).dump(), canonical_json(c).dump());
  const CaseSpec d = parse_case(base + "\n[speed_control]\nspeed = 1.7\nkp = 10\nki = 0\n", "d",
                                AUVLOOP_SOURCE_DIR);
  EXPECT_DOUBLE_EQ(d.speed_control->speed, 1.7);
  EXPECT_NE(canonical_json(c).dump(), canonical_json(d).dump());
  EXPECT_THAT(error_of(base + "\n[speed_control]\nkp = -1\n"), HasSubstr("speed_control.kp"));
  EXPECT_THAT(error_of(base + "\n[speed_control]\nspeed = 30\n"), HasSubstr("speed_control.speed"));
  EXPECT_THAT(error_of(base + "\n[speed_control]\ngain = 1\n"), HasSubstr("speed_control.gain"));
}

TEST(SpeedControl, HoldsTheSpeedThroughThePapersHeadingStep) {
  const std::string base = example("heading-step.toml");
  const auto min_and_last = [](const CaseRun& run) {
    const auto& u = run.loop.series["u"].values;
    return std::pair{*std::min_element(u.begin(), u.end()), u.back()};
  };
  const CaseSpec held = parse_case(base, "rpm", AUVLOOP_SOURCE_DIR);
  const auto [held_min, held_last] = min_and_last(run_case(held));
  const CaseSpec c = parse_case(base + "\n[speed_control]\n", "speed", AUVLOOP_SOURCE_DIR);
  const auto run = run_case(c);
  ASSERT_FALSE(run.loop.failure);
  const auto [min, last] = min_and_last(run);
  const double ud = c.speed_control->speed;
  EXPECT_LT(held_min, 0.8 * ud);  // the case the controller is for
  EXPECT_GT(min, 0.9 * ud);
  EXPECT_NEAR(last, ud, 0.02 * ud);
  EXPECT_LT(held_last, 0.95 * ud);
  const auto& rpm = run.loop.series["rpm"].values;
  EXPECT_GT(*std::max_element(rpm.begin(), rpm.end()), 1.2 * c.rpm);  // it pushed
}
