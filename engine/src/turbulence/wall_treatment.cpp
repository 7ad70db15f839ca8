// SPDX-License-Identifier: GPL-3.0-or-later
// The law of the wall and the first-cell omega: the algorithm is stated in
// auvloop/engine/turbulence/wall_treatment.hpp.
#include "auvloop/engine/turbulence/wall_treatment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace auvloop::engine::turbulence {

double LawOfTheWall::y_plus(double u) const {
  const double ku = kappa * u;
  return u + std::exp(-kappa * B) * (std::expm1(ku) - ku - ku * ku / 2 - ku * ku * ku / 6);
}

double LawOfTheWall::u_plus(double yp) const {
  if (!(yp >= 0) || !std::isfinite(yp))
    throw std::invalid_argument("law of the wall: y+ must be finite and >= 0, got " +
                                std::to_string(yp));
  // y_plus(u) is increasing and convex in u >= 0 with y_plus(u) >= u, so the root lies in
  // [0, min(y+, 300)] (u+ of y+ = 1e50 is below 300): Newton's method kept inside the bracket
  // (bisection when a step would leave it), from its upper end.
  double lo = 0, hi = std::min(yp, 300.0), u = hi;
  for (int it = 0; it < 200; ++it) {
    const double ku = kappa * u;
    const double f = y_plus(u) - yp;
    (f > 0 ? hi : lo) = u;
    const double df = 1 + std::exp(-kappa * B) * kappa * (std::expm1(ku) - ku - ku * ku / 2);
    double next = u - f / df;
    if (!(next >= lo && next <= hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - u) <= 1e-15 * std::max(1.0, u);
    u = next;
    if (done) break;
  }
  return u;
}

double LawOfTheWall::dy_plus_du_plus(double u) const {
  const double ku = kappa * u;
  return 1 + std::exp(-kappa * B) * kappa * (std::expm1(ku) - ku - ku * ku / 2);
}

double LawOfTheWall::friction_velocity(double U, double y, double nu) const {
  if (!(y > 0) || !(nu > 0) || !(U >= 0) || !std::isfinite(U))
    throw std::invalid_argument("friction velocity: need y > 0, nu > 0 and a finite U >= 0");
  if (U == 0) return 0;
  // With Re_y = U y / nu and u+ = U / u_tau, y+ = Re_y / u+: the root of
  //     F(u+) = y_plus(u+) - Re_y / u+,
  // increasing in u+ > 0, lies in (0, min(sqrt(Re_y), 300)] (y_plus(u) >= u): Newton's method
  // kept inside the bracket, from its upper end (a handful of steps; bisection when a step
  // would leave the bracket).
  const double re = U * y / nu;
  double lo = 0, hi = std::min(std::sqrt(re), 300.0), u = hi;
  for (int it = 0; it < 200; ++it) {
    const double f = y_plus(u) - re / u;
    if (f == 0) break;
    (f > 0 ? hi : lo) = u;
    double next = u - f / (dy_plus_du_plus(u) + re / (u * u));
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - u) <= 1e-15 * u;
    u = next;
    if (done) break;
  }
  return U / u;
}

double wall_production(const LawOfTheWall& law, double y_plus, double u_tau, double nu) {
  return wall_production_from_u_plus(law, law.u_plus(y_plus), u_tau, nu);
}

double wall_production_from_u_plus(const LawOfTheWall& law, double u_plus, double u_tau,
                                   double nu) {
  if (u_tau == 0) return 0;
  const double slope = 1 / law.dy_plus_du_plus(u_plus);  // du+/dy+
  return u_tau * u_tau * u_tau * u_tau / nu * (1 - slope) * slope;
}

double menter_roughness(double d1_plus, const SstConstants& c) {
  // 60 nu / (beta1 d1^2) = (u_tau^2 / nu) (50 / ks+)^2  <=>  ks+ = 50 d1+ sqrt(beta1 / 60).
  return 50 * std::sqrt(c.beta1 / 60) * d1_plus;
}

double roughness_share(double ks_plus) {
  if (!(ks_plus > 2.25)) return 0;  // hydraulically smooth (NaN too: no roughness)
  if (ks_plus >= 90) return 1;      // fully rough
  // The published constants put the sine's zero at ks+ = 2.2502 and its maximum at 89.99: clamped.
  return std::clamp(std::sin(0.4258 * (std::log(ks_plus) - 0.811)), 0.0, 1.0);
}

double wall_omega(double y, double u_tau, double nu, const SstConstants& c) {
  const double vis = 6 * nu / (c.beta1 * y * y);
  const double log = u_tau / (std::sqrt(c.beta_star) * c.kappa * y);
  return std::sqrt(vis * vis + log * log);
}

}  // namespace auvloop::engine::turbulence
