// SPDX-License-Identifier: GPL-3.0-or-later
// The registry of validation cases and their pass criteria.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "auvloop/engine/validation.hpp"

namespace auvloop::engine::validation {

bool Result::pass() const {
  for (const auto& r : rows)
    if (!r.pass) return false;
  return !rows.empty();
}

namespace {
// The error of an observed order is its shortfall below the formal order: orders above it are
// normal before the asymptotic range when error terms of opposite sign partly cancel (the MMS
// case shows 2.2-2.35 in L2 from 8^3 to 32^3), while a first-order defect shows about 1.
Row order_row(std::string quantity, double order, double expected, double tolerance) {
  Row r{std::move(quantity), order, expected, std::max(0.0, expected - order), tolerance, false};
  r.pass = r.error <= tolerance;
  return r;
}

// Observed orders from successive halvings of h. A second-order scheme shows 2 asymptotically;
// a shortfall of 0.2 is allowed for the L2 norm (an order within 10 % of the formal order, as
// Roache 2002 accepts) and 0.3 for the maximum norm, which is set by a few cells next to the
// boundary and approaches its asymptote more slowly (measured 1.78, 1.99, 1.87, 1.98 for
// n = 8-12-16-24-32).
Result run_mms(bool quick) {
  Result res{"mms", {}, {}};
  const std::vector<int> sizes = quick ? std::vector<int>{8, 16} : std::vector<int>{8, 16, 32};
  std::vector<MmsError> e;
  for (int n : sizes) {
    e.push_back(mms_convection_diffusion(n));
    res.notes.push_back(fmt::format("{}^3 cells: L2 error {:.4e}, max error {:.4e}, {} iterations",
                                    n, e.back().l2, e.back().max, e.back().iterations));
  }
  const auto& a = e[e.size() - 2];
  const auto& b = e.back();
  const auto label = fmt::format("order {}->{}", a.n, b.n);
  res.rows.push_back(order_row("L2 " + label, std::log2(a.l2 / b.l2), 2.0, 0.2));
  res.rows.push_back(order_row("max " + label, std::log2(a.max / b.max), 2.0, 0.3));
  return res;
}

// BDF2 in time on the Taylor-Green vortex, observed from successive dt halvings on one grid.
// nu = 1 m^2/s to t = 1 s (Re = pi): the dt-dependent part of the error is then BDF2's. With
// little viscosity (nu = 0.1) the Rhie-Chow pressure smoothing, whose coefficient D = V / A
// shrinks with dt, leaves an O(h^2 dt) spatial part that masks the temporal order on coarse grids
// (docs/cfd.md, "Known limitations"). The full case starts at 20 steps: the unrelaxed outer
// loop diverged at 64^2 with dt = 0.1 s (diffusion number nu dt / h^2 = 41).
Result run_taylor_green(bool quick) {
  Result res{"taylor-green", {}, {}};
  const int n = quick ? 32 : 64;
  const std::vector<int> steps =
      quick ? std::vector<int>{10, 20, 40} : std::vector<int>{20, 40, 80, 160};
  std::vector<TaylorGreenRun> runs;
  for (int k : steps) {
    runs.push_back(taylor_green(n, k, 1.0, 1.0));
    res.notes.push_back(
        fmt::format("{}^2 cells, {} steps: L2 error vs exact {:.4e} m/s, up to {} "
                    "outer iterations",
                    n, k, runs.back().error_vs_exact, runs.back().max_outer));
  }
  const std::size_t m = runs.size();
  const double coarse = l2_difference(runs[m - 3], runs[m - 2]);
  const double fine = l2_difference(runs[m - 2], runs[m - 1]);
  res.rows.push_back(order_row(fmt::format("BDF2 order dt/{}->dt/{}", steps[m - 2], steps[m - 1]),
                               std::log2(coarse / fine), 2.0, 0.2));
  return res;
}

// Ghia's centreline profiles. The full case runs 33, 65 and 129 and judges 129 against the
// issue's criterion (2 % of the lid speed). The quick case runs one coarse grid against the
// deviation that the measured grid convergence gives there (docs/cfd.md, table "Lid-driven
// cavity"): Re = 100 converges to within 1 % already on 33 x 33 (0.38 %, 0.45 %, 0.50 % for u on
// 33, 65, 129: the remaining difference is Ghia's own error), so the 2 % criterion stands;
// Re = 1000 needs 65 x 65 for that (7.5 %, 1.8 %, see the table for 129).
Result run_cavity(double reynolds, bool quick) {
  Result res{reynolds < 500 ? "cavity-re100" : "cavity-re1000", {}, {}};
  std::vector<int> sizes{33, 65, 129};
  if (quick) sizes = {reynolds < 500 ? 33 : 65};
  CavityResult last;
  for (int n : sizes) {
    last = lid_driven_cavity(n, reynolds);
    res.notes.push_back(
        fmt::format("{0}x{0}: max |u - Ghia| {1:.4f}, max |v - Ghia| {2:.4f} "
                    "(lid speed 1), {3} steps to |du/dt| < 1e-5, {4:.1f} s",
                    n, last.max_deviation_u, last.max_deviation_v, last.steps, last.seconds));
  }
  for (auto [q, dev] :
       {std::pair{"u", last.max_deviation_u}, std::pair{"v", last.max_deviation_v}}) {
    Row r{fmt::format("max |{} - Ghia| {}x{}", q, last.n, last.n), dev, 0.0, dev, 0.02, false};
    r.pass = dev <= r.tolerance;
    res.rows.push_back(r);
  }
  return res;
}
}  // namespace

const std::vector<Case>& cases() {
  static const std::vector<Case> all{
      {"mms",
       "manufactured steady convection-diffusion on stretched, skewed hexahedra: observed order",
       run_mms},
      {"taylor-green", "2D Taylor-Green vortex: observed temporal order of BDF2 + PIMPLE",
       run_taylor_green},
      {"cavity-re100", "lid-driven cavity Re = 100 against Ghia et al. (1982)",
       [](bool quick) { return run_cavity(100, quick); }},
      {"cavity-re1000", "lid-driven cavity Re = 1000 against Ghia et al. (1982)",
       [](bool quick) { return run_cavity(1000, quick); }},
  };
  return all;
}

}  // namespace auvloop::engine::validation
