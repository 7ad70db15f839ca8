// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/closed_loop.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/geometry/file_io.hpp"

namespace auvloop::engine {
namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;

// The recorded columns, in file order.
class Recorder {
 public:
  // The loop's columns, then the plant's own (Plant::signal_columns).
  explicit Recorder(const Plant& plant) : plant_(plant) {
    for (const auto& [name, unit] : kColumns) series.add(name, unit);
    for (auto& [name, unit] : plant.signal_columns()) series.add(std::move(name), std::move(unit));
  }
  void record(double t, const BodyState& truth, const Measurements& m, const Commands& c,
              const ActuatorValues& a) {
    const EulerAngles e = truth.euler();
    const double psi_d = std::isnan(c.psi_desired) ? std::nan("") : c.psi_desired * kDeg;
    const double values[] = {t,
                             psi_d,
                             m.attitude.psi * kDeg,
                             e.psi * kDeg,
                             std::isnan(c.psi_desired)
                                 ? std::nan("")
                                 : heading_error(c.psi_desired, m.attitude.psi) * kDeg,
                             c.delta_r * kDeg,
                             a.delta_r * kDeg,
                             c.delta_s * kDeg,
                             a.delta_s * kDeg,
                             c.rpm,
                             a.rpm,
                             truth.u(),
                             truth.v(),
                             truth.w(),
                             truth.p() * kDeg,
                             truth.q() * kDeg,
                             truth.r() * kDeg,
                             e.phi * kDeg,
                             e.theta * kDeg,
                             truth.position.x(),
                             truth.position.y(),
                             truth.position.z(),
                             truth.nu.head<3>().norm(),
                             std::atan2(truth.v(), truth.u()) * kDeg};
    for (std::size_t i = 0; i < std::size(values); ++i) series.push(i, values[i]);
    const auto own = plant_.signal_values();
    if (own.size() + std::size(values) != series.signals().size())
      throw std::logic_error(fmt::format("the {} plant recorded {} values for {} columns",
                                         plant_.name(), own.size(),
                                         series.signals().size() - std::size(values)));
    for (std::size_t i = 0; i < own.size(); ++i) series.push(std::size(values) + i, own[i]);
  }
  TimeSeries series;

 private:
  const Plant& plant_;
  static constexpr std::pair<const char*, const char*> kColumns[] = {
      {"t", "s"},         {"psi_d", "deg"},       {"psi", "deg"},     {"psi_true", "deg"},
      {"e", "deg"},       {"delta_r_cmd", "deg"}, {"delta_r", "deg"}, {"delta_s_cmd", "deg"},
      {"delta_s", "deg"}, {"rpm_cmd", "rev/min"}, {"rpm", "rev/min"}, {"u", "m/s"},
      {"v", "m/s"},       {"w", "m/s"},           {"p", "deg/s"},     {"q", "deg/s"},
      {"r", "deg/s"},     {"phi", "deg"},         {"theta", "deg"},   {"x_north", "m"},
      {"y_east", "m"},    {"z_down", "m"},        {"speed", "m/s"},   {"beta", "deg"}};
};
}  // namespace

HeadingStep::HeadingStep(double psi_desired, PidGains gains, PidOptions options, double rpm)
    : psi_desired_(psi_desired), rpm_(rpm), pid_(gains, options) {}

Commands HeadingStep::command(double, const Measurements& m, double dt) {
  Commands c;
  c.psi_desired = psi_desired_;
  c.delta_r = -pid_.update(psi_desired_, m.attitude.psi, dt);
  c.rpm = rpm_;
  return c;
}

RudderRamp::RudderRamp(Surface surface, double angle, double rate, double start, double rpm)
    : surface_(surface), angle_(angle), rate_(rate), start_(start), rpm_(rpm) {}

Commands RudderRamp::command(double t, const Measurements&, double) {
  const double ramp = std::clamp((t - start_) * rate_, 0.0, std::abs(angle_));
  Commands c;
  (surface_ == Surface::rudder ? c.delta_r : c.delta_s) = std::copysign(ramp, angle_);
  c.rpm = rpm_;
  return c;
}

ZigZag::ZigZag(double rudder, double switch_heading, double initial_heading, double rpm)
    : rudder_(rudder), switch_(switch_heading), psi0_(initial_heading), rpm_(rpm) {}

Commands ZigZag::command(double, const Measurements& m, double) {
  const double change = wrap_angle(m.attitude.psi - psi0_);
  if (direction_ > 0 && change >= switch_) direction_ = -1;
  if (direction_ < 0 && change <= -switch_) direction_ = 1;
  Commands c;
  c.delta_r = -direction_ * rudder_;  // Prestero: delta_r < 0 turns to starboard
  c.rpm = rpm_;
  return c;
}

void HeadingStep::save(StateWriter& out) const {
  out.tag("heading step");
  pid_.save(out);
}

