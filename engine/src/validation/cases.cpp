// SPDX-License-Identifier: GPL-3.0-or-later
// The registry of validation cases and their pass criteria.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>

#include <fmt/format.h>

#include "auvloop/engine/validation.hpp"
#include "rows.hpp"

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

// A published interval [lo, hi] (Schaefer and Turek 1996): the error is the distance outside it,
// so the row passes only inside the interval.
Row interval_row(std::string quantity, double value, double lo, double hi) {
  Row r{std::move(quantity),
        value,
        0.5 * (lo + hi),
        std::max({0.0, lo - value, value - hi}),
        0.0,
        false};
  r.pass = r.error <= 0.0;
  return r;
}

// The manufactured Navier-Stokes flow on the overset pair (mms_overset.cpp): the observed orders
// of |U| between successive levels against the bounds (>= 1.8 in L2, >= 1.5 in the
// maximum norm; full m = 16, 32, 64, quick 16, 32, whose orders are the full case's first pair),
// and mass conserved to the solver's tolerance on every level (the background is open: the
// balance acts). Held at nu = 0.001 m^2/s, where convection dominates the cells (cell Reynolds
// number about 10 at m = 32), as it does everywhere on the vehicle (hundreds and more): measured
// |U| L2 orders 2.06 and 2.09, max 1.65 and 2.53, p L2 2.02 and 1.86. Reported, not held: the
// same at nu = 0.01 (cell Reynolds number about 1), where the closed O-grid's pressure sits off
// its fringe by a first-order jump (D ~ h^2 / nu in the Rhie-Chow flux that returns the
// interpolated velocity's mismatch) and |U|'s L2 order falls to 1.6 from m = 32 to 64 (p 1.1):
// a known limitation of the coupling at cell Reynolds numbers of order one
// (docs/overset-flow.md, "Session 21").
Result run_mms_overset(bool quick) {
  Result res{"mms-overset", {}, {}};
  const std::vector<int> levels = quick ? std::vector<int>{16, 32} : std::vector<int>{16, 32, 64};
  for (const double nu : {0.001, 0.01}) {
    const bool held = nu == 0.001;
    std::vector<MmsOversetError> e;
    for (int m : levels) {
      e.push_back(mms_overset(m, nu));
      const auto& x = e.back();
      res.notes.push_back(fmt::format(
          "nu = {} m^2/s, m = {} ({} cells, {} active): |U| L2 {:.4e} max {:.4e} m/s, p L2 {:.4e} "
          "max {:.4e} m^2/s^2; {} pseudo-time steps{}, continuity {:.1e}, interface flux {:.1e} "
          "of the inflow, {:.1f} s",
          nu, m, x.cells, x.active_cells, x.l2_u, x.max_u, x.l2_p, x.max_p, x.iterations,
          x.converged ? "" : " (NOT converged)", x.continuity_error, x.interface_flux, x.seconds));
    }
    for (std::size_t i = 1; i < e.size(); ++i) {
      const auto& a = e[i - 1];
      const auto& b = e[i];
      const auto label = fmt::format("order m={}->{}", a.m, b.m);
      const double u_l2 = std::log2(a.l2_u / b.l2_u), u_max = std::log2(a.max_u / b.max_u);
      if (held) {
        res.rows.push_back(order_row(fmt::format("nu={} |U| L2 {}", nu, label), u_l2, 2.0, 0.2));
        res.rows.push_back(order_row(fmt::format("nu={} |U| max {}", nu, label), u_max, 2.0, 0.5));
      } else {
        res.notes.push_back(
            fmt::format("nu = {}: |U| {}: L2 {:.2f}, max {:.2f} (reported, not held: cell Re ~ 1)",
                        nu, label, u_l2, u_max));
      }
      res.notes.push_back(fmt::format("nu = {}: p {}: L2 {:.2f}, max {:.2f} (reported, not held)",
                                      nu, label, std::log2(a.l2_p / b.l2_p),
                                      std::log2(a.max_p / b.max_p)));
    }
    for (const auto& x : e) {
      const auto level = fmt::format("nu={} m={}", nu, x.m);
      res.rows.push_back(Row{level + " converged", x.converged ? 1.0 : 0.0, 1.0,
                             x.converged ? 0.0 : 1.0, 0.0, x.converged});
      res.rows.push_back(bound_row("interface flux " + level, x.interface_flux, 1e-8));
      res.rows.push_back(bound_row("continuity error " + level, x.continuity_error, 1e-8));
    }
  }
  return res;
}

// Relative deviation from the midpoint of a published interval, for the coarse CI grids: the
// tolerance is what the grid study (docs/cfd.md, "Schaefer-Turek") measured at that resolution,
// with the deviation shrinking on the finer grids.
Row relative_row(std::string quantity, double value, double lo, double hi, double tolerance) {
  const double mid = 0.5 * (lo + hi);
  Row r{std::move(quantity), value, mid, std::abs(value - mid) / mid, tolerance, false};
  r.pass = r.error <= tolerance;
  return r;
}

