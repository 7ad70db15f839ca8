// SPDX-License-Identifier: GPL-3.0-or-later
// Menter's SST k-omega model, 2003 form (Menter, Kuntz and Langtry, "Ten years of industrial
// experience with the SST turbulence model", Turbulence, Heat and Mass Transfer 4, 2003), with the
// constants and definitions of NASA's Turbulence Modeling Resource (../shared/reference/
// validation-data.md, section 4): the model's point functions, which the transport equations
// (to come) evaluate per cell. Incompressible; nu is the kinematic viscosity (m^2/s), k in
// m^2/s^2, omega in 1/s, d the wall distance (m), S = sqrt(2 S_ij S_ij) the strain-rate
// magnitude (1/s).
//   nu_t  = a1 k / max(a1 omega, S F2)
//   F1    = tanh(arg1^4),  arg1 = min(max(sqrt(k) / (beta* omega d), 500 nu / (d^2 omega)),
//                                     4 sigma_w2 k / (CD_kw d^2))
//   F2    = tanh(arg2^2),  arg2 = max(2 sqrt(k) / (beta* omega d), 500 nu / (d^2 omega))
//   CD_kw = max(2 sigma_w2 grad(k) . grad(omega) / omega, 1e-10)
//   phi   = F1 phi_1 + (1 - F1) phi_2 for sigma_k, sigma_w, beta and gamma, with
//   gamma_i = beta_i / beta* - sigma_wi kappa^2 / sqrt(beta*)
//   P_k   = min(nu_t S^2, 10 beta* k omega)  (the production limiter)
#pragma once

#include <algorithm>
#include <cmath>

namespace auvloop::engine::turbulence {

struct SstConstants {
  double beta_star = 0.09, a1 = 0.31, kappa = 0.41;
  double sigma_k1 = 0.85, sigma_w1 = 0.5, beta1 = 0.075;    // set 1: inner (k-omega)
  double sigma_k2 = 1.0, sigma_w2 = 0.856, beta2 = 0.0828;  // set 2: outer (k-epsilon)
  double production_limit = 10;                             // P_k <= production_limit beta* k omega
  double cd_floor = 1e-10;                                  // 1/s^2, the lower bound of CD_kw

  [[nodiscard]] double gamma1() const {
    return beta1 / beta_star - sigma_w1 * kappa * kappa / std::sqrt(beta_star);
  }
  [[nodiscard]] double gamma2() const {
    return beta2 / beta_star - sigma_w2 * kappa * kappa / std::sqrt(beta_star);
  }
};

// The blended constants at a point with blending F1 (1 near walls, 0 in the free stream).
struct SstBlend {
  double sigma_k, sigma_w, beta, gamma;
};
inline SstBlend blend(const SstConstants& c, double F1) {
  const auto mix = [F1](double inner, double outer) { return F1 * inner + (1 - F1) * outer; };
  return {mix(c.sigma_k1, c.sigma_k2), mix(c.sigma_w1, c.sigma_w2), mix(c.beta1, c.beta2),
          mix(c.gamma1(), c.gamma2())};
}

// CD_kw (1/s^2) from grad(k) . grad(omega) (1/s^3).
inline double cross_diffusion(const SstConstants& c, double grad_k_dot_grad_omega, double omega) {
  return std::max(2 * c.sigma_w2 * grad_k_dot_grad_omega / omega, c.cd_floor);
}

inline double f1(const SstConstants& c, double k, double omega, double d, double nu, double cd_kw) {
  const double a = std::max(std::sqrt(k) / (c.beta_star * omega * d), 500 * nu / (d * d * omega));
  const double arg1 = std::min(a, 4 * c.sigma_w2 * k / (cd_kw * d * d));
  return std::tanh(arg1 * arg1 * arg1 * arg1);
}

inline double f2(const SstConstants& c, double k, double omega, double d, double nu) {
  const double arg2 =
      std::max(2 * std::sqrt(k) / (c.beta_star * omega * d), 500 * nu / (d * d * omega));
  return std::tanh(arg2 * arg2);
}

inline double eddy_viscosity(const SstConstants& c, double k, double omega, double S, double F2) {
  return c.a1 * k / std::max(c.a1 * omega, S * F2);
}

// The k equation's production nu_t S^2, limited to production_limit beta* k omega; `limited`
// tells whether the limiter acted (the solver reports how often).
inline double production(const SstConstants& c, double nu_t, double S, double k, double omega,
                         bool* limited = nullptr) {
  const double p = nu_t * S * S, cap = c.production_limit * c.beta_star * k * omega;
  if (limited) *limited = p > cap;
  return std::min(p, cap);
}

// Free-stream values of k (m^2/s^2) and omega (1/s) for inlets and initial fields.
struct FreeStream {
  double k = 0, omega = 0;
};
// The TMR's for its verification cases: k = 1.125 U^2 / Re_L, omega = 125 U / L with
// Re_L = U L / nu (so nu_t / nu = 0.009); U in m/s, L the reference length (m).
inline FreeStream tmr_freestream(double U, double L, double nu) {
  const double re = U * L / nu;
  return {1.125 * U * U / re, 125 * U / L};
}
// From a turbulence intensity I (u' / U) and a viscosity ratio nu_t / nu: k = 1.5 (I U)^2,
// omega = k / (nu ratio).
inline FreeStream freestream_from_intensity(double U, double intensity, double viscosity_ratio,
                                            double nu) {
  const double k = 1.5 * (intensity * U) * (intensity * U);
  return {k, k / (nu * viscosity_ratio)};
}

}  // namespace auvloop::engine::turbulence