void HeadingStep::load(StateReader& in) {
  in.expect_tag("heading step");
  pid_.load(in);
}

void RudderRamp::save(StateWriter& out) const {
  out.tag("rudder ramp");
}

void RudderRamp::load(StateReader& in) {
  in.expect_tag("rudder ramp");
}

void ZigZag::save(StateWriter& out) const {
  out.tag("zig-zag");
  out.put(direction_);
}

void ZigZag::load(StateReader& in) {
  in.expect_tag("zig-zag");
  direction_ = in.get<int>();
}

void Actuators::save(StateWriter& out) const {
  out.tag("actuators");
  for (const auto* a : {&rudder, &stern_plane, &propeller}) a->save(out);
}

void Actuators::load(StateReader& in) {
  in.expect_tag("actuators");
  for (auto* a : {&rudder, &stern_plane, &propeller}) a->load(in);
}

namespace {
constexpr std::string_view kLoopMagic = "auvloop closed-loop checkpoint";
constexpr std::uint32_t kLoopVersion = 1;
}  // namespace

LoopResult run_closed_loop(Plant& plant, Sensors& sensors, Manoeuvre& manoeuvre,
                           Actuators& actuators, const BodyState& initial,
                           const LoopSettings& settings) {
  const double dt = settings.dt;
  const auto steps = static_cast<long>(std::llround(settings.duration / dt));
  Recorder recorder(plant);
  LoopResult result;
  long first = 0;
  if (settings.resume && !settings.checkpoint.empty() &&
      std::filesystem::exists(settings.checkpoint)) {
    StateReader in(read_file_text(settings.checkpoint), settings.checkpoint.string());
    in.expect_tag(kLoopMagic);
    if (const auto version = in.get<std::uint32_t>(); version != kLoopVersion)
      in.fail(fmt::format("version {}, this build reads version {}", version, kLoopVersion));
    if (const auto key = in.get_string(); key != settings.checkpoint_key)
      in.fail(
          fmt::format("written for another run (key {}, this run's {}): remove it to start "
                      "afresh",
                      key.substr(0, 16), settings.checkpoint_key.substr(0, 16)));
    first = in.get<std::int64_t>();
    if (first < 1 || first > steps)
      in.fail(fmt::format("step {} is not within this run's {} steps", first, steps));
    plant.load(in);
    sensors.load(in);
    manoeuvre.load(in);
    actuators.load(in);
    recorder.series.load(in);
    in.expect_end();
    if (recorder.series.rows() != static_cast<std::size_t>(first))
      in.fail(fmt::format("{} recorded rows for step {}", recorder.series.rows(), first));
    result.resumed_at = first;
  } else {
    plant.reset(initial);
    sensors.reset(initial, actuators.values());
  }
  const auto write_checkpoint = [&](long next) {
    try {
      StateWriter out;
      out.tag(kLoopMagic);
      out.put(kLoopVersion);
      out.put(std::string_view(settings.checkpoint_key));
      out.put(static_cast<std::int64_t>(next));
      plant.save(out);
      sensors.save(out);
      manoeuvre.save(out);
      actuators.save(out);
      recorder.series.save(out);
      if (settings.checkpoint.has_parent_path())
        std::filesystem::create_directories(settings.checkpoint.parent_path());
      write_file_atomically(settings.checkpoint, out.bytes());
    } catch (const std::exception& e) {
      result.checkpoint_warning =
          fmt::format("checkpoint at step {} not written: {}", next, e.what());
    }
  };
  for (long k = first;; ++k) {
    const double t = static_cast<double>(k) * dt;
    const Measurements& m = sensors.read();          // 1
    const Commands c = manoeuvre.command(t, m, dt);  // 2
    recorder.record(t, plant.state(), m, c, actuators.values());
    result.final_time = t;
    if (k == steps) break;
    actuators.rudder.step(c.delta_r, dt);  // 3
    actuators.stern_plane.step(c.delta_s, dt);
    actuators.propeller.step(c.rpm, dt);
    const ActuatorValues applied = actuators.values();
    const PlantResult r = plant.advance(applied, dt);  // 4
    if (const auto* failure = std::get_if<PlantFailure>(&r)) {
      result.failure = fmt::format("the {} plant diverged between t = {:.4g} s and {:.4g} s: {}",
                                   plant.name(), t, t + dt, failure->reason);
      break;
    }
    sensors.update(std::get<PlantStep>(r), applied, dt);                                   // 5
    if (settings.after_step) settings.after_step(k + 1, static_cast<double>(k + 1) * dt);  // 6
    if (!settings.checkpoint.empty() && settings.checkpoint_every > 0 && k + 1 < steps &&
        (k + 1) % settings.checkpoint_every == 0)
      write_checkpoint(k + 1);
    if (settings.progress && k % std::max(1, settings.progress_every) == 0) settings.progress(t);
  }
  result.series = std::move(recorder.series);
  return result;
}

}  // namespace auvloop::engine
