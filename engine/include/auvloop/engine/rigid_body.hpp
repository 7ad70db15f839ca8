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

// Fossen (2011) eq. 3.44: the rigid-body mass matrix about the body origin o of a body of mass m
// (kg) with its centre of gravity at r_g (m, from o) and the inertia tensor I_o (kg m^2, about
// o): [[m 1, -m S(r_g)], [m S(r_g), I_o]], S(a) b = a x b.
Matrix6d rigid_body_mass(double m, const Eigen::Vector3d& r_g, const Eigen::Matrix3d& I_o);

// The Coriolis and centripetal term C(nu) nu of a body whose motion has the kinetic energy
// nu^T M nu / 2 (M symmetric: rigid body, or rigid body and added mass), in Kirchhoff's form
// (Fossen 2011, theorem 3.2): with the momenta (p1, p2) = M nu and nu = (v, omega),
// C(nu) nu = (omega x p1, v x p1 + omega x p2), so that M nu' + C(nu) nu = tau. It does no work:
// nu . C(nu) nu = 0.
Vector6d coriolis(const Matrix6d& M, const Vector6d& nu);

// The load of weight W and buoyancy B (N) on the body (N, N m about the origin, body axes) at the
// attitude q (body -> NED): the weight W R^T e_z at r_g and the buoyancy -B R^T e_z at r_b
// (Fossen's -g(eta), eq. 4.6).
Vector6d gravity_and_buoyancy(double W, double B, const Eigen::Vector3d& r_g,
                              const Eigen::Vector3d& r_b, const Eigen::Quaterniond& q);

// One classical fourth-order Runge-Kutta step of the full state under body accelerations
// nu' = f(state). The quaternion is renormalised after the step (its drift is O(dt^5)).
template <class Acceleration>
BodyState rk4_step(const BodyState& s, double dt, Acceleration&& f);

}  // namespace auvloop::engine

#include "auvloop/engine/detail/rk4.ipp"
