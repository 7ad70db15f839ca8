// SPDX-License-Identifier: GPL-3.0-or-later
// The wall treatment against the analytic limits of Spalding's law (u+ = y+ in the viscous
// sublayer, with the formula's first neglected term as the bound; the log law ln(y+) / kappa + B
// further out, with the bound from the formula's own expansion) and round trips: u+(y+(u)) = u,
// and the friction velocity of a speed made from a known u_tau gives that u_tau back.
#include <cmath>
#include <stdexcept>
#include <tuple>

#include <gtest/gtest.h>

#include "auvloop/engine/turbulence/wall_treatment.hpp"

using namespace auvloop::engine::turbulence;

TEST(LawOfTheWall, InvertsSpaldingsFormulaToRoundOff) {
  const LawOfTheWall law;
  for (double u : {0.0, 0.01, 1.0, 5.0, 11.0, 20.0, 30.0, 60.0})
    EXPECT_NEAR(law.u_plus(law.y_plus(u)), u, 1e-12 * std::max(1.0, u)) << "u+ " << u;
  EXPECT_THROW((void)law.u_plus(-1.0), std::invalid_argument);
  EXPECT_GT(law.u_plus(1e40), 200.0);  // far beyond any grid, still finite
}

TEST(LawOfTheWall, IsLinearInTheSublayerAndLogarithmicInTheLogLayer) {
  const LawOfTheWall law;
  for (double yp : {0.01, 0.1, 0.5, 1.0}) {
    const double u = law.u_plus(yp);
    // y+ - u+ = exp(-kappa B) (kappa u)^4 / 24 (1 + O(kappa u)): the first neglected term.
    const double term = std::exp(-law.kappa * law.B) * std::pow(law.kappa * u, 4) / 24;
    EXPECT_NEAR(yp - u, term, 0.1 * term) << "y+ " << yp;  // next term: kappa u / 5 of it
    EXPECT_LT((yp - u) / yp, 2e-4) << "y+ " << yp;
  }
  // u+ = B + ln(y+ - u+ + exp(-kappa B) P3(kappa u+)) / kappa: the log law within 1.2 % at y+ =
  // 100 and 0.1 % from y+ = 1000 (the correction term shrinks as 1 / y+).
  for (const auto& [yp, rel] : {std::pair{100.0, 0.012}, {1000.0, 1e-3}, {1e4, 1e-3}}) {
    const double u = law.u_plus(yp), log_law = std::log(yp) / law.kappa + law.B;
    EXPECT_NEAR(u, log_law, rel * u) << "y+ " << yp;
  }
}

TEST(LawOfTheWall, FrictionVelocityRecoversTheOneTheSpeedWasMadeWith) {
  const LawOfTheWall law;
  const double nu = 1e-6, u_tau = 0.05;
  for (double yp : {0.5, 5.0, 30.0, 300.0}) {
    const double y = yp * nu / u_tau, U = u_tau * law.u_plus(yp);
    EXPECT_NEAR(law.friction_velocity(U, y, nu), u_tau, 1e-12 * u_tau) << "y+ " << yp;
  }
  EXPECT_EQ(law.friction_velocity(0.0, 1e-3, nu), 0.0);
  EXPECT_THROW((void)law.friction_velocity(1.0, 0.0, nu), std::invalid_argument);
  EXPECT_THROW((void)law.friction_velocity(-1.0, 1e-3, nu), std::invalid_argument);
}

TEST(WallOmega, IsTheSublayerValueNearTheWallAndTheLogValueFarFromIt) {
  const double nu = 1e-6, u_tau = 0.05;
  const auto at = [&](double yp) {
    const double y = yp * nu / u_tau;
    return std::pair{wall_omega(y, u_tau, nu), y};
  };
  const auto [w_near, y_near] = at(0.1);
  EXPECT_NEAR(w_near / (6 * nu / (0.075 * y_near * y_near)), 1.0, 1e-4);
  const auto [w_far, y_far] = at(1000.0);
  EXPECT_NEAR(w_far / (u_tau / (0.3 * 0.41 * y_far)), 1.0, 1e-4);
}

