// SPDX-License-Identifier: GPL-3.0-or-later
// The SST model's point functions against the limits the model was built to have, and its
// constants against hand-computed values: gamma_1 = 0.075 / 0.09 - 0.5 * 0.41^2 / 0.3 = 0.55317 and
// gamma_2 = 0.0828 / 0.09 - 0.856 * 0.41^2 / 0.3 = 0.44035 (a typo in a constant shows here;
// OpenFOAM's kOmegaSST takes the rounded 5/9 and 0.44 of the 1994 paper instead); F1 = F2 = 1 in
// the viscous sublayer, where omega = 6 nu / (beta_1 d^2) (the
// near-wall solution of the omega equation) and F1 -> 0 in the free stream; nu_t = k / omega in
// equilibrium and Bradshaw's -u'v' = a1 k (nu_t S = a1 k) where the strain is large; the
// production limiter.
#include <cmath>

#include <gtest/gtest.h>

#include "auvloop/engine/turbulence/sst.hpp"

using namespace auvloop::engine::turbulence;

TEST(Sst, GammasFollowFromTheOtherConstants) {
  const SstConstants c;
  EXPECT_NEAR(c.gamma1(), 0.553167, 1e-6);
  EXPECT_NEAR(c.gamma2(), 0.440355, 1e-6);
  const auto inner = blend(c, 1.0), outer = blend(c, 0.0), half = blend(c, 0.5);
  EXPECT_DOUBLE_EQ(inner.sigma_k, 0.85);
  EXPECT_DOUBLE_EQ(inner.beta, 0.075);
  EXPECT_DOUBLE_EQ(outer.sigma_w, 0.856);
  EXPECT_DOUBLE_EQ(outer.gamma, c.gamma2());
  EXPECT_DOUBLE_EQ(half.beta, 0.5 * (0.075 + 0.0828));
}

TEST(Sst, BlendingIsInnerInTheViscousSublayerAndOuterInTheFreeStream) {
  const SstConstants c;
  const double nu = 1e-6, d = 1e-4, k = 1e-4;
  const double omega = 6 * nu / (c.beta1 * d * d);  // 500 nu / (d^2 omega) = 500 beta1 / 6
  const double cd = cross_diffusion(c, 0.0, omega);
  EXPECT_DOUBLE_EQ(cd, c.cd_floor);
  EXPECT_DOUBLE_EQ(f1(c, k, omega, d, nu, cd), 1.0);
  EXPECT_DOUBLE_EQ(f2(c, k, omega, d, nu), 1.0);
  // Far from walls, weak turbulence: every argument is small.
  const double k_inf = 1e-6, omega_inf = 1.0, d_far = 1.0;
  EXPECT_LT(f1(c, k_inf, omega_inf, d_far, nu, cross_diffusion(c, 0.0, omega_inf)), 1e-6);
  EXPECT_LT(f2(c, k_inf, omega_inf, d_far, nu), 1e-3);
  // Cross diffusion with aligned gradients lifts CD_kw above its floor and lowers arg1's bound.
  EXPECT_DOUBLE_EQ(cross_diffusion(c, 3.0, 2.0), 2 * 0.856 * 3.0 / 2.0);
}

TEST(Sst, EddyViscosityIsKOverOmegaInEquilibriumAndBradshawsAtLargeStrain) {
  const SstConstants c;
  const double k = 2.0, omega = 4.0;
  EXPECT_DOUBLE_EQ(eddy_viscosity(c, k, omega, 1.0, 1.0), k / omega);  // S F2 < a1 omega
  const double S = 50.0;
  const double nu_t = eddy_viscosity(c, k, omega, S, 1.0);
  EXPECT_DOUBLE_EQ(nu_t * S, c.a1 * k);  // the shear stress limited to a1 k
  EXPECT_DOUBLE_EQ(eddy_viscosity(c, k, omega, S, 0.0), k / omega);  // no limiter outside F2
}

TEST(Sst, ProductionIsLimitedToTenBetaStarKOmegaAndSaysSo) {
  const SstConstants c;
  bool limited = true;
  EXPECT_DOUBLE_EQ(production(c, 0.5, 2.0, 1.0, 10.0, &limited), 2.0);
  EXPECT_FALSE(limited);
  EXPECT_DOUBLE_EQ(production(c, 0.5, 20.0, 1.0, 10.0, &limited), 10 * 0.09 * 1.0 * 10.0);
  EXPECT_TRUE(limited);
}

TEST(Sst, FreeStreamValuesGiveTheirViscosityRatios) {
  // The TMR's flat plate: U = 1, L = 1, Re = 5e6 per unit length: nu_t / nu = 1.125 / 125.
  const double nu = 1.0 / 5e6;
  const auto tmr = tmr_freestream(1.0, 1.0, nu);
  EXPECT_NEAR(tmr.k / tmr.omega / nu, 0.009, 1e-15);
  EXPECT_DOUBLE_EQ(tmr.omega, 125.0);
  // 1 % intensity at 1.54 m/s in sea water, nu_t / nu = 10.
  const auto sea = freestream_from_intensity(1.54, 0.01, 10.0, 1.05e-6);
  EXPECT_NEAR(std::sqrt(2.0 / 3 * sea.k), 0.0154, 1e-15);  // u' from k = 3/2 u'^2
  EXPECT_NEAR(sea.k / sea.omega / 1.05e-6, 10.0, 1e-12);
}
