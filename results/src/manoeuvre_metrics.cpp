// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/results/manoeuvre_metrics.hpp"

#include <cmath>
#include <numbers>

#include "auvloop/results/metrics.hpp"

namespace auvloop::results {
namespace {
using engine::TimeSeries;
using nlohmann::json;
constexpr double kDeg = std::numbers::pi / 180;

json optional_number(const std::optional<double>& v) {
  return v ? json(*v) : json(nullptr);
}

// Mean of a signal over the last `fraction` of the run: the steady part of a turn.
double steady_mean(const std::vector<double>& v, double fraction = 0.2) {
  const auto n =
      std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(v.size()) * fraction));
  double sum = 0;
  for (std::size_t i = v.size() - n; i < v.size(); ++i) sum += v[i];
  return sum / static_cast<double>(n);
}

// Linear interpolation of `v` at time `at` (clamped to the run).
double value_at(const std::vector<double>& t, const std::vector<double>& v, double at) {
  if (at <= t.front()) return v.front();
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i] >= at) return v[i - 1] + (v[i] - v[i - 1]) * (at - t[i - 1]) / (t[i] - t[i - 1]);
  }
  return v.back();
}

json steady_turn(const TimeSeries& s) {
  const double r = steady_mean(s["r"].values), u = steady_mean(s["speed"].values);
  return {{"yaw_rate_deg_s", r},
          {"speed_m_s", u},
          {"drift_angle_deg", steady_mean(s["beta"].values)},
          {"radius_m", std::abs(r) > 1e-9 ? json(u / std::abs(r * kDeg)) : json(nullptr)}};
}

json heading_step(const engine::CaseSpec& c, const engine::HeadingStepSpec& h,
                  const TimeSeries& s) {
  const auto& t = s["t"].values;
  const std::vector<double> psi = unwrap_degrees(s["psi_true"].values);
  const double step = engine::wrap_angle(h.target_heading - c.initial_heading) / kDeg;
  const StepMetrics m =
      step_metrics(t, psi, s["e"].values, psi.front(), psi.front() + step,
                   {c.indices.rise_low, c.indices.rise_high, c.indices.settling_band});
  const ActuatorMetrics rudder = actuator_metrics(t, s["delta_r"].values, c.rudder.max / kDeg);
  return {{"step_deg", m.step},
          {"rise_time_s", optional_number(m.rise_time)},
          {"settled", m.settling_time.has_value()},
          {"settling_time_s", optional_number(m.settling_time)},
          {"peak_deg", m.peak},
          {"peak_time_s", m.peak_time},
          {"overshoot_percent", m.overshoot_percent},
          {"itae_deg_s2", m.itae},
          {"iae_deg_s", m.iae},
          {"ise_deg2_s", m.ise},
          {"final_error_deg", m.final_error},
          {"rudder",
           {{"total_variation_deg", rudder.total_variation},
            {"time_at_saturation_s", rudder.time_at_saturation},
            {"max_abs_deg", rudder.max_abs}}}};
}

json rudder_ramp(const engine::RudderRampSpec& r, const TimeSeries& s) {
  const auto& t = s["t"].values;
  const std::vector<double> psi = unwrap_degrees(s["psi_true"].values);
  const double at = r.start + r.report_time;
  return {{"report_time_s", at},
          {"heading_change_deg", value_at(t, psi, at) - psi.front()},
          {"pitch_change_deg", value_at(t, s["theta"].values, at) - s["theta"].values.front()},
          {"steady", steady_turn(s)}};
}

json turning_circle(const engine::CaseSpec& c, const TimeSeries& s) {
  const auto& t = s["t"].values;
  const std::vector<double> psi = unwrap_degrees(s["psi_true"].values);
  const auto& north = s["x_north"].values;
  const auto& east = s["y_east"].values;
  const double c0 = std::cos(c.initial_heading), s0 = std::sin(c.initial_heading);
  // Position along and across the approach course at the first time the heading has changed
  // by `angle` degrees (ITTC: advance and transfer at 90 deg, tactical diameter at 180 deg).
  auto at_change = [&](double angle) -> json {
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (std::abs(psi[i] - psi.front()) >= angle) {
        const double dn = north[i] - north.front(), de = east[i] - east.front();
        return {{"time_s", t[i]}, {"along_m", dn * c0 + de * s0}, {"across_m", -dn * s0 + de * c0}};
      }
    }
    return nullptr;
  };
  const json at90 = at_change(90), at180 = at_change(180);
  return {{"advance_m", at90.is_null() ? json(nullptr) : at90["along_m"]},
          {"transfer_m", at90.is_null() ? json(nullptr) : at90["across_m"]},
          {"tactical_diameter_m", at180.is_null() ? json(nullptr) : at180["across_m"]},
          {"time_to_90_deg_s", at90.is_null() ? json(nullptr) : at90["time_s"]},
          {"time_to_180_deg_s", at180.is_null() ? json(nullptr) : at180["time_s"]},
          {"steady", steady_turn(s)}};
}

json zigzag(const engine::ZigZagSpec& z, const TimeSeries& s) {
  const auto& t = s["t"].values;
  const std::vector<double> psi = unwrap_degrees(s["psi_true"].values);
  const auto& cmd = s["delta_r_cmd"].values;
  std::vector<std::size_t> reversals;
  for (std::size_t i = 1; i < cmd.size(); ++i) {
    if (std::signbit(cmd[i]) != std::signbit(cmd[i - 1])) reversals.push_back(i);
  }
  // Overshoot k: how far the heading change goes beyond the switch angle after reversal k.
  json overshoots = json::array();
  for (std::size_t k = 0; k < reversals.size(); ++k) {
    const std::size_t end = k + 1 < reversals.size() ? reversals[k + 1] : psi.size();
    double extreme = 0;
    for (std::size_t i = reversals[k]; i < end; ++i)
      extreme = std::max(extreme, std::abs(psi[i] - psi.front()));
    if (k + 1 < reversals.size()) overshoots.push_back(extreme - z.switch_heading / kDeg);
  }
  json times = json::array();
  for (std::size_t i : reversals) times.push_back(t[i]);
  return {
      {"reversal_times_s", times},
      {"overshoot_angles_deg", overshoots},
      {"first_overshoot_deg", overshoots.empty() ? json(nullptr) : overshoots[0]},
      {"second_overshoot_deg", overshoots.size() < 2 ? json(nullptr) : overshoots[1]},
      {"initial_turning_time_s", reversals.empty() ? json(nullptr) : json(t[reversals[0]])},
      {"period_s", reversals.size() < 3 ? json(nullptr) : json(t[reversals[2]] - t[reversals[0]])}};
}

}  // namespace

json manoeuvre_metrics(const engine::CaseSpec& c, const TimeSeries& series) {
  if (series.rows() < 2) return {{"error", "the run recorded fewer than two samples"}};
  return std::visit(
      [&](const auto& m) -> json {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, engine::HeadingStepSpec>) return heading_step(c, m, series);
        if constexpr (std::is_same_v<T, engine::RudderRampSpec>) return rudder_ramp(m, series);
        if constexpr (std::is_same_v<T, engine::TurningCircleSpec>)
          return turning_circle(c, series);
        if constexpr (std::is_same_v<T, engine::ZigZagSpec>) return zigzag(m, series);
      },
      c.manoeuvre);
}

}  // namespace auvloop::results
