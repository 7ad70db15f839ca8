// SPDX-License-Identifier: GPL-3.0-or-later
// Method of manufactured solutions (Roache 2002) for the steady convection-diffusion equation
//     div(u phi) - div(Gamma grad phi) = s
// with u = (1, 0.5, 0.25) m/s, Gamma = 0.05 m^2/s and phi = sin(pi x) cos(pi y / 2) exp(z / 2) + 1
// on the unit cube, phi fixed on all sides. The grid is stretched (ratios 1.1 and 0.9 across the
// box) and skewed by a smooth mapping, so refinement keeps the shape of the cells and the
// observed order measures the scheme: 2 for second-order convection (van Leer) and diffusion with
// non-orthogonal correction.
#include <cmath>
#include <numbers>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "auvloop/engine/fv/operators.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::engine::validation {

namespace {
using fv::Mesh;
using fv::ScalarField;
constexpr double kPi = std::numbers::pi;
const Eigen::Vector3d kU(1.0, 0.5, 0.25);
constexpr double kGamma = 0.05;

double exact(const Eigen::Vector3d& x) {
  return std::sin(kPi * x.x()) * std::cos(0.5 * kPi * x.y()) * std::exp(0.5 * x.z()) + 1;
}
double source(const Eigen::Vector3d& x) {
  const double sx = std::sin(kPi * x.x()), cx = std::cos(kPi * x.x());
  const double sy = std::sin(0.5 * kPi * x.y()), cy = std::cos(0.5 * kPi * x.y());
  const double ez = std::exp(0.5 * x.z());
  const Eigen::Vector3d g(kPi * cx * cy * ez, -0.5 * kPi * sx * sy * ez, 0.5 * sx * cy * ez);
  const double lap = (-kPi * kPi - 0.25 * kPi * kPi + 0.25) * sx * cy * ez;
  return kU.dot(g) - kGamma * lap;
}

// Stretched box, then every point moved by a smooth displacement that vanishes normal to each
// side, so the boundary stays the unit cube: the cells are skewed and non-orthogonal everywhere.
mesher::Grid skewed_box(int n) {
  auto g = mesher::cartesian_box(mesher::graded_nodes(0, 1, n, std::pow(1.1, 16.0 / n)),
                                 mesher::graded_nodes(0, 1, n, std::pow(0.9, 16.0 / n)),
                                 mesher::graded_nodes(0, 1, n), {}, "mms");
  for (auto& p : g.points) {
    const double sx = std::sin(kPi * p.x()), sy = std::sin(kPi * p.y()), sz = std::sin(kPi * p.z());
    p += 0.06 * Eigen::Vector3d(sx * std::sin(2 * kPi * p.y()), sy * std::sin(2 * kPi * p.z()),
                                sz * std::sin(2 * kPi * p.x()));
  }
  return g;
}
}  // namespace

MmsError mms_convection_diffusion(int n) {
  const auto grid = skewed_box(n);
  const Mesh mesh(grid);
  ScalarField phi(mesh, "phi");
  for (std::size_t p = 0; p < grid.patches.size(); ++p) {
    auto& bc = phi.bcs[p];
    bc.kind = fv::BcKind::fixed_value;
    for (int i = 0; i < grid.patches[p].size; ++i)
      bc.value.push_back(exact(mesh.face_centre(grid.patches[p].start + i)));
  }
  phi.update_boundary(mesh);
  std::vector<double> flux(static_cast<std::size_t>(mesh.faces())), s(phi.cells.size());
  for (int f = 0; f < mesh.faces(); ++f) flux[static_cast<std::size_t>(f)] = kU.dot(mesh.area(f));
  for (int c = 0; c < mesh.cells(); ++c) s[static_cast<std::size_t>(c)] = source(mesh.centre(c));
  fv::LinearSolver solver(mesh, 1e-12);
  MmsError e{n, 0, 0, 0};
  // Deferred corrections (non-orthogonality, van Leer) converge by fixed-point iteration.
  for (int it = 0; it < 200; ++it) {
    fv::Matrix eq =
        fv::div(mesh, flux, phi, fv::Convection::van_leer_skew) - fv::laplacian(mesh, kGamma, phi);
    eq.add_rhs(mesh, s);
    const auto before = phi.cells;
    solver.solve_asymmetric(eq, phi.cells, fv::AsymmetricMethod::bicgstab_ilut);
    phi.update_boundary(mesh);
    double change = 0;
    for (std::size_t i = 0; i < before.size(); ++i)
      change = std::max(change, std::abs(phi.cells[i] - before[i]));
    e.iterations = it + 1;
    if (change < 1e-11) break;
  }
  double sum = 0;
  for (int c = 0; c < mesh.cells(); ++c) {
    const double err = phi.cells[static_cast<std::size_t>(c)] - exact(mesh.centre(c));
    sum += err * err * mesh.volume(c);
    e.max = std::max(e.max, std::abs(err));
  }
  e.l2 = std::sqrt(sum / mesh.total_volume());
  return e;
}

}  // namespace auvloop::engine::validation
