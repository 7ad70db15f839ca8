// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/sensors.hpp"

#include <cmath>

namespace auvloop::engine {

Measurements measure_exactly(const BodyState& s, const ActuatorValues& a) {
  Measurements m;
  m.nu = s.nu;
  m.position = s.position;
  m.attitude = s.euler();
  m.speed = s.nu.head<3>().norm();
  m.beta = std::atan2(s.v(), s.u());
  m.delta_r = a.delta_r;
  m.delta_s = a.delta_s;
  m.rpm = a.rpm;
  return m;
}

void IdealSensors::reset(const BodyState& initial, const ActuatorValues& actuators) {
  m_ = measure_exactly(initial, actuators);
}

void IdealSensors::update(const PlantStep& step, const ActuatorValues& actuators, double) {
  m_ = measure_exactly(step.state, actuators);
}

void VirtualIns::reset(const BodyState& initial, const ActuatorValues& actuators) {
  m_ = measure_exactly(initial, actuators);
  nu_ = initial.nu;
  attitude_ = initial.attitude;
  have_acceleration_ = false;
}

void VirtualIns::update(const PlantStep& step, const ActuatorValues& actuators, double dt) {
  // The plant reports accelerations at the end of each step; on the first step the start value
  // is unknown and taken equal to the end value.
  const Vector6d& a1 = step.acceleration;
  const Vector6d& a0 = have_acceleration_ ? last_acceleration_ : a1;
  have_acceleration_ = true;
  last_acceleration_ = a1;

  const Eigen::Vector3d v_old = nu_.head<3>();
  const Eigen::Vector3d w_old = nu_.tail<3>();
  const Eigen::Quaterniond q_old = attitude_;
  nu_.head<3>() += 0.5 * dt * (a0.head<3>() + a1.head<3>());  // accelerometers, integrated
  nu_.tail<3>() = step.state.nu.tail<3>();                    // gyros measure rates directly
  // Attitude: rotate by the mean rate over the step (exact for a constant rate).
  const Eigen::Vector3d w_mean = 0.5 * (w_old + nu_.tail<3>());
  const double angle = w_mean.norm() * dt;
  if (angle > 0)
    attitude_ = attitude_ * Eigen::Quaterniond(Eigen::AngleAxisd(angle, w_mean.normalized()));
  attitude_.normalize();
  m_.position += 0.5 * dt * (q_old * v_old + attitude_ * nu_.head<3>());

  m_.nu = nu_;
  m_.attitude = euler_from_quaternion(attitude_);
  m_.speed = nu_.head<3>().norm();
  m_.beta = std::atan2(nu_[1], nu_[0]);
  m_.delta_r = actuators.delta_r;
  m_.delta_s = actuators.delta_s;
  m_.rpm = actuators.rpm;
}

namespace {
void put(StateWriter& out, const Measurements& m) {
  out.put(m.nu);
  out.put(m.position);
  out.put(m.attitude);
  for (double v : {m.speed, m.beta, m.delta_r, m.delta_s, m.rpm}) out.put(v);
}

Measurements get_measurements(StateReader& in) {
  Measurements m;
  in.get(m.nu);
  in.get(m.position);
  m.attitude = in.get<EulerAngles>();
  for (double* v : {&m.speed, &m.beta, &m.delta_r, &m.delta_s, &m.rpm}) *v = in.get<double>();
  return m;
}
}  // namespace

void IdealSensors::save(StateWriter& out) const {
  out.tag("ideal sensors");
  put(out, m_);
}

void IdealSensors::load(StateReader& in) {
  in.expect_tag("ideal sensors");
  m_ = get_measurements(in);
}

void VirtualIns::save(StateWriter& out) const {
  out.tag("virtual INS");
  put(out, m_);
  out.put(nu_);
  out.put(last_acceleration_);
  out.put(attitude_);
  out.put(have_acceleration_);
}

void VirtualIns::load(StateReader& in) {
  in.expect_tag("virtual INS");
  auto m = get_measurements(in);
  in.get(nu_);
  in.get(last_acceleration_);
  in.get(attitude_);
  have_acceleration_ = in.get<bool>();
  m_ = m;
}

}  // namespace auvloop::engine