// Richardson extrapolation (Roache 2002) from grids with m[0] < m[1] < m[2] cells per side
// (h ~ 1 / m): the observed order p solves (f0 - f1) / (f1 - f2) = (h0^p - h1^p) / (h1^p - h2^p);
// the grid-converged estimate is f2 + (f2 - f1) h2^p / (h1^p - h2^p). Only for monotone
// convergence with 0.5 <= p <= 4; otherwise the finest value stands (order reported as 0).
struct Extrapolated {
  double value = 0, order = 0;
};
Extrapolated richardson(const std::array<double, 3>& m, const std::array<double, 3>& f) {
  const double d01 = f[0] - f[1], d12 = f[1] - f[2];
  if (d01 * d12 <= 0 || std::abs(d12) >= std::abs(d01)) return {f[2], 0.0};
  auto ratio = [&](double p) {
    const double h0 = std::pow(m[0], -p), h1 = std::pow(m[1], -p), h2 = std::pow(m[2], -p);
    return (h0 - h1) / (h1 - h2);
  };
  double lo = 0.05, hi = 8;  // ratio(p) increases with p
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ratio(mid) < d01 / d12 ? lo : hi) = mid;
  }
  const double p = 0.5 * (lo + hi);
  if (p < 0.5 || p > 4) return {f[2], 0.0};
  const double h1 = std::pow(m[1], -p), h2 = std::pow(m[2], -p);
  return {f[2] - d12 * h2 / (h1 - h2), p};
}

// The 2D-1 grid: the steady Re = 20 flow needs neither the wall layer nor the wake of 2D-2's
// grid (m / 2 radial cells graded 4 : 1, 2 m downstream; 2,104 / 4,692 / 8,416 cells for
// m = 16 / 24 / 32).
ChannelGrid steady_grid(int m) {
  return {.m = m, .radial_cells_per_side = 0.5, .radial_ratio = 4, .downstream_cells_per_side = 2};
}

// Schaefer-Turek 2D-1 (Re = 20, steady). Full: m = 16, 24, 32 and each quantity's Richardson
// estimate against the published interval. Quick: m = 16 alone; cD, cL and L_a inside their
// intervals there already, dp within 0.5 % of the interval's midpoint (measured 0.28 % low; it
// converges into the interval with refinement: docs/cfd.md).
Result run_schaefer_turek_2d1(bool quick, bool overset) {
  Result res{overset ? "schaefer-turek-2d1-overset" : "schaefer-turek-2d1", {}, {}};
  const std::vector<int> grids = quick ? std::vector<int>{16} : std::vector<int>{16, 24, 32};
  std::vector<CylinderResult> r;
  for (int m : grids) {
    r.push_back(schaefer_turek_2d1(steady_grid(m), 0.008, overset));
    const auto& x = r.back();
    res.notes.push_back(fmt::format(
        "m = {} ({} cells{}): cD {:.4f}, cL {:.5f}, dp {:.5f} Pa, L_a {:.5f} m; {} pseudo-time "
        "steps to max |du/dt| < 1e-6 1/s, {:.1f} s",
        m, x.cells, overset ? fmt::format(", {} active", x.active_cells) : "", x.cd, x.cl, x.dp,
        x.la, x.steps, x.seconds));
    if (overset)
      res.notes.push_back(fmt::format(
          "m = {}: continuity error over the active cells {:.2e}, interface flux {:.2e} of the "
          "inflow",
          m, x.continuity_error, x.interface_flux));
  }
  // Overset: mass conserved to the solver's tolerance on every level (overset_mass.cpp; the
  // interface flux is 2.6e-3 of the inflow without the balance).
  if (overset)
    for (std::size_t k = 0; k < r.size(); ++k) {
      res.rows.push_back(
          bound_row(fmt::format("interface flux m={}", grids[k]), r[k].interface_flux, 1e-8));
      res.rows.push_back(
          bound_row(fmt::format("continuity error m={}", grids[k]), r[k].continuity_error, 1e-10));
    }
  if (quick && overset) {
    // The overset m = 16 pair is coarser than the single grid where it counts (the background
    // is uniform at the O-grid's outer cell size): a regression check of the present scheme,
    // measured 0.14 %, 11.5 %, 0.88 % and 4.4 % from the midpoints since the mass balance runs in
    // every non-orthogonal corrector (0.74 %, 12.9 %, 1.4 % and 2.8 % before, from fringe
    // pressures the balance had moved: docs/overset-flow.md, "Session 20"). The full study
    // misses dp by 0.1 % and L_a by 0.8 % since (not understood yet; docs/overset-flow.md).
    const auto& q = r.front();
    res.rows.push_back(relative_row("cD m=16 (rel. to midpoint)", q.cd, 5.57, 5.59, 0.01));
    res.rows.push_back(relative_row("cL m=16 (rel. to midpoint)", q.cl, 0.0104, 0.0110, 0.15));
    res.rows.push_back(relative_row("dp m=16 (rel. to midpoint)", q.dp, 0.1172, 0.1176, 0.02));
    res.rows.push_back(relative_row("L_a m=16 (rel. to midpoint)", q.la, 0.0842, 0.0852, 0.05));
    return res;
  }
  if (quick) {
    const auto& q = r.front();
    res.rows.push_back(interval_row("cD m=16", q.cd, 5.57, 5.59));
    res.rows.push_back(interval_row("cL m=16", q.cl, 0.0104, 0.0110));
    res.rows.push_back(relative_row("dp m=16 (rel. to midpoint)", q.dp, 0.1172, 0.1176, 0.005));
    res.rows.push_back(interval_row("L_a m=16", q.la, 0.0842, 0.0852));
    return res;
  }
  const std::array<double, 3> m{16, 24, 32};
  auto add = [&](const char* name, double CylinderResult::*field, double lo, double hi) {
    const auto e = richardson(m, {r[0].*field, r[1].*field, r[2].*field});
    res.notes.push_back(
        fmt::format("{}: observed order {:.2f}, estimate {:.5f}", name, e.order, e.value));
    res.rows.push_back(
        interval_row(fmt::format("{} (Richardson 16-24-32)", name), e.value, lo, hi));
  };
  add("cD", &CylinderResult::cd, 5.57, 5.59);
  add("cL", &CylinderResult::cl, 0.0104, 0.0110);
  add("dp (Pa)", &CylinderResult::dp, 0.1172, 0.1176);
  add("L_a (m)", &CylinderResult::la, 0.0842, 0.0852);
  return res;
}

