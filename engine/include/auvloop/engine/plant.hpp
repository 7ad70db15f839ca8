// SPDX-License-Identifier: GPL-3.0-or-later
// The Plant: what the closed loop drives. The derivative (Prestero) plant, its linearisation and,
// later, the CFD plant all implement it, so the same controller, actuators and sensors run on each.
//
// Contract: advance() moves the vehicle from t_k to t_k + dt holding the actuator values constant
// over the step, and returns the new state with the body-frame accelerations nu' at t_k + dt (what
// a DFBI solver reports and what the virtual INS integrates). A plant that cannot continue (NaN,
// runaway speed, a diverged flow solution) returns an error instead of a state; its last good state
// stays available through state().
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "auvloop/engine/rigid_body.hpp"
#include "auvloop/engine/state_archive.hpp"

namespace auvloop::engine {

struct ActuatorValues {
  double delta_r = 0;  // rudder angle (rad), Prestero's sign: > 0 turns the nose to port
  double delta_s = 0;  // stern-plane angle (rad), > 0 pitches the nose down
  double rpm = 0;      // propeller speed (rev/min)
};

struct PlantStep {
  BodyState state;
  Vector6d acceleration = Vector6d::Zero();  // u' v' w' (m/s^2), p' q' r' (rad/s^2), body frame
};

struct PlantFailure {
  std::string reason;  // e.g. "speed 41.2 m/s exceeds the runaway limit of 20 m/s"
};

using PlantResult = std::variant<PlantStep, PlantFailure>;

class Plant {
 public:
  virtual ~Plant() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  virtual void reset(const BodyState& initial) = 0;
  virtual PlantResult advance(const ActuatorValues& actuators, double dt) = 0;
  [[nodiscard]] virtual const BodyState& state() const = 0;
  // Exact checkpoint (the closed loop's, closed_loop.hpp): everything the next advance() reads
  // besides the construction's settings, so that a plant built alike and loaded continues
  // bitwise. The defaults throw std::runtime_error (a plant without one); load() throws
  // std::runtime_error on a record of another plant or grid, leaving the plant unchanged.
  virtual void save(StateWriter& out) const;
  virtual void load(StateReader& in);
  // The plant's own quantities, recorded by the closed loop beside its columns at every step
  // (the CFD plant's forces per part and its propeller): names and units, fixed from
  // construction on, and the values of the last advance() (NaN before the first after a reset;
  // restored by load(), so that a resumed run records what the uninterrupted one did). None by
  // default.
  [[nodiscard]] virtual std::vector<std::pair<std::string, std::string>> signal_columns() const {
    return {};
  }
  [[nodiscard]] virtual std::vector<double> signal_values() const { return {}; }
  // Where advance()'s wall clock went since the last reset() or load(): (phase, seconds), the
  // phases disjoint and summing to the whole; none by default (a cheap plant).
  [[nodiscard]] virtual std::vector<std::pair<std::string, double>> wall_clock() const {
    return {};
  }
};

void put(StateWriter& out, const BodyState& s);
BodyState get_body_state(StateReader& in);
// The whole record of a plant whose state is its body's (the derivative and linearised plants):
// the tag naming the plant, then the state.
void save_body_state(StateWriter& out, std::string_view tag, const BodyState& s);
BodyState load_body_state(StateReader& in, std::string_view tag);

}  // namespace auvloop::engine
