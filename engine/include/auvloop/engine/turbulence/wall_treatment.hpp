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
//   Menter's wall-face omega 60 nu / (beta1 d1^2) (d1 the first cell's height), read as a rough
//   wall: Wilcox's rough-wall value omega_w = u_tau^2 S_R / nu with S_R = (50 / ks+)^2 (Wilcox
//   1988, calibrated for the k-omega model with beta = 3/40, which is SST's inner layer) equals
//   it for the sand-grain roughness ks+ = sqrt(2500 beta1 / 60) d1+ = 1.768 d1+: smooth only
//   while the first cell is thin. The share of a roughness' effect (Cebeci and Bradshaw 1977,
//   on Nikuradse's sand grains): 0 for ks+ <= 2.25 (hydraulically smooth), sin(0.4258 (ln ks+ -
//   0.811)) in the transitional range, 1 from ks+ = 90 (fully rough).
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
// The same from u+ = U / u_tau, which friction_velocity's caller has already (no inverse of the
// law to take); zero when u_tau is zero.
double wall_production_from_u_plus(const LawOfTheWall& law, double u_plus, double u_tau, double nu);

// The sand-grain roughness ks+ that Menter's wall-face omega amounts to on a first cell of
// height d1+ = d1 u_tau / nu (above).
double menter_roughness(double d1_plus, const SstConstants& c = {});

// The share in [0, 1] of a sand-grain roughness ks+'s effect on the wall (Cebeci-Bradshaw, above).
double roughness_share(double ks_plus);

// The first cell's omega (1/s) at wall distance y with friction velocity u_tau, with the model's
// beta1, beta* and kappa.
double wall_omega(double y, double u_tau, double nu, const SstConstants& c = {});

}  // namespace auvloop::engine::turbulence
