// SPDX-License-Identifier: GPL-3.0-or-later
// NASA TMR 2DZP with SST k-omega (validation.hpp, flat_plate_sst):
//   1. the TMR's set-up in SI units: U = 1 m/s, Re = 5e6 per metre (nu = 2e-7 m^2/s), free
//      stream k = 1.125 U^2 / Re_L and omega = 125 U / L with L = 1 m; inlet: U, k, omega fixed;
//      outlet and top: p = 0; symmetry plane ahead of the plate: slip; plate: no-slip with the
//      SST's wall treatment;
//   2. a steady SIMPLE solve from the free stream or a coarser level's solution
//      (PimpleSettings::steady), until the change of Cf(0.97) and of the plate drag still to
//      come, extrapolated from their last two changes over `check_every` iterations, is below
//      `tolerance` (relative);
//   3. the wall shear of every plate face, tau_w = (nu + nu_t,w) U_t / y (the momentum
//      equation's discrete wall flux), Cf = tau_w / (U^2 / 2); Cf(0.97) linear between face
//      centres; CD = the integral of Cf over the plate / 2 (the TMR's reference length 2);
//   4. the free stream against its analytic decay (the TMR's): along the top row of cells, far
//      from the plate (F1 = 0, no production, diffusion and cross-diffusion negligible),
//      U d omega/dx = -beta2 omega^2 and U dk/dx = -beta* k omega, so with X = x - x_inlet
//          omega = omega_in / (1 + beta2 omega_in X / U),  k = k_in (1 + beta2 omega_in X /
//          U)^(-beta*/beta2);
//      the largest relative error from x = 0.2 to the outlet (a free stream the solves leave
//      frozen shows tens of per cent), and the streamwise size of the outlet cell, which sets it
//      (first order: validation/cases.cpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/turbulence/sst_model.hpp"
#include "auvloop/engine/turbulence/wall_distance.hpp"
#include "auvloop/engine/validation.hpp"

