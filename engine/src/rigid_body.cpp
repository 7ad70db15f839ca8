// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/rigid_body.hpp"

#include <cmath>
#include <numbers>

namespace auvloop::engine {

double wrap_angle(double a) {
  a = std::remainder(a, 2 * std::numbers::pi);  // in [-pi, pi]
  return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
}

Eigen::Quaterniond quaternion_from_euler(const EulerAngles& e) {
  return Eigen::AngleAxisd(e.psi, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(e.theta, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(e.phi, Eigen::Vector3d::UnitX());
}

EulerAngles euler_from_quaternion(const Eigen::Quaterniond& q) {
  // Fossen (2011) eq. 2.69 from the rotation matrix R = Rz(psi) Ry(theta) Rx(phi).
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  EulerAngles e;
  e.phi = std::atan2(R(2, 1), R(2, 2));
  e.theta = -std::asin(std::clamp(R(2, 0), -1.0, 1.0));
  e.psi = wrap_angle(std::atan2(R(1, 0), R(0, 0)));
  return e;
}

EulerAngles BodyState::euler() const {
  return euler_from_quaternion(attitude);
}

KinematicRates kinematic_rates(const BodyState& s) {
  KinematicRates k;
  k.position = s.attitude * s.nu.head<3>();
  const Eigen::Quaterniond omega(0, s.p(), s.q(), s.r());
  const Eigen::Quaterniond dq = s.attitude * omega;
  k.attitude = 0.5 * Eigen::Vector4d(dq.w(), dq.x(), dq.y(), dq.z());
  return k;
}

}  // namespace auvloop::engine
