// SPDX-License-Identifier: GPL-3.0-or-later
// The wall treatment for any y+ (issue 16, item 4): the continuous law of the wall and the
// first-cell omega, both valid from the viscous sublayer through the buffer layer to the log
// layer, so that one grid family needs no switch between low-Re and wall-function treatment.
//   Spalding's law (J. Appl. Mech. 28, 1961), y+ as a function of u+:
//     y+ = u+ + exp(-kappa B) [exp(kappa u+) - 1 - kappa u+ - (kappa u+)^2 / 2 - (kappa u+)^3 / 6]
//   with kappa = 0.41, B = 5.2: u+ -> y+ in the sublayer, u+ -> ln(y+) / kappa + B in the log
//   layer. u_plus() inverts it (Newton's method inside the bracket [0, min(y+, 300)]), and
//   friction_velocity() solves U = u_tau u+(y u_tau / nu) for u_tau given the wall-parallel
//   speed U at wall distance y (Newton's method on u+, in the bracket (0, min(sqrt(U y / nu),
//   300)], to round-off).
//   The turbulent part of the wall shear stress at y+, from the total stress being constant
//   across the inner layer: tau_t / tau_w = 1 - du+/dy+ (zero in the sublayer, 1 in the log
//   layer), so the first cell's k production tau_t du/dy is
//     P = u_tau^4 / nu (1 - du+/dy+) du+/dy+,
//   continuous in y+ and u_tau^3 / (kappa y) in the log layer.
//   omega at the first cell: the viscous-sublayer value 6 nu / (beta1 y^2) and the log-layer value
//   u_tau / (sqrt(beta*) kappa y) blended as sqrt(omega_vis^2 + omega_log^2) (as OpenFOAM's
//   omegaWallFunction blends them), so each dominates where it holds.
#pragma once

#include "auvloop/engine/turbulence/sst.hpp"

namespace auvloop::engine::turbulence {

struct LawOfTheWall {
  double kappa = 0.41, B = 5.2;
  // Spalding's y+ for a given u+.
  [[nodiscard]] double y_plus(double u_plus) const;
  // u+ for a given y+ >= 0 (the inverse of y_plus, by Newton's method).
  [[nodiscard]] double u_plus(double y_plus) const;
  // dy+/du+ at u+ (>= 1; 1 in the viscous sublayer, kappa y+ in the log layer).
  [[nodiscard]] double dy_plus_du_plus(double u_plus) const;
  // u_tau (m/s) such that U = u_tau u+(y u_tau / nu): U the wall-parallel speed (m/s) relative to
  // the wall at wall distance y (m), nu (m^2/s). Zero when U is zero; throws std::invalid_argument
  // for y or nu not positive or U negative or not finite.
  [[nodiscard]] double friction_velocity(double U, double y, double nu) const;
};

// The first cell's k production (m^2/s^3) at y+ (above), friction velocity u_tau.
double wall_production(const LawOfTheWall& law, double y_plus, double u_tau, double nu);

// The first cell's omega (1/s) at wall distance y with friction velocity u_tau, with the model's
// beta1, beta* and kappa.
double wall_omega(double y, double u_tau, double nu, const SstConstants& c = {});

}  // namespace auvloop::engine::turbulence
