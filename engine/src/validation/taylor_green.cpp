// SPDX-License-Identifier: GPL-3.0-or-later
// 2D Taylor-Green vortex, an exact solution of the Navier-Stokes equations:
//   u = -cos x sin y F(t), v = sin x cos y F(t), p = -(cos 2x + cos 2y) F(t)^2 / 4,
//   F(t) = exp(-2 nu t),
// here on [0, pi]^2 with the exact velocity imposed on the sides at every time level (time-
// dependent Dirichlet values; dp/dn = 0 there exactly). The temporal order is observed on one
// grid by halving dt (differences of successive solutions, Roache 2002), so the spatial error,
// the same for every dt, cancels; the outer loop is iterated to convergence so the splitting error
// does not mask BDF2.
#include <cmath>
#include <numbers>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::engine::validation {

namespace {
constexpr double kPi = std::numbers::pi;

Eigen::Vector3d exact_velocity(const Eigen::Vector3d& x, double nu, double t) {
  const double F = std::exp(-2 * nu * t);
  return {-std::cos(x.x()) * std::sin(x.y()) * F, std::sin(x.x()) * std::cos(x.y()) * F, 0.0};
}

void impose_exact(const fv::Mesh& mesh, fv::Pimple& flow, double nu, double t) {
  const auto& patches = mesh.grid().patches;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (patches[p].type == mesher::PatchType::empty) continue;
    for (int i = 0; i < patches[p].size; ++i) {
      const auto u = exact_velocity(mesh.face_centre(patches[p].start + i), nu, t);
      for (std::size_t c = 0; c < 3; ++c)
        flow.U.c[c].bcs[p].value[static_cast<std::size_t>(i)] = u[static_cast<Eigen::Index>(c)];
    }
  }
}
}  // namespace

TaylorGreenRun taylor_green(int n, int steps, double end_time, double nu) {
  const auto nodes = mesher::graded_nodes(0, kPi, n);
  mesher::BoxPatches patches;
  patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  const auto grid = mesher::cartesian_box(nodes, nodes, {0.0, kPi / n}, patches, "taylor-green");
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = nu;
  s.dt = end_time / steps;
  s.outer_iterations = 60;
  s.outer_tolerance = 1e-10;
  s.pressure_correctors = 2;
  s.tolerance = 1e-12;
  fv::Pimple flow(mesh, s);
  for (const char* side : {"xmin", "xmax", "ymin", "ymax"}) flow.U.fix(mesh, side, {0, 0, 0});
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto u = exact_velocity(mesh.centre(c), nu, 0);
    const auto& x = mesh.centre(c);
    for (std::size_t k = 0; k < 3; ++k)
      flow.U.c[k].cells[static_cast<std::size_t>(c)] = u[static_cast<Eigen::Index>(k)];
    flow.p.cells[static_cast<std::size_t>(c)] = -0.25 * (std::cos(2 * x.x()) + std::cos(2 * x.y()));
  }
  impose_exact(mesh, flow, nu, 0);
  flow.initialise();
  TaylorGreenRun run;
  for (int k = 0; k < steps; ++k) {
    impose_exact(mesh, flow, nu, flow.time() + s.dt);
    const auto r = flow.step();
    run.max_outer = std::max(run.max_outer, r.outer_iterations);
  }
  double sum = 0;
  for (int c = 0; c < mesh.cells(); ++c) {
    const Eigen::Vector3d u = flow.U.cell(c);
    run.u.push_back(u.x());
    run.v.push_back(u.y());
    sum += (u - exact_velocity(mesh.centre(c), nu, flow.time())).squaredNorm() * mesh.volume(c);
  }
  run.error_vs_exact = std::sqrt(sum / mesh.total_volume());
  run.volumes = mesh.geometry().cell_volume;
  return run;
}

double l2_difference(const TaylorGreenRun& a, const TaylorGreenRun& b) {
  double sum = 0, volume = 0;
  for (std::size_t c = 0; c < a.u.size(); ++c) {
    const double du = a.u[c] - b.u[c], dv = a.v[c] - b.v[c];
    sum += (du * du + dv * dv) * a.volumes[c];
    volume += a.volumes[c];
  }
  return std::sqrt(sum / volume);
}

}  // namespace auvloop::engine::validation
