// SPDX-License-Identifier: GPL-3.0-or-later
// The grid convergence index of a quantity on three systematically refined grids (Celik, Ghia,
// Roache, Freitas, Coleman and Raad 2008, "Procedure for estimation and reporting of uncertainty
// due to discretization in CFD applications", J. Fluids Eng. 130, 078001; the paper's Table 2
// follows it). Grid 1 is the finest, 3 the coarsest:
//   1. representative cell sizes h_i = (1 / N_i)^(1/3) (3D), ratios r21 = h2 / h1, r32 = h3 / h2;
//   2. changes e21 = phi2 - phi1, e32 = phi3 - phi2, s = sign(e32 / e21) (s < 0: oscillatory);
//   3. apparent order p by fixed-point iteration of
//        p = |ln|e32 / e21| + q(p)| / ln r21,  q(p) = ln((r21^p - s) / (r32^p - s)),
//      from q = 0 (OrderEstimate::celik); or, as the paper computed its Table 2 (its figures
//      come out to every printed digit this way), p = |ln|e32 / e21|| / ln r with one ratio,
//      the mean r = sqrt(r21 r32) (OrderEstimate::mean_ratio);
//   4. the extrapolated value phi_ext = (r21^p phi1 - phi2) / (r21^p - 1), the relative errors
//      e_a21 = |(phi1 - phi2) / phi1| and e_ext21 = |(phi_ext - phi1) / phi_ext|;
//   5. GCI21 = 1.25 e_a21 / (r21^p - 1) (the fine grid's) and GCI32 = 1.25 e_a32 / (r32^p - 1)
//      with e_a32 = |(phi2 - phi3) / phi2|; GCI32 / (r21^p GCI21) near 1 says the three are in
//      the asymptotic range.
#include <cmath>
#include <limits>

#include "auvloop/engine/validation.hpp"

namespace auvloop::engine::validation {

GridConvergence grid_convergence(const std::array<double, 3>& cells,
                                 const std::array<double, 3>& phi, OrderEstimate order) {
  GridConvergence g;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  g.r21 = std::cbrt(cells[0] / cells[1]);  // 1.
  g.r32 = std::cbrt(cells[1] / cells[2]);
  const double e21 = phi[1] - phi[0], e32 = phi[2] - phi[1];  // 2.
  g.oscillatory = e21 * e32 < 0;
  g.p = g.extrapolated = g.e_ext21 = g.gci21 = g.gci32 = g.asymptotic = nan;
  g.e_a21 = std::abs(e21 / phi[0]);
  if (e21 == 0 || e32 == 0 || !(g.r21 > 1) || !(g.r32 > 1)) return g;
  const double s = g.oscillatory ? -1.0 : 1.0;
  const double ratio = std::log(std::abs(e32 / e21));
  double p = std::abs(ratio) / std::log(g.r21);  // 3.
  if (order == OrderEstimate::mean_ratio) {
    p = std::abs(ratio) / std::log(std::sqrt(g.r21 * g.r32));
    g.converged = true;
  }
  for (int k = 0; order == OrderEstimate::celik && k < 200; ++k) {
    const double q = std::log((std::pow(g.r21, p) - s) / (std::pow(g.r32, p) - s));
    const double next = std::abs(ratio + q) / std::log(g.r21);
    g.converged = std::abs(next - p) <= 1e-12 * std::max(1.0, p);
    p = next;
    if (g.converged || !std::isfinite(p)) break;
  }
  if (!g.converged || !(p > 0)) return g;
  g.p = p;
  const double a21 = std::pow(g.r21, p), a32 = std::pow(g.r32, p);
  g.extrapolated = (a21 * phi[0] - phi[1]) / (a21 - 1);  // 4.
  g.e_ext21 = std::abs((g.extrapolated - phi[0]) / g.extrapolated);
  g.gci21 = 1.25 * g.e_a21 / (a21 - 1);  // 5.
  g.gci32 = 1.25 * std::abs(e32 / phi[1]) / (a32 - 1);
  g.asymptotic = g.gci32 / (a21 * g.gci21);
  return g;
}

}  // namespace auvloop::engine::validation
