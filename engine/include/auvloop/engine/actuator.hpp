// SPDX-License-Identifier: GPL-3.0-or-later
// First-order actuator with amplitude and rate limits, exactly the paper's discrete update
// (section 4.2): x_{k+1} = c_k + (x_k - c_k) exp(-dt / T), then x_{k+1} = sat(x_{k+1}, min, max),
// then the rate (x_{k+1} - x_k) / dt is saturated to +-max_rate. The exponential update is exact
// for a command held constant over the step, so it is stable and accurate for any dt / T.
#pragma once

#include <limits>

#include "auvloop/engine/state_archive.hpp"

namespace auvloop::engine {

struct ActuatorLimits {
  double time_constant = 0;  // s; 0 follows the command within the step
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  double max_rate = std::numeric_limits<double>::infinity();  // units per second
};

class FirstOrderActuator {
 public:
  FirstOrderActuator(ActuatorLimits limits, double initial);
  // Advances one step toward `command`; returns the new value.
  double step(double command, double dt);
  [[nodiscard]] double value() const { return value_; }
  // True when the amplitude or rate limit changed the last step's result.
  [[nodiscard]] bool limited() const { return limited_; }
  [[nodiscard]] const ActuatorLimits& limits() const { return limits_; }
  // Exact checkpoint of the state (not the limits).
  void save(StateWriter& out) const;
  void load(StateReader& in);

 private:
  ActuatorLimits limits_;
  double value_;
  bool limited_ = false;
};

}  // namespace auvloop::engine
