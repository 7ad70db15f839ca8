// SPDX-License-Identifier: GPL-3.0-or-later
// What the controller sees (paper section 4.1 (2)). The virtual INS reconstructs velocity, attitude
// and position from what a DFBI solver reports, the body accelerations nu' and angular rates: body
// velocity by trapezoidal integration of nu', attitude by integrating the rates on the unit
// quaternion (for level turns this is the paper's psi = integral of r dt), position by integrating
// the NED velocity. Rudder-angle and rpm feedback report the actuator states. The ideal sensors
// copy the plant state instead.
#pragma once

#include "auvloop/engine/plant.hpp"

namespace auvloop::engine {

struct Measurements {
  Vector6d nu = Vector6d::Zero();                      // u v w p q r
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // NED (m)
  EulerAngles attitude;
  double speed = 0;    // m/s, |(u, v, w)|
  double beta = 0;     // drift angle atan2(v, u) (rad)
  double delta_r = 0;  // rudder feedback (rad)
  double delta_s = 0;
  double rpm = 0;
};

class Sensors {
 public:
  virtual ~Sensors() = default;
  virtual void reset(const BodyState& initial, const ActuatorValues& actuators) = 0;
  // Called after each plant step with the step's result and the actuator values it used.
  virtual void update(const PlantStep& step, const ActuatorValues& actuators, double dt) = 0;
  [[nodiscard]] virtual const Measurements& read() const = 0;
  // Exact checkpoint of the state (closed_loop.hpp).
  virtual void save(StateWriter& out) const = 0;
  virtual void load(StateReader& in) = 0;
};

class IdealSensors final : public Sensors {
 public:
  void reset(const BodyState& initial, const ActuatorValues& actuators) override;
  void update(const PlantStep& step, const ActuatorValues& actuators, double dt) override;
  [[nodiscard]] const Measurements& read() const override { return m_; }
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

 private:
  Measurements m_;
};

class VirtualIns final : public Sensors {
 public:
  void reset(const BodyState& initial, const ActuatorValues& actuators) override;
  void update(const PlantStep& step, const ActuatorValues& actuators, double dt) override;
  [[nodiscard]] const Measurements& read() const override { return m_; }
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

 private:
  Measurements m_;
  Vector6d nu_, last_acceleration_;
  Eigen::Quaterniond attitude_;
  bool have_acceleration_ = false;
};

Measurements measure_exactly(const BodyState& s, const ActuatorValues& a);

}  // namespace auvloop::engine
