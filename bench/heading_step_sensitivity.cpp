// SPDX-License-Identifier: GPL-3.0-or-later
// How the paper's heading step (examples/heading-step.toml) depends on what the paper leaves
// unstated: rudder limit, rate limit and lag, anti-windup, speed, dt, sensors, and the model's
// documented options (Y_vv, fin coefficients, buoyancy). One choice changes at a time from the
// example's defaults. Prints a table beside the paper's Table 4 "linear model" row.
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "auvloop/engine/case.hpp"
#include "auvloop/geometry/input.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"

using namespace auvloop;
using engine::CaseSpec;
constexpr double kDeg = std::numbers::pi / 180;

namespace {
void row(const std::string& label, const CaseSpec& c) {
  const auto run = engine::run_case(c);
  if (run.loop.failure) {
    std::printf("%-34s diverged at t = %.2f s\n", label.c_str(), run.loop.final_time);
    return;
  }
  const auto m = results::manoeuvre_metrics(c, run.loop.series);
  auto num = [&](const char* k) {
    return m[k].is_null() ? std::string("  n/a") : std::to_string(m[k].get<double>()).substr(0, 6);
  };
  std::printf("%-34s %7s %11s %8.2f %9.2f %9.1f\n", label.c_str(), num("rise_time_s").c_str(),
              m["settled"].get<bool>() ? num("settling_time_s").c_str() : "not settled",
              m["peak_deg"].get<double>(), m["overshoot_percent"].get<double>(),
              m["itae_deg_s2"].get<double>());
}
}  // namespace

int main() {
  const CaseSpec base = engine::parse_case(
      input::read_file(std::string(AUVLOOP_SOURCE_DIR) + "/examples/heading-step.toml"),
      "heading-step.toml", AUVLOOP_SOURCE_DIR);
  std::printf("%-34s %7s %11s %8s %9s %9s\n", "variant (one change from defaults)", "t_r s",
              "t_s s", "peak", "sigma %", "ITAE");
  std::printf("%-34s %7s %11s %8s %9s %9s\n", "paper Table 4, linear model", "3.528", "12.688",
              "102.77", "14.18", "2733.6");
  std::printf("%-34s %7s %11s %8s %9s %9s\n", "paper Table 4, CFD", "1.312", "not settled",
              "110.86", "23.17", "12337.8");
  row("defaults (30 deg, 30 deg/s, 0.1 s)", base);
  const std::vector<std::pair<std::string, std::function<void(CaseSpec&)>>> variants{
      {"rudder limit 13.6 deg",
       [](CaseSpec& c) {
         c.rudder.max = 13.6 * kDeg;
         c.rudder.min = -c.rudder.max;
       }},
      {"rudder limit 20 deg",
       [](CaseSpec& c) {
         c.rudder.max = 20 * kDeg;
         c.rudder.min = -c.rudder.max;
       }},
      {"rudder limit 40 deg",
       [](CaseSpec& c) {
         c.rudder.max = 40 * kDeg;
         c.rudder.min = -c.rudder.max;
       }},
      {"rate limit 10 deg/s", [](CaseSpec& c) { c.rudder.max_rate = 10 * kDeg; }},
      {"rate limit 60 deg/s", [](CaseSpec& c) { c.rudder.max_rate = 60 * kDeg; }},
      {"rudder time constant 0 s", [](CaseSpec& c) { c.rudder.time_constant = 0; }},
      {"rudder time constant 0.3 s", [](CaseSpec& c) { c.rudder.time_constant = 0.3; }},
      {"anti-windup on",
       [](CaseSpec& c) {
         std::get<engine::HeadingStepSpec>(c.manoeuvre).options.anti_windup = true;
       }},
      {"1000 rpm (1.03 m/s)",
       [](CaseSpec& c) {
         c.rpm = 1000;
         c.initial_speed = 1.5436 * 1000 / 1500;
       }},
      {"dt 0.001 s", [](CaseSpec& c) { c.dt = 0.001; }},
      {"dt 0.05 s", [](CaseSpec& c) { c.dt = 0.05; }},
      {"ideal sensors", [](CaseSpec& c) { c.ideal_sensors = true; }},
      {"Y_vv = -131 (Table 4.2)", [](CaseSpec& c) { c.vehicle.hydrodynamics.Y_vv = -131; }},
      {"fin coefficients per fin (x2)",
       [](CaseSpec& c) { c.vehicle.hydrodynamics.fin_pair_factor = 2; }},
      {"buoyancy from the file (306 N)",
       [](CaseSpec& c) { c.buoyancy = engine::Buoyancy::vehicle; }},
      {"Y_vv -131 and anti-windup",
       [](CaseSpec& c) {
         c.vehicle.hydrodynamics.Y_vv = -131;
         std::get<engine::HeadingStepSpec>(c.manoeuvre).options.anti_windup = true;
       }},
  };
  for (const auto& [label, change] : variants) {
    CaseSpec c = base;
    change(c);
    row(label, c);
  }
}
