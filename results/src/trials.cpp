// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant's closed-loop validation cases (trials.hpp):
//   1. the case: the embedded file below (the examples' settings: coarse, the [cfd] defaults,
//      horizontal plane for the yaw trial and the circle, six degrees of freedom for the pitch
//      trial), its mesh, straight run, duration and report time set per version;
//   2. the run: run_case (the straight run computed afresh), the indices: manoeuvre_metrics;
//   3. quick: the same case on the derivative plant, and the CFD figure over the derivative
//      figure, within a factor of two either way (a sign error or a response off by more than
//      that fails; the CFD loop is expected to respond faster than the model, as in the paper);
//      full: coarse, then medium,
//      whose figure is held against the sea trial; the paper's CFD figure and the derivative
//      plant's are reported beside it.
#include "auvloop/results/trials.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <variant>

#include <fmt/format.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"

namespace auvloop::results {

namespace {

using engine::validation::Case;
using engine::validation::Result;
using engine::validation::Row;

constexpr const char* kYawTrial = R"(name = "remus-yaw-trial"
vehicle = "preset:remus100"
plant = "cfd"
[cfd]
dof = "horizontal"
[time]
dt = 0.01
duration = 6
[initial]
speed = 1.54
rpm = 1500
[manoeuvre]
type = "rudder-ramp"
surface = "rudder"
angle = 4
rate = 10
report_time = 5
[actuators.rudder]
time_constant = 0
)";

constexpr const char* kPitchTrial = R"(name = "remus-pitch-trial"
vehicle = "preset:remus100"
plant = "cfd"
[cfd]
dof = "6dof"
[time]
dt = 0.01
duration = 3
[initial]
speed = 1.54
rpm = 1500
[manoeuvre]
type = "rudder-ramp"
surface = "stern-plane"
angle = 4
rate = 10
report_time = 2
[actuators.stern_plane]
time_constant = 0
)";

constexpr const char* kTurningCircle = R"(name = "remus-turning-circle"
vehicle = "preset:remus100"
plant = "cfd"
[cfd]
dof = "horizontal"
[time]
dt = 0.01
duration = 30
[initial]
speed = 1.03
rpm = 1001
[manoeuvre]
type = "turning-circle"
rudder = 13.6
[actuators.rudder]
limit = 13.6
)";

struct Trial {
  const char* name;
  const char* text;
  const char* metric;        // in manoeuvre_metrics, "steady." for its steady-turn part
  const char* what;          // for the rows
  double sea = 0;            // the sea trial's figure
  double paper = 0;          // the paper's CFD figure
  double tolerance = 0;      // relative, the issue's acceptance
  const char* quick_metric;  // the first second's figure (the report time set to 1 s)
  const char* quick_what;
};

double figure(const nlohmann::json& metrics, const std::string& path) {
  const nlohmann::json* at = &metrics;
  std::size_t from = 0;
  while (true) {
    const auto dot = path.find('.', from);
    const std::string key = path.substr(from, dot == std::string::npos ? dot : dot - from);
    if (!at->contains(key) || (*at)[key].is_null()) return std::nan("");
    at = &(*at)[key];
    if (dot == std::string::npos) break;
    from = dot + 1;
  }
  return at->get<double>();
}

// Runs `c` and reads `metric`; a failed run's reason goes to the notes (its figure, if any, is
// of the steps before the failure).
double run(const engine::CaseSpec& c, const std::string& metric, Result& res) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = engine::run_case(c);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double value = figure(manoeuvre_metrics(c, r.loop.series), metric);
  res.notes.push_back(fmt::format("{} plant{}: {} {:.4g} ({:.0f} s){}", engine::to_string(c.plant),
                                  c.plant == engine::PlantKind::cfd ? ", " + c.cfd.mesh : "",
                                  metric, value, seconds,
                                  r.loop.failure ? "; failed: " + *r.loop.failure : ""));
  return r.loop.failure ? std::nan("") : value;
}

Result run_trial(const Trial& t, bool quick) {
  Result res{t.name, {}, {}};
  engine::CaseSpec c = engine::parse_case(t.text, t.name, std::filesystem::path{});  // 1.
  if (quick) {
    c.cfd.spin_up = 0.2;
    c.duration = 1;
    if (auto* ramp = std::get_if<engine::RudderRampSpec>(&c.manoeuvre)) ramp->report_time = 1;
    const double cfd = run(c, t.quick_metric, res);  // 2.
    auto derivative = c;
    derivative.plant = engine::PlantKind::derivative;
    const double reference = run(derivative, t.quick_metric, res);  // 3.
    // Within a factor of two either way: |log2(ratio)| <= 1 (a ratio of the other sign is NaN).
    const double ratio = cfd / reference;
    Row row{fmt::format("{}, CFD / derivative", t.quick_what),
            ratio,
            1.0,
            std::abs(std::log2(ratio)),
            1.0,
            false};
    row.pass = row.error <= row.tolerance;  // NaN fails
    res.rows.push_back(row);
    return res;
  }
  auto derivative = c;
  derivative.plant = engine::PlantKind::derivative;
  const double model = run(derivative, t.metric, res);
  double medium = std::nan("");
  for (const char* mesh : {"coarse", "medium"}) {
    c.cfd.mesh = mesh;
    const double value = run(c, t.metric, res);
    if (std::string(mesh) == "medium") medium = value;
  }
  res.notes.push_back(
      fmt::format("{}: sea trial {:g}, the paper's CFD {:g}, the derivative plant "
                  "{:.4g}",
                  t.what, t.sea, t.paper, model));
  Row row{fmt::format("{}, medium / sea trial", t.what),
          medium,
          t.sea,
          std::abs(medium / t.sea - 1),
          t.tolerance,
          false};
  row.pass = row.error <= row.tolerance;  // NaN fails
  res.rows.push_back(row);
  return res;
}

const Trial kTrials[] = {
    {"remus-yaw-trial", kYawTrial, "heading_change_deg", "heading change at 5 s (deg)", 51.9, 52.4,
     0.10, "heading_change_deg", "heading change at 1 s (deg)"},
    {"remus-pitch-trial", kPitchTrial, "pitch_change_deg", "pitch change at 2 s (deg)", 17.2, 17.9,
     0.10, "pitch_change_deg", "pitch change at 1 s (deg)"},
    {"remus-turning-circle", kTurningCircle, "steady.radius_m", "steady turning radius (m)", 4.0,
     4.12, 0.15, "steady.yaw_rate_deg_s", "yaw rate over 0.8-1 s (deg/s)"},
};

}  // namespace

std::vector<Case> trial_cases() {
  std::vector<Case> all;
  for (const Trial& t : kTrials) {
    all.push_back({t.name,
                   fmt::format("the CFD plant's {} against the sea trial's {:g} (the paper's CFD "
                               "{:g}), on medium",
                               t.what, t.sea, t.paper),
                   [&t](bool quick) { return run_trial(t, quick); }});
  }
  return all;
}

}  // namespace auvloop::results
