// SPDX-License-Identifier: GPL-3.0-or-later
// A manufactured steady Navier-Stokes solution on an overset pair (issue 17's mms-overset):
//   1. the exact flow, divergence-free from a stream function, on the unit square:
//          psi = U0 y + A g(x) sin(k y),  g(x) = sin^3(pi (1 - x) / 2),  k = 2 pi,
//          u = U0 + A k g(x) cos(k y),  v = -A g'(x) sin(k y),
//          p = P cos(pi x) sin(pi y),
//      g'(1) = g''(1) = 0, so u and v have no x-derivative at the outlet x = 1, where the
//      solver's zero-gradient U then holds to second order;
//   2. the momentum source f = (U . grad) U + grad p - nu lap U, analytic, at the cell centres
//      (Pimple::body_force);
//   3. the grids: mesher::cylinder_overset's pair in the unit square (the O-grid round a
//      cylinder of radius 0.1 at (0.45, 0.5) out to 0.25, radially stretched 4:1; the Cartesian
//      background uniform to x = 0.85 and stretched from there to the outlet), both skewed by
//      smooth displacements that keep their boundaries: the background's points moved by
//      a (sin(pi x) sin(2 pi y), sin(pi y) sin(2 pi x)), the O-grid's rings turned by
//      b sin(pi (r - R) / (R_o - R)), so its radial lines bend;
//   4. conditions: U the exact value on the inlet, the sides and the cylinder (p zero gradient
//      there); p the exact value on the outlet (U zero gradient): the background is open, so
//      the mass balance acts;
//   5. pseudo-time marching (implicit Euler, PISO with one non-orthogonal corrector) until U
//      changes by less than 1e-10 m/s a step; the errors of |U| and p over the active cells of
//      both grids (fringe cells are interpolated, holes are not flow), L2 weighted by volume and
//      maximum.
// A level m has 4 m cells round the O-grid, m radially and background cells of its outer
// tangential size (pi / (8 m) m); doubling m halves every size.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"

namespace auvloop::engine::validation {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kU0 = 1.0, kA = 0.05, kP = 0.25;                      // m/s, m^2/s, m^2/s^2
constexpr double kK = 2 * kPi;                                         // 1/m
constexpr double kRadius = 0.1, kOuter = 0.25, kCx = 0.45, kCy = 0.5;  // m

// g and its first three derivatives at x (1. above).
std::array<double, 4> g_of(double x) {
  const double s = std::sin(0.5 * kPi * (1 - x)), c = std::cos(0.5 * kPi * (1 - x));
  return {s * s * s, -1.5 * kPi * s * s * c, 0.75 * kPi * kPi * (2 * s * c * c - s * s * s),
          0.375 * kPi * kPi * kPi * (7 * s * s * c - 2 * c * c * c)};
}

Eigen::Vector3d exact_u(const Eigen::Vector3d& x) {
  const auto g = g_of(x.x());
  return {kU0 + kA * kK * g[0] * std::cos(kK * x.y()), -kA * g[1] * std::sin(kK * x.y()), 0};
}

double exact_p(const Eigen::Vector3d& x) {
  return kP * std::cos(kPi * x.x()) * std::sin(kPi * x.y());
}

// 2.
Eigen::Vector3d source(const Eigen::Vector3d& x, double nu) {
  const auto g = g_of(x.x());
  const double C = std::cos(kK * x.y()), S = std::sin(kK * x.y());
  const double u = kU0 + kA * kK * g[0] * C, v = -kA * g[1] * S;
  const double ux = kA * kK * g[1] * C, uy = -kA * kK * kK * g[0] * S;
  const double uxx = kA * kK * g[2] * C, uyy = -kA * kK * kK * kK * g[0] * C;
  const double vx = -kA * g[2] * S, vy = -kA * kK * g[1] * C;
  const double vxx = -kA * g[3] * S, vyy = kA * kK * kK * g[1] * S;
  const double px = -kP * kPi * std::sin(kPi * x.x()) * std::sin(kPi * x.y());
  const double py = kP * kPi * std::cos(kPi * x.x()) * std::cos(kPi * x.y());
  return {u * ux + v * uy + px - nu * (uxx + uyy), u * vx + v * vy + py - nu * (vxx + vyy), 0};
}

// 3.
mesher::CylinderOverset skewed_pair(int m) {
  mesher::CylinderOversetSpec spec;
  spec.length = 1;
  spec.height = 1;
  spec.cx = kCx;
  spec.cy = kCy;
  spec.radius = kRadius;
  spec.outer_radius = kOuter;
  spec.around = 4 * m;
  spec.radial_cells = m;
  spec.radial_ratio = 4;
  spec.near_end = 0.85;
  spec.downstream_cells = std::max(2, m / 2);
  spec.thickness = 0.01;
  auto pair = mesher::cylinder_overset(spec);
  for (auto& q : pair.background.points) {
    const double x = q.x(), y = q.y();
    q.x() += 0.03 * std::sin(kPi * x) * std::sin(2 * kPi * y);
    q.y() += 0.03 * std::sin(kPi * y) * std::sin(2 * kPi * x);
  }
  for (auto& q : pair.cylinder.points) {
    const double dx = q.x() - kCx, dy = q.y() - kCy, r = std::hypot(dx, dy);
    const double turn =
        0.15 * std::sin(kPi * std::clamp((r - kRadius) / (kOuter - kRadius), 0.0, 1.0));
    const double c = std::cos(turn), s = std::sin(turn);
    q.x() = kCx + c * dx - s * dy;
    q.y() = kCy + s * dx + c * dy;
  }
  return pair;
}

void fix_exact(const fv::Mesh& mesh, fv::VectorField& U, const std::string& patch) {
  const auto p = static_cast<std::size_t>(fv::patch_index(mesh, patch));
  U.fix(mesh, patch, {0, 0, 0});
  const auto& range = mesh.grid().patches[p];
  for (int i = 0; i < range.size; ++i) {
    const auto u = exact_u(mesh.face_centre(range.start + i));
    for (std::size_t k = 0; k < 3; ++k)
      U.c[k].bcs[p].value[static_cast<std::size_t>(i)] = u[static_cast<Eigen::Index>(k)];
  }
}
}  // namespace

