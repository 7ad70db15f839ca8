// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

namespace auvloop::engine {
namespace detail {
struct Derivative {
  Vector6d nu;
  Eigen::Vector3d position;
  Eigen::Vector4d attitude;
};

inline BodyState advanced(const BodyState& s, const Derivative& d, double h) {
  BodyState out;
  out.nu = s.nu + h * d.nu;
  out.position = s.position + h * d.position;
  Eigen::Vector4d q(s.attitude.w(), s.attitude.x(), s.attitude.y(), s.attitude.z());
  q += h * d.attitude;
  out.attitude = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  return out;
}

template <class Acceleration>
Derivative evaluate(const BodyState& s, Acceleration& f) {
  const KinematicRates k = kinematic_rates(s);
  return {f(s), k.position, k.attitude};
}
}  // namespace detail

template <class Acceleration>
BodyState rk4_step(const BodyState& s, double dt, Acceleration&& f) {
  using detail::advanced;
  using detail::evaluate;
  const auto k1 = evaluate(s, f);
  const auto k2 = evaluate(advanced(s, k1, dt / 2), f);
  const auto k3 = evaluate(advanced(s, k2, dt / 2), f);
  const auto k4 = evaluate(advanced(s, k3, dt), f);
  detail::Derivative sum{(k1.nu + 2 * k2.nu + 2 * k3.nu + k4.nu) / 6,
                         (k1.position + 2 * k2.position + 2 * k3.position + k4.position) / 6,
                         (k1.attitude + 2 * k2.attitude + 2 * k3.attitude + k4.attitude) / 6};
  BodyState out = advanced(s, sum, dt);
  out.attitude.normalize();
  return out;
}

}  // namespace auvloop::engine
