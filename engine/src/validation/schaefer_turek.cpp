// SPDX-License-Identifier: GPL-3.0-or-later
// Schaefer and Turek (1996) DFG benchmark 2D-1: steady flow past a cylinder (D = 0.1 m, centre
// (0.2, 0.2)) in a channel [0, 2.2] x [0, 0.41] m, parabolic inflow with Um = 0.3 m/s, nu = 1e-3,
// Re = Ubar D / nu = 20. Reference intervals: shared/reference/validation-data.md, section 2.
// The steady state is reached by pseudo-time marching (Euler); forces are integrated over the
// cylinder faces: pressure p S_f and viscous nu dU/dn |S|.
//
// NOT YET A VALIDATION CASE (not listed by `auvloop validate`): the results converge at about
// first order and are outside the reference intervals on the grids tried (docs/cfd.md,
// "Schaefer-Turek: open").
#include <chrono>
#include <cmath>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"

namespace auvloop::engine::validation {

namespace {
// Value of a cell field at x: nearest cell centre plus its gradient (second order in smooth
// regions; the sampled points lie inside the fluid).
double sample(const fv::Mesh& mesh, const fv::ScalarField& f,
              const std::vector<Eigen::Vector3d>& grad, const Eigen::Vector3d& x) {
  int best = 0;
  double d2 = 1e300;
  for (int c = 0; c < mesh.cells(); ++c) {
    const double d = (mesh.centre(c) - x).squaredNorm();
    if (d < d2) {
      d2 = d;
      best = c;
    }
  }
  const auto b = static_cast<std::size_t>(best);
  return f.cells[b] + grad[b].dot(x - mesh.centre(best));
}
}  // namespace

CylinderResult schaefer_turek_2d1(int cells_per_side, double dt) {
  const auto t_start = std::chrono::steady_clock::now();
  mesher::CylinderChannelSpec spec;
  spec.cells_per_side = cells_per_side;
  spec.radial_cells = cells_per_side;
  spec.downstream_cells = 2 * cells_per_side;
  const auto grid = mesher::cylinder_channel(spec);
  const fv::Mesh mesh(grid);
  const double Um = 0.3, H = spec.height, D = 2 * spec.radius, Ubar = 2 * Um / 3;
  fv::PimpleSettings s;
  s.nu = 1e-3;
  s.dt = dt;
  s.non_orthogonal_correctors = 1;
  s.bdf2 = false;
  s.pressure_correctors = 2;
  s.max_courant = 1e3;
  fv::Pimple flow(mesh, s);
  flow.U.fix(mesh, "walls", {0, 0, 0});
  flow.U.fix(mesh, "cylinder", {0, 0, 0});
  flow.U.fix(mesh, "inlet", {0, 0, 0});
  const auto inlet = static_cast<std::size_t>(fv::patch_index(mesh, "inlet"));
  for (int i = 0; i < grid.patches[inlet].size; ++i) {
    const double y = mesh.face_centre(grid.patches[inlet].start + i).y();
    flow.U.c[0].bcs[inlet].value[static_cast<std::size_t>(i)] = 4 * Um * y * (H - y) / (H * H);
  }
  flow.p.fix(mesh, "outlet", 0.0);
  flow.initialise();
  CylinderResult r;
  r.cells = mesh.cells();
  for (r.steps = 1; r.steps <= 20000; ++r.steps) {
    const auto before = flow.U.c[0].cells;
    flow.step();
    double change = 0;
    for (std::size_t c = 0; c < before.size(); ++c)
      change = std::max(change, std::abs(flow.U.c[0].cells[c] - before[c]));
    r.final_change = change / s.dt;
    if (r.final_change < 1e-6) break;
  }
  // Forces on the cylinder per unit depth.
  const auto& cyl = grid.patches[static_cast<std::size_t>(fv::patch_index(mesh, "cylinder"))];
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  const auto gp = fv::grad(mesh, flow.p);
  const std::array<std::vector<Eigen::Vector3d>, 3> gU{
      fv::grad(mesh, flow.U.c[0]), fv::grad(mesh, flow.U.c[1]), fv::grad(mesh, flow.U.c[2])};
  for (int i = 0; i < cyl.size; ++i) {
    const int f = cyl.start + i;
    const int P = mesh.owner(f);
    const Eigen::Vector3d& S = mesh.area(f);
    const double pf = flow.p.cells[static_cast<std::size_t>(P)] +
                      gp[static_cast<std::size_t>(P)].dot(mesh.face_centre(f) - mesh.centre(P));
    // Wall-normal derivative of U to second order: a parabola through the wall value (0), the
    // cell value and the cell's normal gradient, dU/dn_wall = 2 U_P / dn - dU/dn_P.
    const double dn = S.dot(mesh.d(f)) / S.norm();
    const Eigen::Vector3d n_fluid = -S.normalized();
    Eigen::Vector3d dudn_P;
    for (std::size_t k = 0; k < 3; ++k)
      dudn_P[static_cast<Eigen::Index>(k)] = gU[k][static_cast<std::size_t>(P)].dot(n_fluid);
    const Eigen::Vector3d dudn_wall = 2 * flow.U.cell(P) / dn - dudn_P;
    force += pf * S + s.nu * dudn_wall * S.norm();
  }
  force /= spec.thickness;
  r.cd = 2 * force.x() / (Ubar * Ubar * D);
  r.cl = 2 * force.y() / (Ubar * Ubar * D);
  const double z = 0.5 * spec.thickness;
  r.dp = sample(mesh, flow.p, gp, {spec.cx - spec.radius, spec.cy, z}) -
         sample(mesh, flow.p, gp, {spec.cx + spec.radius, spec.cy, z});
  // Recirculation length: first sign change of u on y = cy behind the cylinder.
  const auto gu = fv::grad(mesh, flow.U.c[0]);
  double x_prev = spec.cx + spec.radius, u_prev = 0;
  for (double x = x_prev + 1e-3; x < 0.6; x += 1e-3) {
    const double u = sample(mesh, flow.U.c[0], gu, {x, spec.cy, z});
    if (u > 0 && u_prev <= 0 && x_prev > spec.cx + spec.radius) {
      r.la = x_prev + (x - x_prev) * (-u_prev) / (u - u_prev) - (spec.cx + spec.radius);
      break;
    }
    x_prev = x;
    u_prev = u;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return r;
}

}  // namespace auvloop::engine::validation