TEST(WallProduction, VanishesInTheSublayerAndIsTheLogLayersInIt) {
  // P = u_tau^4 / nu (1 - du+/dy+) du+/dy+: in the sublayer u+ = y+ - O(y+^4), so P ~ y+^3 and
  // tiny; in the log layer du+/dy+ = 1 / (kappa y+) (1 + O(1 / y+)), so P -> u_tau^3 / (kappa y).
  const LawOfTheWall law;
  const double nu = 1e-6, u_tau = 0.05;
  const double log_value_at_1 = u_tau * u_tau * u_tau / (law.kappa * nu / u_tau);
  EXPECT_LT(wall_production(law, 0.1, u_tau, nu), 1e-4 * log_value_at_1);
  for (const auto& [yp, rel] : {std::pair{300.0, 0.02}, {3000.0, 3e-3}}) {
    const double y = yp * nu / u_tau;
    EXPECT_NEAR(wall_production(law, yp, u_tau, nu) / (u_tau * u_tau * u_tau / (law.kappa * y)),
                1.0, rel)
        << "y+ " << yp;
  }
  // From u+ (the SST model's path): the same as from the y+ that u+ belongs to; zero without
  // friction.
  for (double up : {0.7, 9.0, 22.0})
    EXPECT_NEAR(wall_production_from_u_plus(law, up, u_tau, nu) /
                    wall_production(law, law.y_plus(up), u_tau, nu),
                1.0, 1e-12)
        << "u+ " << up;
  EXPECT_EQ(wall_production_from_u_plus(law, 3.0, 0.0, nu), 0.0);
  // dy+/du+ against a central difference of y_plus.
  for (double u : {0.5, 8.0, 20.0}) {
    const double h = 1e-5;
    EXPECT_NEAR(law.dy_plus_du_plus(u), (law.y_plus(u + h) - law.y_plus(u - h)) / (2 * h),
                1e-7 * law.dy_plus_du_plus(u))
        << "u+ " << u;
  }
}

TEST(MenterRoughness, IsTheSandGrainWhoseWilcoxWallOmegaIsMentersValue) {
  // Wilcox (1988): omega_w = u_tau^2 S_R / nu with S_R = (50 / ks+)^2; Menter: 60 nu / (beta1
  // d1^2). The same value for ks+ = menter_roughness(d1 u_tau / nu), whatever nu and u_tau are.
  const SstConstants c;
  for (const auto& [nu, u_tau, d1] :
       {std::tuple{2e-7, 0.037, 1e-5}, {1e-6, 0.05, 3e-4}, {1.2e-6, 0.08, 2e-3}}) {
    const double ks = menter_roughness(d1 * u_tau / nu, c);
    const double wilcox = u_tau * u_tau / nu * (50 / ks) * (50 / ks);
    EXPECT_NEAR(wilcox / (60 * nu / (c.beta1 * d1 * d1)), 1.0, 1e-12);
  }
  EXPECT_NEAR(menter_roughness(1.0, c), 1.7678, 1e-4);
}

TEST(RoughnessShare, IsZeroWhenSmoothOneWhenFullyRoughAndContinuousBetween) {
  // Cebeci-Bradshaw's transitional range 2.25 < ks+ < 90: the share leaves 0 and reaches 1 at
  // its ends (to the published constants' rounding), is sin(pi / 4) at their geometric mean
  // (the sine's argument is linear in ln ks+), and increases in between.
  EXPECT_EQ(roughness_share(0.0), 0.0);
  EXPECT_EQ(roughness_share(2.25), 0.0);
  EXPECT_LT(roughness_share(2.25 * (1 + 1e-6)), 1e-4);
  EXPECT_GT(roughness_share(90 * (1 - 1e-6)), 1 - 1e-4);
  EXPECT_EQ(roughness_share(90.0), 1.0);
  EXPECT_EQ(roughness_share(1e4), 1.0);
  EXPECT_NEAR(roughness_share(std::sqrt(2.25 * 90)), std::sqrt(0.5), 1e-3);
  double last = 0;
  for (double ks = 2.3; ks < 90; ks *= 1.2) {
    const double s = roughness_share(ks);
    EXPECT_GT(s, last) << "ks+ " << ks;
    EXPECT_LE(s, 1.0);
    last = s;
  }
}
