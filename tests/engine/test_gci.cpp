// SPDX-License-Identifier: GPL-3.0-or-later
// The grid convergence index (engine/src/validation/gci.cpp) against the paper's Table 2 and an
// exact power law.
#include <cmath>

#include <gtest/gtest.h>

#include "auvloop/engine/validation.hpp"

namespace v = auvloop::engine::validation;

TEST(GridConvergence, ReproducesThePapersTable2) {
  // The paper's three grids (2.58, 3.54 and 4.88 million cells; drag 8.85, 9.06 and 9.22 N) and
  // what it printed: r32 1.111, r21 1.113, p 2.56, GCI21 6.88 %, GCI32 9.35 %, and the
  // asymptotic check 1.03. Each within half a unit of its last printed digit.
  const auto g = v::grid_convergence({4.88e6, 3.54e6, 2.58e6}, {9.22, 9.06, 8.85},
                                     v::OrderEstimate::mean_ratio);
  EXPECT_NEAR(g.r32, 1.111, 5e-4);
  EXPECT_NEAR(g.r21, 1.113, 5e-4);
  EXPECT_NEAR(g.p, 2.56, 5e-3);
  EXPECT_NEAR(100 * g.gci21, 6.88, 5e-3);
  EXPECT_NEAR(100 * g.gci32, 9.35, 5e-3);
  EXPECT_NEAR(g.asymptotic, 1.03, 5e-3);
  EXPECT_FALSE(g.oscillatory);
}

TEST(GridConvergence, CelikRecoversAnExactPowerLawOnUnequalRatios) {
  // phi = 5 + 3 h^1.7 with h = N^(-1/3) on ratios 1.5 and 1.2: the order, the extrapolated value
  // and its relative error exactly; the asymptotic check exactly phi1 / phi2.
  const std::array<double, 3> cells{1e6, 1e6 / std::pow(1.5, 3), 1e6 / std::pow(1.5 * 1.2, 3)};
  std::array<double, 3> phi{};
  for (std::size_t i = 0; i < 3; ++i) phi[i] = 5 + 3 * std::pow(cells[i], -1.7 / 3);
  const auto g = v::grid_convergence(cells, phi);
  ASSERT_TRUE(g.converged);
  EXPECT_NEAR(g.r21, 1.5, 1e-12);
  EXPECT_NEAR(g.r32, 1.2, 1e-12);
  EXPECT_NEAR(g.p, 1.7, 1e-9);
  EXPECT_NEAR(g.extrapolated, 5, 1e-12);
  EXPECT_NEAR(g.e_ext21, (phi[0] - 5) / 5, 1e-12);
  EXPECT_NEAR(g.asymptotic, phi[0] / phi[1], 1e-9);  // each GCI relative to its own grid's value
  // The mean ratio misjudges the order when the ratios differ.
  const auto m = v::grid_convergence(cells, phi, v::OrderEstimate::mean_ratio);
  EXPECT_GT(std::abs(m.p - 1.7), 0.1);
}

TEST(GridConvergence, OscillatingOrFlatSequencesAreFlagged) {
  const auto o = v::grid_convergence({8e6, 1e6, 1.25e5}, {1.0, 1.1, 0.9});
  EXPECT_TRUE(o.oscillatory);
  const auto flat = v::grid_convergence({8e6, 1e6, 1.25e5}, {1.0, 1.0, 1.2});
  EXPECT_FALSE(flat.converged);
  EXPECT_TRUE(std::isnan(flat.gci21));
}
