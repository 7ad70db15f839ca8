// SPDX-License-Identifier: GPL-3.0-or-later
// 6-DOF rigid-body state and kinematics (Fossen 2011, ch. 2): body velocities nu = (u, v, w, p, q,
// r) in the body frame (x forward, y starboard, z down), position in NED, attitude as the unit
// quaternion rotating body vectors into NED. Euler angles (zyx: phi, theta, psi) only appear at the
// interface, so kinematics stay regular through any heading, including the wrap at +-180 deg.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

namespace auvloop::engine {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct EulerAngles {
  double phi = 0;    // roll (rad)
  double theta = 0;  // pitch (rad)
  double psi = 0;    // yaw / heading (rad), in (-pi, pi]
};

struct BodyState {
  Vector6d nu = Vector6d::Zero();                                // u v w (m/s), p q r (rad/s)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();            // north, east, down (m)
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();  // body -> NED

  [[nodiscard]] double u() const { return nu[0]; }
  [[nodiscard]] double v() const { return nu[1]; }
  [[nodiscard]] double w() const { return nu[2]; }
  [[nodiscard]] double p() const { return nu[3]; }
  [[nodiscard]] double q() const { return nu[4]; }
  [[nodiscard]] double r() const { return nu[5]; }
  [[nodiscard]] EulerAngles euler() const;
};

Eigen::Quaterniond quaternion_from_euler(const EulerAngles& e);
EulerAngles euler_from_quaternion(const Eigen::Quaterniond& q);

// Wraps an angle to (-pi, pi].
double wrap_angle(double a);

// Time derivative of (position, attitude) for body velocity nu: position' = R(q) (u, v, w),
// q' = q * (0, p, q, r) / 2.
struct KinematicRates {
  Eigen::Vector3d position;
  Eigen::Vector4d attitude;  // (w, x, y, z) components of dq/dt
};
KinematicRates kinematic_rates(const BodyState& s);

// One classical fourth-order Runge-Kutta step of the full state under body accelerations
// nu' = f(state). The quaternion is renormalised after the step (its drift is O(dt^5)).
template <class Acceleration>
BodyState rk4_step(const BodyState& s, double dt, Acceleration&& f);

}  // namespace auvloop::engine

#include "auvloop/engine/detail/rk4.ipp"