// Schaefer-Turek 2D-2 (Re = 100, periodic): from rest with a 0.2 s spin of the cylinder to start
// the shedding, to t = 4 s, measured over the last three periods of cL, on the default
// ChannelGrid (wall layer and near wake resolved). Full: m = 32 (14,688 cells), dt = 0.002 s
// (about 170 steps per period) against the published intervals. Quick: m = 16, dt = 0.005 s:
// shedding settles (the last three periods within 1 % of the three before); St, cD max and
// cL max within 4 %, 2 % and 15 % of the intervals' midpoints (measured 3.2 %, 1.4 % and 12.4 %
// low there; all three converge into their intervals from below: docs/cfd.md).
// Overset: the same on cylinder_overset_spec's pair. The background resolves the wake: quick,
// 7.4 mm (the full O-grid's outer cell size; the m = 16 O-grid's own 14.7 mm, 3,768 cells, left
// St, cD max and cL max 3.2 %, 2.3 % and 27 % low; with 7.4 mm, 8,416 cells: 0.2 % low, 1.2 %
// and 0.2 % high); full, 3.7 mm (m = 32: cL max 0.941 on 7.4 mm, 0.983 on 4.9 mm, 0.9978 on
// 3.7 mm, 33,400 cells, St and cD max inside the intervals on all three: docs/overset-flow.md).
// Mass is conserved to the solver's tolerance in every step, the impulsive start included: the
// interface flux at most 1e-6 of the inflow (without the balance 0.97 of it leaves through the
// fringe in the first step, 0.80 in the fifth), the continuity error at most 1e-7, an order above
// the pressure solver's relative tolerance (1e-8): the first step's right side is the whole flow
// (measured 1.3e-8 there, 2e-11 once shedding). The quick bounds are the single grid's.
Result run_schaefer_turek_2d2(bool quick, bool overset) {
  Result res{overset ? "schaefer-turek-2d2-overset" : "schaefer-turek-2d2", {}, {}};
  const int m = quick ? 16 : 32;
  SheddingCase c;
  c.grid.m = m;
  c.dt = quick ? 0.005 : 0.002;
  c.overset = overset;
  if (overset) c.grid.background_spacing = 2 * std::numbers::pi * 0.15 / (quick ? 128 : 256);
  const auto r = schaefer_turek_2d2(c);
  res.notes.push_back(fmt::format(
      "m = {} ({} cells{}), {} steps to t = 4 s, max Courant {:.2f}: St {:.4f}, cD max {:.4f}, "
      "cL max {:.4f} over the last {} periods (period drift {:.2e}), {:.1f} s",
      m, r.cells, overset ? fmt::format(", {} active", r.active_cells) : "", r.steps, r.max_courant,
      r.strouhal, r.cd_max, r.cl_max, r.periods, r.period_drift, r.seconds));
  Row settled{"period drift (shedding settled)", r.period_drift, 0.0, r.period_drift, 0.01, false};
  settled.pass = r.periods > 0 && r.period_drift <= settled.tolerance;
  res.rows.push_back(settled);
  if (overset) {
    res.notes.push_back(fmt::format(
        "largest continuity error of a step {:.2e}, largest interface flux {:.2e} of the inflow",
        r.max_continuity, r.max_interface_flux));
    res.rows.push_back(bound_row("max interface flux / inflow", r.max_interface_flux, 1e-6));
    res.rows.push_back(bound_row("max continuity error per step", r.max_continuity, 1e-7));
  }
  if (quick) {
    res.rows.push_back(relative_row("St m=16 (rel. to midpoint)", r.strouhal, 0.295, 0.305, 0.04));
    res.rows.push_back(relative_row("cD max m=16 (rel. to midpoint)", r.cd_max, 3.22, 3.24, 0.02));
    res.rows.push_back(relative_row("cL max m=16 (rel. to midpoint)", r.cl_max, 0.99, 1.01, 0.15));
    return res;
  }
  res.rows.push_back(interval_row("St", r.strouhal, 0.295, 0.305));
  res.rows.push_back(interval_row("cD max", r.cd_max, 3.22, 3.24));
  res.rows.push_back(interval_row("cL max", r.cl_max, 0.99, 1.01));
  return res;
}
// A steady run that reached its stopping test (a row, so that a run that did not fails).
Row converged_row(const std::string& grid, const FlatPlateResult& x) {
  return Row{grid + " converged", x.converged ? 1.0 : 0.0, 1.0, x.converged ? 0.0 : 1.0, 0.0,
             x.converged};
}

// The free stream's omega and k against their analytic decay (flat_plate.cpp, step 4). The
// error is first order in the outlet cell's streamwise size dx (largest there): measured e / dx
// = 0.20 / m for omega and 0.23 / m for k on levels 2 and 1 and on the wall-function grids
// (outlet cells 0.16, 0.082 and 0.095 m), so each grid is held to 0.25 dx / m; a free stream
// left frozen by the linear solves is off by 30 % (level 1, before the SST solves' row scaling).
void freestream_rows(Result& res, const std::string& grid, const FlatPlateResult& x) {
  const double tolerance = 0.25 * x.outlet_dx;  // dx in metres
  for (auto [name, e] :
       {std::pair{"omega", x.freestream_omega_error}, std::pair{"k", x.freestream_k_error}}) {
    Row row{fmt::format("free-stream {} {} vs decay", name, grid), e, 0.0, e, tolerance, false};
    row.pass = e <= tolerance;
    res.rows.push_back(row);
  }
}