namespace auvloop::engine::validation {

namespace {
struct PlateShear {
  std::vector<double> x, cf;  // per plate face, ascending x
  double cd = 0;
};

PlateShear plate_shear(const fv::Mesh& mesh, const fv::Pimple& flow,
                       const turbulence::SstModel& sst, double U_inf, double nu) {
  PlateShear out;
  const auto& patch = mesh.grid().patches[static_cast<std::size_t>(fv::patch_index(mesh, "plate"))];
  const int internal = mesh.internal_faces();
  double drag = 0, area = 0;  // area: the plate's length times the grid's depth
  for (int i = 0; i < patch.size; ++i) {
    const int f = patch.start + i;
    const int P = mesh.owner(f);
    const Eigen::Vector3d n_hat = mesh.area(f).normalized();
    const double y = std::abs((mesh.face_centre(f) - mesh.centre(P)).dot(n_hat));
    Eigen::Vector3d u = flow.U.cell(P);
    u -= u.dot(n_hat) * n_hat;
    const double nu_w =
        nu + (flow.turbulence() ? sst.nu_t.boundary[static_cast<std::size_t>(f - internal)] : 0.0);
    out.x.push_back(mesh.face_centre(f).x());
    out.cf.push_back(nu_w * u.norm() / y / (0.5 * U_inf * U_inf));
    drag += nu_w * u.x() / y * mesh.area(f).norm();
    area += mesh.area(f).norm();
  }
  out.cd = drag / (0.5 * U_inf * U_inf * area);
  return out;
}

double at(const PlateShear& s, double x) {
  for (std::size_t i = 1; i < s.x.size(); ++i)
    if (s.x[i] >= x) {
      const double t = (x - s.x[i - 1]) / (s.x[i] - s.x[i - 1]);
      return (1 - t) * s.cf[i - 1] + t * s.cf[i];
    }
  throw std::logic_error("flat plate: x beyond the plate");
}
}  // namespace

FlatPlateResult flat_plate_sst(const FlatPlateCase& c) {
  const auto t0 = std::chrono::steady_clock::now();
  // 1.
  constexpr double U_inf = 1.0, L = 1.0, Re = 5e6;
  const double nu = U_inf * L / Re;
  const mesher::Grid grid = mesher::flat_plate(c.spec, c.level);
  const fv::Mesh mesh(grid);
  const fv::Mesh* meshes[] = {&mesh};
  const turbulence::WallDistances walls(meshes);
  fv::PimpleSettings s;
  s.nu = nu;
  s.steady = true;
  s.dt = 1;  // a label: steady
  s.outer_iterations = 1;
  s.pressure_correctors = 1;
  s.relax_u = c.relax_u;
  s.relax_p = c.relax_p;
  s.tolerance = c.pressure_tolerance;
  s.momentum_tolerance = c.transport_tolerance;
  s.max_courant = 1e30;  // steady: the "Courant number" of the label dt means nothing
  fv::Pimple flow(mesh, s);
  turbulence::SstSettings ts;
  ts.nu = nu;
  ts.freestream = turbulence::tmr_freestream(U_inf, L, nu);
  ts.relax = c.relax_turbulence;
  ts.convection = c.turbulence_convection;
  ts.wall = c.wall;
  ts.tolerance = c.transport_tolerance;
  const auto distance = walls.of(0);
  turbulence::SstModel sst(mesh, {distance.begin(), distance.end()}, ts);
  flow.U.fix(mesh, "inlet", {U_inf, 0, 0});
  flow.U.fix(mesh, "plate", {0, 0, 0});
  flow.slip("symmetry");
  flow.p.fix(mesh, "outlet", 0.0);
  if (c.spec.top_type == mesher::PatchType::outlet) flow.p.fix(mesh, "top", 0.0);
  sst.inlet("inlet");
  const int stride = 1 << c.level;
  const int nx = (c.spec.plate_cells + c.spec.upstream_cells) / stride;
  const int ny = c.spec.normal_cells / stride;
  if (nx * ny != mesh.cells()) throw std::logic_error("flat plate: cells are not nx x ny");
  for (std::size_t i = 0; i < flow.U.c[0].cells.size(); ++i) flow.U.c[0].cells[i] = U_inf;
  if (c.start) {  // grid sequencing from level + 1
    const auto& s0 = *c.start;
    if (s0.level != c.level + 1 || 2 * s0.nx != nx || 2 * s0.ny != ny)
      throw std::invalid_argument(fmt::format(
          "flat plate: a start must be the solution of level {} ({} x {} cells), got level {} "
          "({} x {})",
          c.level + 1, nx / 2, ny / 2, s0.level, s0.nx, s0.ny));
    std::array<std::vector<double>, 5> f;
    for (auto& v : f) v.resize(static_cast<std::size_t>(mesh.cells()));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (std::size_t q = 0; q < 5; ++q)
          f[q][static_cast<std::size_t>(i + nx * j)] =
              s0.fields[q][static_cast<std::size_t>(i / 2 + s0.nx * (j / 2))];
    flow.U.c[0].cells = f[0];
    flow.U.c[1].cells = f[1];
    flow.p.cells = f[2];
    sst.start_from(f[3], f[4]);
  }
  if (!c.laminar) flow.set_turbulence(&sst);
  flow.initialise();
  // 2.
  FlatPlateResult r;
  r.cells = mesh.cells();
  double cf_prev = 0, cd_prev = 0, dcf_prev = 0, dcd_prev = 0;
  for (int it = 1; it <= c.max_iterations; ++it) {
    const auto report = flow.step();
    r.iterations = it;
    r.bounded_cells += report.turbulence.bounded_cells;
    r.limited_cells = report.turbulence.limited_cells;
    r.final_residuals = {report.momentum_residual, report.pressure_residual,
                         report.turbulence.k_residual, report.turbulence.omega_residual};
    if (it % c.check_every != 0) continue;
    const auto shear = plate_shear(mesh, flow, sst, U_inf, nu);
    const double cf = at(shear, 0.97), cd = shear.cd;
    if (c.progress)
      c.progress(
          fmt::format("iteration {}: Cf(0.97) {:.6f}, CD {:.6f}, residuals U {:.2e} p {:.2e} "
                      "k {:.2e} omega {:.2e}",
                      it, cf, cd, report.momentum_residual, report.pressure_residual,
                      report.turbulence.k_residual, report.turbulence.omega_residual));
    // The change still to come, from the last two changes (remaining_change: Aitken).
    const double dcf = std::abs(cf - cf_prev), dcd = std::abs(cd - cd_prev);
    const bool settled = cf_prev > 0 && remaining_change(dcf, dcf_prev) <= c.tolerance * cf &&
                         remaining_change(dcd, dcd_prev) <= c.tolerance * cd;
    dcf_prev = cf_prev > 0 ? dcf : 0.0;
    dcd_prev = cf_prev > 0 ? dcd : 0.0;
    cf_prev = cf;
    cd_prev = cd;
    if (settled) {
      r.converged = true;
      break;
    }
  }
  // 3.
  const auto shear = plate_shear(mesh, flow, sst, U_inf, nu);
  r.cf_097 = at(shear, 0.97);
  r.cd = shear.cd;
  r.x = shear.x;
  r.cf = shear.cf;
  for (const auto& y : sst.y_plus())
    if (y.patch == "plate") r.y_plus = y;
  r.level = c.level;
  r.nx = nx;
  r.ny = ny;
  r.fields = {flow.U.c[0].cells, flow.U.c[1].cells, flow.p.cells, sst.k.cells, sst.omega.cells};
  // 4.
  if (!c.laminar) {
    const auto& sc = ts.constants;
    r.outlet_dx = 2 * (c.spec.plate_length - mesh.centre(nx * ny - 1).x());
    for (int i = 0; i < nx; ++i) {
      const int cell = i + nx * (ny - 1);
      const double x = mesh.centre(cell).x();
      if (x < 0.2) continue;
      const double decay = 1 + sc.beta2 * ts.freestream.omega * (x + c.spec.upstream) / U_inf;
      const auto s_cell = static_cast<std::size_t>(cell);
      r.freestream_omega_error =
          std::max(r.freestream_omega_error,
                   std::abs(sst.omega.cells[s_cell] * decay / ts.freestream.omega - 1));
      r.freestream_k_error =
          std::max(r.freestream_k_error,
                   std::abs(sst.k.cells[s_cell] /
                                (ts.freestream.k * std::pow(decay, -sc.beta_star / sc.beta2)) -
                            1));
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace auvloop::engine::validation
