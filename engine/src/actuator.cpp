// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/actuator.hpp"

#include <algorithm>
#include <cmath>

namespace auvloop::engine {

FirstOrderActuator::FirstOrderActuator(ActuatorLimits limits, double initial)
    : limits_(limits), value_(std::clamp(initial, limits.min, limits.max)) {}

double FirstOrderActuator::step(double command, double dt) {
  const double lag = limits_.time_constant > 0 ? std::exp(-dt / limits_.time_constant) : 0.0;
  const double unlimited = command + (value_ - command) * lag;
  const double amplitude = std::clamp(unlimited, limits_.min, limits_.max);
  const double max_step = limits_.max_rate * dt;
  const double next = value_ + std::clamp(amplitude - value_, -max_step, max_step);
  limited_ = next != unlimited;
  value_ = next;
  return value_;
}

void FirstOrderActuator::save(StateWriter& out) const {
  out.put(value_);
  out.put(limited_);
}

void FirstOrderActuator::load(StateReader& in) {
  const auto value = in.get<double>();
  limited_ = in.get<bool>();
  value_ = value;
}

}  // namespace auvloop::engine