// NASA TMR 2DZP with SST k-omega (validation-data.md, section 4) with the TMR's wall values
// (k = 0, omega_w = 60 nu / (beta1 d1^2): WallTreatment::resolved), solved steady on the
// mesher::flat_plate family. Quick: level 2 (3,840 cells, first cell y+ about 0.4) against
// CFL3D on the TMR's coarsest grid (3,264 cells), within 2 % (measured 1.2 % and 1.0 % high:
// the two grids stretch differently). Full: levels 2, 1, 0, each started from the one before
// (grid sequencing), with the observed order, the finest against CFL3D's finest (545 x 385),
// Cf(0.97) within 1 % and CD within 1.5 % (issue 16).
Result run_flat_plate_sst(bool quick) {
  Result res{"flat-plate-sst", {}, {}};
  const std::vector<int> levels = quick ? std::vector<int>{2} : std::vector<int>{2, 1, 0};
  std::vector<FlatPlateResult> r;
  r.reserve(levels.size());
  for (int level : levels) {
    FlatPlateCase c;
    c.level = level;
    c.wall = turbulence::WallTreatment::resolved;  // the TMR's wall values (validation-data.md)
    if (!r.empty()) c.start = &r.back();           // grid sequencing: from the coarser level
    r.push_back(flat_plate_sst(c));
    const auto& x = r.back();
    res.notes.push_back(fmt::format(
        "level {} ({} cells): Cf(0.97) {:.6f}, CD {:.6f}, plate y+ {:.3g}-{:.3g}, {} SIMPLE "
        "iterations{}, {} cells bounded, {:.1f} s",
        level, x.cells, x.cf_097, x.cd, x.y_plus.min, x.y_plus.max, x.iterations,
        x.converged ? "" : " (NOT converged)", x.bounded_cells, x.seconds));
    res.rows.push_back(converged_row(fmt::format("level {}", level), x));
    freestream_rows(res, fmt::format("level {}", level), x);
  }
  if (quick) {
    res.rows.push_back(
        relative_to("Cf(0.97) level 2 vs CFL3D 3,264 cells", r[0].cf_097, 0.00262625, 0.02));
    res.rows.push_back(relative_to("CD level 2 vs CFL3D 3,264 cells", r[0].cd, 0.00278507, 0.02));
    return res;
  }
  const auto& fine = r.back();
  for (auto [name, f] :
       {std::pair{"Cf(0.97)", &FlatPlateResult::cf_097}, std::pair{"CD", &FlatPlateResult::cd}}) {
    const double a = r[0].*f, b = r[1].*f, c = r[2].*f;
    const double order = (a - b) * (b - c) > 0 ? std::log2((a - b) / (b - c)) : 0.0;
    res.notes.push_back(fmt::format("{}: observed order {:.2f} (levels 2-1-0)", name, order));
  }
  res.rows.push_back(
      relative_to("Cf(0.97) finest vs CFL3D 545x385", fine.cf_097, 0.00269085, 0.01));
  res.rows.push_back(relative_to("CD finest vs CFL3D 545x385", fine.cd, 0.00285332, 0.015));
  return res;
}