MmsOversetError mms_overset(int m, double nu) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto pair = skewed_pair(m);
  auto system = mesher::composite_system(
      {{&pair.cylinder, 1, pair.solid.get()}, {&pair.background, 0, nullptr}});
  const auto grid = std::move(system.composite.grid);
  const fv::Mesh mesh(grid);
  const fv::Overset overset(mesh, std::move(system.stencils),
                            std::move(system.composite.cell_offset));
  fv::PimpleSettings s;  // 5.
  s.nu = nu;
  s.bdf2 = false;  // pseudo-time marching to the steady state
  s.dt = 0.05;     // s: the steady state does not depend on it (measured: 0.01 to 0.2)
  s.pressure_correctors = 2;
  s.non_orthogonal_correctors = 1;
  s.max_courant = 1e3;
  fv::Pimple flow(mesh, s);
  flow.set_overset(&overset);
  for (const char* patch :
       {"background/inlet", "background/bottom", "background/top", "cylinder/cylinder"})
    fix_exact(mesh, flow.U, patch);
  const auto outlet = static_cast<std::size_t>(fv::patch_index(mesh, "background/outlet"));
  flow.p.fix(mesh, "background/outlet", 0.0);
  for (int i = 0; i < grid.patches[outlet].size; ++i)
    flow.p.bcs[outlet].value[static_cast<std::size_t>(i)] =
        exact_p(mesh.face_centre(grid.patches[outlet].start + i));
  flow.body_force.resize(static_cast<std::size_t>(mesh.cells()));
  for (int c = 0; c < mesh.cells(); ++c) {
    flow.body_force[static_cast<std::size_t>(c)] = source(mesh.centre(c), nu);
    flow.U.c[0].cells[static_cast<std::size_t>(c)] = kU0;  // from the uniform stream
  }
  flow.U.update_boundary(mesh);
  flow.initialise();

  MmsOversetError e;
  e.m = m;
  e.cells = mesh.cells();
  e.active_cells = static_cast<int>(overset.active_cells().size());
  for (e.iterations = 1; e.iterations <= 20000; ++e.iterations) {
    const auto before = flow.U.c;
    const auto rep = flow.step();
    e.interface_flux = rep.interface_flux / kU0;  // inflow per unit depth and height: U0
    e.continuity_error = rep.continuity_error;
    double change = 0;
    for (std::size_t k = 0; k < 2; ++k)
      for (int c : overset.active_cells()) {
        const auto i = static_cast<std::size_t>(c);
        change = std::max(change, std::abs(flow.U.c[k].cells[i] - before[k].cells[i]));
      }
    if (change < 1e-10) {
      e.converged = true;
      break;
    }
  }
  double su = 0, sp = 0, volume = 0;
  for (int c : overset.active_cells()) {
    const auto i = static_cast<std::size_t>(c);
    const Eigen::Vector3d x = mesh.centre(c);
    const Eigen::Vector3d du =
        Eigen::Vector3d(flow.U.c[0].cells[i], flow.U.c[1].cells[i], 0) - exact_u(x);
    const double dp = flow.p.cells[i] - exact_p(x);
    su += du.squaredNorm() * mesh.volume(c);
    sp += dp * dp * mesh.volume(c);
    volume += mesh.volume(c);
    e.max_u = std::max(e.max_u, du.norm());
    e.max_p = std::max(e.max_p, std::abs(dp));
  }
  e.l2_u = std::sqrt(su / volume);
  e.l2_p = std::sqrt(sp / volume);
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

}  // namespace auvloop::engine::validation
