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
#include <optional>
#include <string>
#include <variant>

#include <fmt/format.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"
#include "auvloop/results/metrics.hpp"

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

// The paper's heading step (section 4.3, Table 4), as examples/cfd-heading-step.toml runs it.
constexpr const char* kHeadingStep = R"(name = "remus-heading-step"
vehicle = "preset:remus100"
plant = "cfd"
[cfd]
dof = "horizontal"
[time]
dt = 0.01
duration = 30
[initial]
speed = 1.54
rpm = 1500
[manoeuvre]
type = "heading-step"
target_heading = 90
[controller]
kp = 1.5
ki = 0.6
kd = 1.0
[actuators.rudder]
time_constant = 0.1
limit = 30
rate_limit = 30
[actuators.propeller]
time_constant = 0.5
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

// One run of a case: its indices (manoeuvre_metrics, of the steps before a failure), its series'
// heading change at `at` s (deg; NaN beyond its end), its wall time (s) and the plant's failure.
struct Outcome {
  nlohmann::json metrics;
  double heading_change = std::nan("");
  double seconds = 0;
  std::optional<std::string> failure;
  // "cfd plant, coarse, dt 0.01 s (812 s)", and "; failed: ..." after a failure.
  std::string label(const engine::CaseSpec& c) const {
    return fmt::format("{} plant{}, dt {:g} s ({:.0f} s){}", engine::to_string(c.plant),
                       c.plant == engine::PlantKind::cfd ? ", " + c.cfd.mesh : "", c.dt, seconds,
                       failure ? "; failed: " + *failure : "");
  }
};
Outcome run_outcome(const engine::CaseSpec& c, double at) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = engine::run_case(c);
  Outcome out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.failure = r.loop.failure;
  const auto& s = r.loop.series;
  out.metrics = manoeuvre_metrics(c, s);
  const auto& t = s["t"].values;
  const std::vector<double> psi = unwrap_degrees(s["psi_true"].values);  // deg
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    if (t[i + 1] < at - 1e-9) continue;
    const double w = (at - t[i]) / (t[i + 1] - t[i]);
    out.heading_change = psi[i] + w * (psi[i + 1] - psi[i]) - psi.front();
    break;
  }
  return out;
}

// Runs `c` and reads `metric`; a failed run's reason goes to the notes (its figure, if any, is
// of the steps before the failure) and its figure is NaN.
double run(const engine::CaseSpec& c, const std::string& metric, Result& res) {
  const auto o = run_outcome(c, c.duration);
  const double value = figure(o.metrics, metric);
  res.notes.push_back(fmt::format("{}: {} {:.4g}", o.label(c), metric, value));
  return o.failure ? std::nan("") : value;
}

// Runs the heading step `c`: its indices in the notes, and returned (null after a failure).
nlohmann::json run_heading_indices(const engine::CaseSpec& c, Result& res) {
  const auto o = run_outcome(c, c.duration);
  const auto& m = o.metrics;
  res.notes.push_back(fmt::format(
      "{}: rise time {:.3f} s, peak {:.2f} deg at {:.2f} s, overshoot {:.2f} %, settling {}, "
      "ITAE {:.1f} deg s^2",
      o.label(c), figure(m, "rise_time_s"), figure(m, "peak_deg"), figure(m, "peak_time_s"),
      figure(m, "overshoot_percent"),
      m.value("settled", false) ? fmt::format("{:.2f} s", figure(m, "settling_time_s"))
                                : std::string("not settled"),
      figure(m, "itae_deg_s2")));
  return o.failure ? nlohmann::json() : m;
}

// remus-heading-step (issue 18 items 8 and 9). Quick (CI): coarse, 0.2 s straight, the first
// second: the heading change at 1 s over the derivative plant's, within a factor of four either
// way (the response's sign and size). Not the trials' factor of two: the paper's own CFD loop
// rises 2.69 times as fast as its linear model here (1.312 s against 3.528 s), and the rudder,
// rate-limited to 30 deg/s, sweeps to 30 deg in that second, far beyond the trials' 4 deg. Full:
// the derivative plant, then the CFD plant on coarse and medium at 10 ms and on coarse at 5 and 20
// ms: every run's indices beside the paper's Table 4 (CFD in the loop: rise 1.312 s, peak 110.86
// deg, overshoot 23.17 %, ITAE 12,337.82; linear model: 3.528 s, 102.77 deg, 14.18 %, 2,733.55),
// and the grid and time-step study's criteria (the issue's acceptance): ITAE and overshoot within 5
// % between coarse and medium and within 3 % between 10 and 5 ms.
Result run_heading_step(bool quick) {
  Result res{"remus-heading-step", {}, {}};
  engine::CaseSpec c = engine::parse_case(kHeadingStep, res.name, std::filesystem::path{});
  auto derivative = c;
  derivative.plant = engine::PlantKind::derivative;
  if (quick) {
    c.cfd.spin_up = 0.2;
    c.duration = derivative.duration = 1;
    double change[2];  // deg at 1 s: CFD, derivative
    for (const auto* run : {&c, &derivative}) {
      const auto o = run_outcome(*run, 1);
      res.notes.push_back(
          fmt::format("{}: heading change at 1 s {:.2f} deg", o.label(*run), o.heading_change));
      change[run == &c ? 0 : 1] = o.failure ? std::nan("") : o.heading_change;
    }
    const double ratio = change[0] / change[1];
    Row row{"heading change at 1 s (deg), CFD / derivative",
            ratio,
            1.0,
            std::abs(std::log2(ratio)),
            2.0,
            false};
    row.pass = row.error <= row.tolerance;  // NaN fails
    res.rows.push_back(row);
    return res;
  }
  run_heading_indices(derivative, res);
  struct Variant {
    const char* mesh;
    double dt;
  };
  std::vector<nlohmann::json> m;
  for (const Variant v : {Variant{"coarse", 0.01}, Variant{"medium", 0.01},
                          Variant{"coarse", 0.005}, Variant{"coarse", 0.02}}) {
    c.cfd.mesh = v.mesh;
    c.dt = v.dt;
    m.push_back(run_heading_indices(c, res));
  }
  res.notes.push_back(
      "the paper's Table 4: CFD in the loop rise 1.312 s, peak 110.86 deg, overshoot 23.17 %, "
      "not settled, ITAE 12,337.82; linear model 3.528 s, 102.77 deg, 14.18 %, settled at "
      "12.688 s, ITAE 2,733.55");
  const auto compare = [&](const nlohmann::json& a, const nlohmann::json& b, const char* what,
                           double tolerance) {
    for (const char* index : {"itae_deg_s2", "overshoot_percent"}) {
      const double x = a.is_null() ? std::nan("") : figure(a, index);
      const double y = b.is_null() ? std::nan("") : figure(b, index);
      res.rows.push_back(engine::validation::Row{fmt::format("{}, {}", index, what), x, y,
                                                 std::abs(x / y - 1), tolerance,
                                                 std::abs(x / y - 1) <= tolerance});
    }
  };
  compare(m[0], m[1], "coarse / medium at 10 ms", 0.05);
  compare(m[0], m[2], "10 ms / 5 ms on coarse", 0.03);
  return res;
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
  all.push_back({"remus-heading-step",
                 "the paper's PID heading step 0 -> 90 deg on the CFD plant: its indices beside "
                 "the paper's Table 4 and the derivative plant's, and the grid (coarse, medium) "
                 "and time-step (20, 10, 5 ms) study",
                 run_heading_step});
  return all;
}

}  // namespace auvloop::results