// The same plate on grids whose first cell sits at y+ of about 1, 5, 30 and 100 at x = 0.97
// (128 cells along the plate, 32 ahead of it, 64 or 48 wall-normal; the first height H sets y+),
// with the any-y+ wall treatment: Cf(0.97) and CD against the converged y+ < 1 value (CFL3D on
// the TMR's finest grid), within 3 % (6 % at y+ 5, the buffer layer; issue 16). Quick: the y+ 1
// and y+ 30 grids (the sublayer and the log-layer ends of the treatment), the same tolerances.
Result run_flat_plate_wall_functions(bool quick) {
  Result res{"flat-plate-wall-functions", {}, {}};
  struct Grid {
    double y_plus, first_height;
    int normal_cells;
    double tolerance;
  };
  std::vector<Grid> grids{{1, 1.1e-5, 64, 0.03},
                          {5, 5.5e-5, 64, 0.06},
                          {30, 3.3e-4, 48, 0.03},
                          {100, 1.1e-3, 48, 0.03}};
  if (quick) grids = {grids[0], grids[2]};
  for (const auto& g : grids) {
    FlatPlateCase c;
    c.level = 0;
    c.spec.plate_cells = 128;
    c.spec.upstream_cells = 32;
    c.spec.normal_cells = g.normal_cells;
    c.spec.first_height = g.first_height;
    c.wall = turbulence::WallTreatment::any_y_plus;
    const auto x = flat_plate_sst(c);
    res.notes.push_back(fmt::format(
        "y+ {:g} grid ({} cells, first height {:g} m): Cf(0.97) {:.6f}, CD {:.6f}, plate y+ "
        "{:.3g}-{:.3g} (mean {:.3g}), {} SIMPLE iterations{}, {:.1f} s",
        g.y_plus, x.cells, g.first_height, x.cf_097, x.cd, x.y_plus.min, x.y_plus.max,
        x.y_plus.mean, x.iterations, x.converged ? "" : " (NOT converged)", x.seconds));
    res.rows.push_back(converged_row(fmt::format("y+ {:g}", g.y_plus), x));
    freestream_rows(res, fmt::format("y+ {:g}", g.y_plus), x);
    for (auto [name, v, ref] :
         {std::tuple{"Cf(0.97)", x.cf_097, 0.00269085}, std::tuple{"CD", x.cd, 0.00285332}}) {
      res.rows.push_back(relative_to(fmt::format("{} y+ {:g} vs CFL3D 545x385", name, g.y_plus), v,
                                     ref, g.tolerance));
    }
  }
  return res;
}
// rotating-frame-at-rest: quick m = 16, 40 steps of 5 ms (5.7 degrees); full m = 32, 600 steps
// (86 degrees). The largest |u| against the largest grid speed, and |p| against the
// grid speed squared, within 1e-12: the exact solution is zero, so anything the discretisation
// of the moving grids, its far field or the overset coupling got wrong would show.
Result run_rotating_frame_at_rest(bool quick) {
  Result res{"rotating-frame-at-rest", {}, {}};
  const int m = quick ? 16 : 32;
  const double rate = 0.5, dt = 0.005;
  const auto r = rotating_frame_at_rest(steady_grid(m), rate, dt, quick ? 40 : 600);
  res.notes.push_back(fmt::format(
      "m = {} ({} cells, {} active): {} steps of {} s at {} rad/s ({:.1f} degrees), largest grid "
      "speed {:.3f} m/s, max Courant {:.2f}; max |u| {:.3g} m/s, max |p| {:.3g} m^2/s^2, "
      "continuity {:.3g}; {:.1f} s",
      m, r.cells, r.active_cells, r.steps, dt, rate, r.turned * 180 / std::numbers::pi,
      r.max_grid_speed, r.max_courant, r.max_u, r.max_p, r.continuity_error, r.seconds));
  res.rows.push_back(bound_row("max |u| / max |w|", r.max_u / r.max_grid_speed, 1e-12));
  res.rows.push_back(
      bound_row("max |p| / max |w|^2", r.max_p / std::pow(r.max_grid_speed, 2), 1e-12));
  return res;
}
// The unconfined cylinder's grid of galilean-cylinder and released-cylinder: the default (64
// cells round, a box 40 D across), or the quick cases' coarse one (32 round, 16 out, 30 D).
mesher::UnconfinedCylinderSpec unconfined_grid(bool quick) {
  mesher::UnconfinedCylinderSpec g;
  if (quick) {
    g.around = 32;
    g.radial_cells = 16;
    g.extent = 30;
  }
  return g;
}
// galilean-cylinder: the unconfined cylinder at Re = 100 fixed in the stream and towed through
// fluid at rest. Full (validation-data.md section 3): the default grid (64 cells round, a box
// 40 D across), dt = 0.02 s to 150 s, the last 5 periods: St, mean cD and the cL amplitude of
// the fixed cylinder inside the published ranges, and each of the towed cylinder's within 0.5 %
// of the fixed one's (the bound). Quick: a coarse grid (32 round, 30 D) to 4 s, before
// the shedding: the towed cD and cL histories against the fixed ones, within 0.5 % of the
// largest |cD| at every step.
Result run_galilean_cylinder(bool quick) {
  Result res{"galilean-cylinder", {}, {}};
  const auto g = unconfined_grid(quick);
  double dt = 0.02, end = 150;
  if (quick) {
    dt = 0.04;
    end = 4;
  }
  const int periods = 5;
  const auto fixed = unconfined_cylinder(g, false, dt, end, periods);
  const auto towed = unconfined_cylinder(g, true, dt, end, periods);
  for (const auto* r : {&fixed, &towed})
    res.notes.push_back(fmt::format(
        "{}: {} cells ({} active), {} steps of {} s, max Courant {:.2f}; St {:.4f}, mean cD "
        "{:.4f}, cL amplitude {:.4f} over {} periods (period drift {:.1e}); {:.1f} s",
        r == &fixed ? "fixed in the stream" : "towed through fluid at rest", r->cells,
        r->active_cells, r->steps, dt, r->max_courant, r->strouhal, r->cd_mean, r->cl_amplitude,
        r->periods, r->period_drift, r->seconds));
  if (quick) {
    double scale = 0, d = 0;
    for (std::size_t i = 0; i < fixed.cd.size() && i < towed.cd.size(); ++i) {
      scale = std::max(scale, std::abs(fixed.cd[i]));
      d = std::max({d, std::abs(fixed.cd[i] - towed.cd[i]), std::abs(fixed.cl[i] - towed.cl[i])});
    }
    res.rows.push_back(bound_row("max |towed - fixed| cD, cL / max |cD|", d / scale, 0.005));
    return res;
  }
  res.rows.push_back(interval_row("St (fixed)", fixed.strouhal, 0.164, 0.165));
  res.rows.push_back(interval_row("mean cD (fixed)", fixed.cd_mean, 1.33, 1.35));
  res.rows.push_back(interval_row("cL amplitude (fixed)", fixed.cl_amplitude, 0.33, 0.339));
  for (auto [name, a, b] : {std::tuple{"St", towed.strouhal, fixed.strouhal},
                            std::tuple{"mean cD", towed.cd_mean, fixed.cd_mean},
                            std::tuple{"cL amplitude", towed.cl_amplitude, fixed.cl_amplitude}}) {
    res.rows.push_back(relative_to(fmt::format("{} towed vs fixed", name), a, b, 0.005));
  }
  return res;
}
// released-cylinder: the cylinder, half as heavy as the water it displaces (so that the added
// mass is twice its own: the coupling's hard case, REMUS in sway), released from rest under a
// constant force in water at rest, nu = 1e-5 m^2/s (the boundary layer's share of the force,
// about 2 sqrt(nu t) / R, below 0.3 % over the run): its acceleration against potential flow's
// F / (m + rho pi R^2), every step after the first. Two couplings: the added-mass estimate of
// potential flow unrelaxed, and no estimate with the acceleration relaxed by 0.5 (within the
// bound 2 m / (m + m_a) = 2/3 of dfbi.hpp). Quick: the galilean case's coarse grid (32 round,
// 30 D box), 10 steps of 10 ms; full: its default grid (64 round, 40 D), 20 steps of 5 ms.
Result run_released_cylinder(bool quick) {
  Result res{"released-cylinder", {}, {}};
  const auto g = unconfined_grid(quick);
  double dt = 0.005;
  int steps = 20;
  if (quick) {
    dt = 0.01;
    steps = 10;
  }
  const double tolerance = quick ? 0.02 : 0.01;
  for (auto [estimate, relax] : {std::pair{1.0, 1.0}, std::pair{0.0, 0.5}}) {
    const auto r = released_cylinder(g, 0.5, estimate, relax, 1e-5, dt, steps, 5);
    std::string history;
    double worst = 0, residual = 0;
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      history += fmt::format("{}{:.4f}", i == 0 ? "" : " ", r.acceleration[i]);
      if (i == 0) continue;  // the first step's predictor starts from rest
      worst = std::max(worst, std::abs(r.acceleration[i] - 1.0));
      residual = std::max(residual, r.change[i]);
    }
    const auto label = fmt::format("estimate {:g} m_a, relax {:g}", estimate, relax);
    res.notes.push_back(fmt::format(
        "{}: {} cells, {} steps of {} s; u' (m/s^2, potential flow 1) {}; u at the end {:.5f} "
        "m/s; largest last correction {:.2e} m/s^2; {:.1f} s",
        label, r.cells, r.steps, dt, history, r.u.back(), residual, r.seconds));
    res.rows.push_back(
        bound_row(fmt::format("|u' - potential flow|, {}", label), worst, tolerance));
    res.rows.push_back(bound_row(fmt::format("coupling residual / u', {}", label), residual, 0.01));
  }
  return res;
}
// pitching-foil: the NACA 0012 at Re = 1000 pitching by 5 degrees about its quarter chord at a
// reduced frequency k = omega c / 2 U = 1, its O-grid turning over the background against the
// single grid turning as a whole. Full: the default grids (48 cells per side, 32 out to one
// chord), 200 steps a period, three periods; the cL and cM histories of the last period agree
// within 2 % of the single grid's amplitude (the bound). Quick: the same grids, 100 steps
// a period, one period, its second half compared (docs/overset-flow.md, "Pitching foil").
Result run_pitching_foil(bool quick) {
  Result res{"pitching-foil", {}, {}};
  // The O-grid out to 1.5 chords about the pivot (the quarter chord), so that the background's
  // hole edge (about 1.1 chords out) passes half a chord behind the trailing edge, not through
  // the near wake beside it as with a circle of one chord (docs/overset-flow.md, "Pitching
  // foil"); the background's core cells the O-grid's tangential size there.
  mesher::FoilOversetSpec g;
  g.outer_radius = 1.5;
  g.normal_cells = 40;
  g.core_upstream = g.core_side = 1.9;
  g.core_downstream = 3.3;
  g.spacing = 0.056;
  const double amplitude = 5 * std::numbers::pi / 180, omega = 2.0;
  const double period = 2 * std::numbers::pi / omega;
  int per_period = 200;
  double end = 3 * period, from = 2 * period;
  if (quick) {
    per_period = 100;
    end = period;
    from = 0.5 * period;
  }
  const double dt = period / per_period;
  const auto single = pitching_foil(g, false, amplitude, omega, dt, end);
  const auto overset = pitching_foil(g, true, amplitude, omega, dt, end);
  for (const auto* r : {&single, &overset})
    res.notes.push_back(fmt::format(
        "{}: {} cells, {} steps of {:.4g} s, max Courant {:.2f}, continuity {:.2g}{}; {:.1f} s",
        r == &single ? "single grid turning as a whole" : "O-grid turning over the background",
        r->cells, r->steps, dt, r->max_courant, r->continuity_error,
        r == &overset ? fmt::format(", {} cells out of a hole, re-assembly {:.1f} s", r->came_out,
                                    r->assembly_seconds)
                      : "",
        r->seconds));
  for (auto [name, a, b] :
       {std::tuple{"cL", &overset.cl, &single.cl}, std::tuple{"cM", &overset.cm, &single.cm}}) {
    double lo = 1e300, hi = -1e300, d = 0;
    for (std::size_t i = 0; i < single.t.size() && i < overset.t.size(); ++i) {
      if (single.t[i] < from - 1e-9) continue;
      lo = std::min(lo, (*b)[i]);
      hi = std::max(hi, (*b)[i]);
      d = std::max(d, std::abs((*a)[i] - (*b)[i]));
    }
    const double amp = 0.5 * (hi - lo);
    res.notes.push_back(
        fmt::format("{} from t = {:.3g} s: single grid between {:.4f} and {:.4f} "
                    "(amplitude {:.4f}), largest difference {:.2e}",
                    name, from, lo, hi, amp, d));
    res.rows.push_back(
        bound_row(fmt::format("max |overset - single| {} / amplitude", name), d / amp, 0.02));
  }
  return res;
}
// remus-overset: the REMUS coarse system (issue 17's acceptance run): the body at 1.54 m/s
// (Prestero's trial point) from an impulsive start, straight with the fins at rest, then every
// fin turning at 30 deg/s for 1 s. Full: 2 s straight (about 2.3 hull lengths, for the laminar
// boundary layers to settle: the hull's drag then changes by less than 1 % over its last 0.2 s),
// then 1 s turning. Quick: 10 steps straight and 20 turning. Every step conserves mass to the
// solver's tolerance (continuity over the active cells, interface flux against the volume the
// hull sweeps); the run completes (no divergence, no orphan in any update).
// remus-overset-sst: the same with SST k-omega (k and omega on the coupling, the composite's
// wall distances followed as the fins turn), as the CFD plant runs it: U by linear upwind with
// Barth-Jespersen's limiter (upwind triples the hull's pressure drag: docs/overset-flow.md,
// "Session 23"), the ambient sources that keep the free stream from decaying in the water at
// rest (without them the boundary layer relaminarises at 0.45 s), k and omega by BiCGSTAB with
// Gauss-Seidel sweeps (the Jacobi one broke down there); the hull's y+ and drag reported.
// actuator-disk: the propeller's disk in a uniform stream (actuator_disk.cpp). The row held is
// the mid-plane's flux speed against annular momentum theory, within 5 %: the theory takes each
// annulus alone (no radial pressure coupling between them) and the disk two cells thick, errors
// of a few per cent at this loading (a = 0.05); the disk cells' own mean velocity (OpenFOAM's
// propellerDisk reads it) is reported, not held: beside a force concentrated in two cells a
// collocated solver's cell velocities differ from the face fluxes (Rhie-Chow), 13 % too much
// induction on the quick grid, which is why the CFD plant takes J from a plane upstream.
Result run_actuator_disk(bool quick) {
  Result res{"actuator-disk", {}, {}};
  ActuatorDiskCase c;
  c.cell = quick ? 0.014 : 0.007;  // R / 5, R / 10
  const auto r = actuator_disk(c);
  const double theory = r.theory_speed - c.speed;
  res.notes.push_back(fmt::format(
      "{} cells ({} in the disk, core cubes of {} m), U {} m/s, T {:.4g} m^4/s^2 (3.86 N), {} "
      "SIMPLE iterations (last change {:.1e} m/s), {:.0f} s",
      r.cells, r.disk_cells, c.cell, c.speed, c.thrust, r.iterations, r.last_change, r.seconds));
  res.notes.push_back(fmt::format(
      "induced speed at the disk (m/s): mid-plane flux {:.5f}, disk cells' mean {:.5f} (not "
      "held), annular momentum theory {:.5f}, the light-loading T / (2 u_d A) {:.5f}",
      r.face_speed - c.speed, r.disk_speed - c.speed, theory, r.light_loading_induction));
  Row row{"induced speed, mid-plane flux / theory",
          (r.face_speed - c.speed) / theory,
          1.0,
          0.0,
          0.05,
          false};
  row.error = std::abs(row.value - 1);
  row.pass = row.error <= row.tolerance;  // NaN fails
  res.rows.push_back(row);
  res.rows.push_back(
      bound_row("SIMPLE not converged (last change / U)", r.last_change / c.speed, 1e-8));
  return res;
}

