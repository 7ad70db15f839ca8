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

Matrix6d rigid_body_mass(double m, const Eigen::Vector3d& r_g, const Eigen::Matrix3d& I_o) {
  Eigen::Matrix3d S;  // S(r_g) a = r_g x a
  S << 0, -r_g.z(), r_g.y(), r_g.z(), 0, -r_g.x(), -r_g.y(), r_g.x(), 0;
  Matrix6d M;
  M << m * Eigen::Matrix3d::Identity(), -m * S, m * S, I_o;
  return M;
}

Vector6d coriolis(const Matrix6d& M, const Vector6d& nu) {
  const Vector6d momentum = M * nu;
  const Eigen::Vector3d v = nu.head<3>(), omega = nu.tail<3>();
  const Eigen::Vector3d p1 = momentum.head<3>(), p2 = momentum.tail<3>();
  Vector6d c;
  c << omega.cross(p1), v.cross(p1) + omega.cross(p2);
  return c;
}

Vector6d gravity_and_buoyancy(double W, double B, const Eigen::Vector3d& r_g,
                              const Eigen::Vector3d& r_b, const Eigen::Quaterniond& q) {
  const Eigen::Vector3d down = q.conjugate() * Eigen::Vector3d::UnitZ();  // e_z of NED, body axes
  const Eigen::Vector3d fg = W * down, fb = -B * down;
  Vector6d tau;
  tau << fg + fb, r_g.cross(fg) + r_b.cross(fb);
  return tau;
}

}  // namespace auvloop::engine