Result run_remus_overset(bool quick, bool sst) {
  Result res{sst ? "remus-overset-sst" : "remus-overset", {}, {}};
  constexpr double kSpeed = 1.54, kDt = 2e-3;
  const double rate = 30 * std::numbers::pi / 180;
  const double straight = quick ? 10 * kDt : 2.0, turning = quick ? 20 * kDt : 1.0;
  RemusOversetRun run;
  run.speed = kSpeed;
  run.dt = kDt;
  run.straight = straight;
  run.turning = turning;
  run.fin_rate = rate;
  run.sst = sst;
  if (sst) {
    run.convection = fv::Convection::linear_upwind_limited;
    run.ambient_sources = true;
    run.turbulence_solver = fv::AsymmetricMethod::bicgstab_gs;
  }
  const auto r = remus_overset(run);
  const double swept = kSpeed * std::numbers::pi * 0.25 * 0.19 * 0.19;  // m^3/s, REMUS D = 0.19 m
  res.notes.push_back(fmt::format(
      "coarse: {} cells, {} of {} steps of {} s ({} s straight, {} s with the fins turning at 30 "
      "deg/s), max Courant {:.1f}, {} status changes ({} cells out of a hole); {:.0f} s, "
      "re-assembly {:.1f} s",
      r.cells, r.steps, r.planned_steps, kDt, straight, turning, r.max_courant, r.status_changes,
      r.uncovered_cells, r.seconds, r.assembly_seconds));
  if (!r.failure.empty()) res.notes.push_back("failed: " + r.failure);
  if (sst)
    res.notes.push_back(fmt::format("hull y+ at the end: mean {:.1f}, max {:.1f}",
                                    r.hull_y_plus_mean, r.hull_y_plus_max));
  res.rows.push_back(bound_row("steps not completed / planned",
                               1.0 - static_cast<double>(r.steps) / r.planned_steps, 0.0));
  res.rows.push_back(bound_row("max continuity error per step", r.max_continuity, 1e-10));
  res.rows.push_back(
      bound_row("max interface flux / swept volume flux", r.max_interface_flux / swept, 1e-6));
  // SST's health: the bound (k_min, omega_min) should act rarely (sst_model.hpp). In session 26
  // the straight run's bounded cells grew from 48 at 0.05 s (a ring of cells round the axis
  // ahead of the nose) to 490 at 1.19 s, and at 1.2 s omega collapsed to its floor in the first
  // cells of the hull's rear half and 38,000 cells were bounded a step, the shear drag falling by
  // a third: a run that passed on its figures of mass. (Two positivity traps, mended in session
  // 27: turbulence/positivity.hpp.)
  if (sst)
    res.rows.push_back(bound_row("max cells bounded in a step / cells",
                                 static_cast<double>(r.max_bounded_cells) / r.cells, 0.01));
  const auto straight_steps = static_cast<std::size_t>(std::lround(straight / kDt));
  if (!quick && r.drag.size() >= straight_steps) {
    const double end = r.drag[straight_steps - 1];
    const double before = r.drag[straight_steps - 1 - static_cast<std::size_t>(0.2 / kDt)];
    const double pressure = r.drag_pressure[straight_steps - 1];
    res.notes.push_back(fmt::format(
        "hull drag (per unit density) at t = {:.2f} s: {:.5g} m^4/s^2 (pressure {:.4g}, shear "
        "{:.4g}; {:.2f} N in sea water), 0.2 s before: {:.5g}",
        straight, end, pressure, end - pressure, 1025 * end, before));
    // Its history (whether the straight run's flow is steady by its end or still moving), and
    // the range over the last 0.5 s.
    std::string history;
    const auto quarter = static_cast<std::size_t>(std::lround(0.25 / kDt));
    for (std::size_t k = 1; k * quarter <= straight_steps; ++k) {
      const auto i = k * quarter - 1;
      history += fmt::format("{}{:.2f} s {:.5g}", history.empty() ? "" : ", ",
                             static_cast<double>(i + 1) * kDt, r.drag[i]);
    }
    const auto last = straight_steps - 2 * quarter;
    const auto [lo, hi] =
        std::minmax_element(r.drag.begin() + static_cast<std::ptrdiff_t>(last),
                            r.drag.begin() + static_cast<std::ptrdiff_t>(straight_steps));
    res.notes.push_back(fmt::format(
        "hull drag every 0.25 s of the straight run: {}; over its last 0.5 s {:.5g} to {:.5g}",
        history, *lo, *hi));
    res.rows.push_back(bound_row("hull drag change over the straight run's last 0.2 s",
                                 std::abs(end / before - 1), 0.01));
  }
  return res;
}
}  // namespace

const std::vector<Case>& cases() {
  static const std::vector<Case> all{
      {"mms",
       "manufactured steady convection-diffusion on stretched, skewed hexahedra: observed order",
       run_mms},
      {"mms-overset",
       "manufactured steady Navier-Stokes on an overset pair of stretched, skewed grids: observed "
       "order of U and p",
       run_mms_overset},
      {"taylor-green", "2D Taylor-Green vortex: observed temporal order of BDF2 + PIMPLE",
       run_taylor_green},
      {"cavity-re100", "lid-driven cavity Re = 100 against Ghia et al. (1982)",
       [](bool quick) { return run_cavity(100, quick); }},
      {"cavity-re1000", "lid-driven cavity Re = 1000 against Ghia et al. (1982)",
       [](bool quick) { return run_cavity(1000, quick); }},
      {"schaefer-turek-2d1",
       "cylinder in a channel, Re = 20 steady: cD, cL, dp, L_a against Schaefer-Turek (1996)",
       [](bool quick) { return run_schaefer_turek_2d1(quick, false); }},
      {"schaefer-turek-2d1-overset",
       "the same on an overset O-grid over a Cartesian channel: the same intervals",
       [](bool quick) { return run_schaefer_turek_2d1(quick, true); }},
      {"schaefer-turek-2d2",
       "cylinder in a channel, Re = 100 shedding: St, cD max, cL max against Schaefer-Turek",
       [](bool quick) { return run_schaefer_turek_2d2(quick, false); }},
      {"schaefer-turek-2d2-overset",
       "the same on an overset O-grid over a Cartesian channel: the same intervals",
       [](bool quick) { return run_schaefer_turek_2d2(quick, true); }},
      {"rotating-frame-at-rest",
       "the overset cylinder pair turning as a whole through fluid at rest (slip cylinder, far "
       "field): the velocity stays at round-off",
       run_rotating_frame_at_rest},
      {"galilean-cylinder",
       "the unconfined cylinder at Re = 100 towed through fluid at rest against the fixed one in "
       "the stream: St, mean cD, cL amplitude",
       run_galilean_cylinder},
      {"released-cylinder",
       "a cylinder lighter than its added mass released under a constant force in water at "
       "rest, its motion coupled to the flow (DFBI): the acceleration against potential flow",
       run_released_cylinder},
      {"pitching-foil",
       "a NACA 0012 pitching in its overset grid over a background against the single grid "
       "turning as a whole: cL and cM histories",
       run_pitching_foil},
      {"remus-overset",
       "the REMUS 100 coarse overset system straight at 1.54 m/s, then its fins turning at 30 "
       "deg/s: stable, mass conserved every step, no orphan",
       [](bool quick) { return run_remus_overset(quick, false); }},
      {"remus-overset-sst",
       "the same with SST k-omega riding on the overset coupling, as the CFD plant runs it "
       "(limited linear upwind, ambient sources): stable, mass conserved every step, no orphan",
       [](bool quick) { return run_remus_overset(quick, true); }},
      {"actuator-disk",
       "the propeller's Hough-Ordway body-force disk in a uniform stream: the induced speed "
       "through the disk against annular momentum theory",
       run_actuator_disk},
      {"remus-resistance",
       "the REMUS 100 towed at 1.54 m/s without its propeller, hull alone and hull + fins, "
       "coarse, medium and fine: the drag against ITTC-57 with form factors, and its GCI",
       run_remus_resistance},
      {"remus-self-propulsion",
       "the REMUS 100 free in surge at 1500 rpm with its calibrated body-force propeller, coarse "
       "and medium: speed, J, wake fraction, thrust deduction, thrust and torque",
       run_remus_self_propulsion},
      {"flat-plate-sst",
       "NASA TMR zero-pressure-gradient flat plate, SST k-omega: Cf(0.97) and CD against CFL3D",
       run_flat_plate_sst},
      {"flat-plate-wall-functions",
       "the TMR flat plate on grids with first-cell y+ of 1, 5, 30 and 100: the any-y+ wall "
       "treatment's Cf(0.97) and CD against the y+ < 1 value",
       run_flat_plate_wall_functions},
  };
  return all;
}

}  // namespace auvloop::engine::validation
