// SPDX-License-Identifier: GPL-3.0-or-later
// Exactness and boundedness of the finite-volume operators on distorted grids.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "auvloop/engine/fv/operators.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"
#include "sheared_box.hpp"

using namespace auvloop;
namespace fv = engine::fv;
using test::sheared_box;

namespace {

double residual_max(const fv::Mesh& mesh, const fv::Matrix& m, const std::vector<double>& x) {
  std::vector<double> ax(x.size());
  m.multiply(mesh, x, ax);
  double r = 0;
  for (std::size_t i = 0; i < x.size(); ++i) r = std::max(r, std::abs(ax[i] - m.source[i]));
  return r;
}
}  // namespace

TEST(FvOperators, LaplacianOfALinearFieldVanishesOnNonOrthogonalCells) {
  // div(grad phi) = 0 for linear phi; the least-squares gradient is exact for linear fields, so
  // with the non-orthogonal correction every cell's flux balance is zero to round-off (without it
  // the k . grad(phi) part would be missing on each sheared face: about 1e-2 here).
  const auto grid = sheared_box(6);
  const fv::Mesh mesh(grid);
  fv::ScalarField phi(mesh, "phi");
  const auto linear = [](const Eigen::Vector3d& x) { return 2 + 3 * x.x() - x.y() + 0.5 * x.z(); };
  for (std::size_t p = 0; p < grid.patches.size(); ++p) {
    phi.bcs[p].kind = fv::BcKind::fixed_value;
    for (int i = 0; i < grid.patches[p].size; ++i)
      phi.bcs[p].value.push_back(linear(mesh.face_centre(grid.patches[p].start + i)));
  }
  for (int c = 0; c < mesh.cells(); ++c)
    phi.cells[static_cast<std::size_t>(c)] = linear(mesh.centre(c));
  phi.update_boundary(mesh);
  const fv::Matrix lap = fv::laplacian(mesh, 0.7, phi);
  EXPECT_LT(residual_max(mesh, lap, phi.cells), 1e-13);
  double k_max = 0;
  for (int f = 0; f < mesh.faces(); ++f) k_max = std::max(k_max, mesh.k(f).norm());
  EXPECT_GT(k_max, 1e-3);  // the grid is really non-orthogonal
}

TEST(FvOperators, ConvectionSchemesReadBackFromTheirNames) {
  for (auto c : {fv::Convection::upwind, fv::Convection::linear_upwind,
                 fv::Convection::linear_upwind_limited, fv::Convection::van_leer,
                 fv::Convection::van_leer_skew})
    EXPECT_EQ(fv::convection_from_string(fv::to_string(c)), c);
  try {
    (void)fv::convection_from_string("central");
    FAIL() << "an unknown scheme was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'central'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("van-leer-skew"), std::string::npos) << e.what();
  }
}

TEST(FvOperators, VanLeerConvectionOfAStepStaysBounded) {
  // A step (1 behind x = 0.2, 0 ahead) convected by u = 1 m/s along a 1D row of 60 cells with
  // implicit Euler at Courant number 2: a TVD limiter keeps the converged implicit solution
  // within [0, 1] (Harten 1983: the implicit TVD scheme is TVD for any Courant number), and so
  // does Barth and Jespersen's gradient limiter here, while unlimited linear upwind overshoots
  // behind the front (to 1.043). The 2D oblique version is not strictly
  // bounded with face-wise r factors (docs/cfd.md).
  const int n = 60;
  mesher::BoxPatches patches;
  for (int side = 2; side < 6; ++side)
    patches.types[static_cast<std::size_t>(side)] = mesher::PatchType::empty;
  const auto grid =
      mesher::cartesian_box(mesher::graded_nodes(0, 1, n), {0, 0.1}, {0, 0.1}, patches, "row");
  const fv::Mesh mesh(grid);
  std::vector<double> flux(static_cast<std::size_t>(mesh.faces()));
  for (int f = 0; f < mesh.faces(); ++f) flux[static_cast<std::size_t>(f)] = mesh.area(f).x();
  auto run = [&](fv::Convection scheme) {
    fv::ScalarField phi(mesh, "phi");
    phi.fix(mesh, "xmin", 1.0);
    for (int c = 0; c < n; ++c)
      phi.cells[static_cast<std::size_t>(c)] = mesh.centre(c).x() < 0.2 ? 1 : 0;
    phi.update_boundary(mesh);
    fv::LinearSolver solver(mesh, 1e-13);
    const fv::TimeScheme ts{2.0 / n, false};
    std::pair<double, double> bounds{0, 1};
    for (int step = 0; step < 10; ++step) {
      const auto old = phi.cells;
      for (int it = 0; it < 100; ++it) {
        fv::Matrix eq = fv::ddt(mesh, ts, old, old) + fv::div(mesh, flux, phi, scheme);
        solver.solve_asymmetric(eq, phi.cells, fv::AsymmetricMethod::bicgstab_ilut);
        phi.update_boundary(mesh);
      }
      for (double v : phi.cells) bounds = {std::min(bounds.first, v), std::max(bounds.second, v)};
    }
    return bounds;
  };
  for (const auto scheme : {fv::Convection::van_leer, fv::Convection::van_leer_skew,
                            fv::Convection::linear_upwind_limited}) {
    const auto [lo, hi] = run(scheme);
    EXPECT_GE(lo, -1e-9);
    EXPECT_LE(hi, 1 + 1e-9);
  }
  const auto [lo_lu, hi_lu] = run(fv::Convection::linear_upwind);
  EXPECT_TRUE(lo_lu < -1e-3 || hi_lu > 1 + 1e-3) << lo_lu << " " << hi_lu;
}

namespace {
// The Schaefer-Turek channel with m cells per side of the O-grid's box.
mesher::CylinderChannelSpec o_grid_spec(int m) {
  mesher::CylinderChannelSpec spec;
  spec.cells_per_side = m;
  spec.radial_cells = m / 2;
  spec.downstream_cells = 2 * m;
  return spec;
}
}  // namespace

TEST(FvOperators, SkewCorrectedInterpolationIsSecondOrderAtTheOGridCorners) {
  // The cylinder channel's O-grid kinks at the box corners: skewness |x_f - x_f'| / |d| about
  // 0.47 there on every refinement. Interpolating a smooth field (exact cell and boundary values)
  // to the faces: plain linear interpolation is first order in the maximum face error, the
  // skewness-corrected one second order (Ferziger and Peric, section 8.6).
  const auto exact = [](const Eigen::Vector3d& x) {
    return std::sin(2 * std::numbers::pi * x.x() / 0.41) *
           std::cos(2 * std::numbers::pi * x.y() / 0.41);
  };
  auto errors = [&](int m) {
    const auto spec = o_grid_spec(m);
    const auto grid = mesher::cylinder_channel(spec);
    const fv::Mesh mesh(grid);
    std::vector<double> cells(static_cast<std::size_t>(mesh.cells()));
    std::vector<double> boundary(static_cast<std::size_t>(mesh.boundary_faces()));
    for (int c = 0; c < mesh.cells(); ++c)
      cells[static_cast<std::size_t>(c)] = exact(mesh.centre(c));
    for (int b = 0; b < mesh.boundary_faces(); ++b)
      boundary[static_cast<std::size_t>(b)] = exact(mesh.face_centre(b + mesh.internal_faces()));
    std::vector<Eigen::Vector3d> g(cells.size());
    mesh.gradient(cells, boundary, g);
    std::pair<double, double> e{0, 0};  // plain, corrected
    for (int f = 0; f < mesh.internal_faces(); ++f) {
      // The O-grid's faces only: the graded block downstream has larger O(h^2) errors that would
      // hide the ones at the kinks.
      const Eigen::Vector3d r = mesh.face_centre(f) - Eigen::Vector3d(spec.cx, spec.cy, 0);
      if (std::max(std::abs(r.x()), std::abs(r.y())) > spec.box_half_width + 1e-9) continue;
      const double w = mesh.weight(f), want = exact(mesh.face_centre(f));
      const double plain = w * cells[static_cast<std::size_t>(mesh.owner(f))] +
                           (1 - w) * cells[static_cast<std::size_t>(mesh.neighbour(f))];
      e.first = std::max(e.first, std::abs(plain - want));
      const double ec = std::abs(fv::interpolate(mesh, cells, g, f) - want);
      e.second = std::max(e.second, ec);
    }
    return e;
  };
  const auto coarse = errors(16), fine = errors(32);
  const double plain_order = std::log2(coarse.first / fine.first);
  const double corrected_order = std::log2(coarse.second / fine.second);
  EXPECT_LT(plain_order, 1.3) << coarse.first << " " << fine.first;
  EXPECT_GT(corrected_order, 1.8) << coarse.second << " " << fine.second;
}

TEST(FvOperators, SkewVanLeerConvectionIsConsistentAtTheOGridCorners) {
  // Truncation error of div(F, phi) for a smooth monotone field (no limiter clipping) on the
  // cylinder channel's O-grid: per cell, (volume integral from the operator - sum_f F_f phi(x_f))
  // / V. van Leer's face value sits off the face by the skewness, an O(h) face error and so an
  // O(1) truncation error at the kinks that does not shrink; evaluated at the face centre the
  // face error is O(h^2) and the truncation error O(h).
  const auto exact = [](const Eigen::Vector3d& x) { return std::exp(2 * x.x() + x.y()); };
  const Eigen::Vector3d u(0.3, 0.1, 0);
  auto truncation = [&](int m, fv::Convection scheme) {
    const auto spec = o_grid_spec(m);
    const auto grid = mesher::cylinder_channel(spec);
    const fv::Mesh mesh(grid);
    fv::ScalarField phi(mesh, "phi");
    for (std::size_t p = 0; p < grid.patches.size(); ++p) {
      if (grid.patches[p].type == mesher::PatchType::empty) continue;
      auto& bc = phi.bcs[p];
      bc.kind = fv::BcKind::fixed_value;
      for (int i = 0; i < grid.patches[p].size; ++i)
        bc.value.push_back(exact(mesh.face_centre(grid.patches[p].start + i)));
    }
    for (int c = 0; c < mesh.cells(); ++c)
      phi.cells[static_cast<std::size_t>(c)] = exact(mesh.centre(c));
    phi.update_boundary(mesh);
    std::vector<double> flux(static_cast<std::size_t>(mesh.faces()));
    for (int f = 0; f < mesh.faces(); ++f) flux[static_cast<std::size_t>(f)] = u.dot(mesh.area(f));
    const fv::Matrix eq = fv::div(mesh, flux, phi, scheme);
    std::vector<double> integral(phi.cells.size()), want(phi.cells.size(), 0.0);
    eq.multiply(mesh, phi.cells, integral);
    for (int f = 0; f < mesh.faces(); ++f) {
      const double F = flux[static_cast<std::size_t>(f)] * exact(mesh.face_centre(f));
      want[static_cast<std::size_t>(mesh.owner(f))] += F;
      if (f < mesh.internal_faces()) want[static_cast<std::size_t>(mesh.neighbour(f))] -= F;
    }
    double worst = 0;
    for (int c = 0; c < mesh.cells(); ++c) {
      const Eigen::Vector3d r = mesh.centre(c) - Eigen::Vector3d(spec.cx, spec.cy, 0);
      if (std::max(std::abs(r.x()), std::abs(r.y())) > spec.box_half_width) continue;
      const auto s = static_cast<std::size_t>(c);
      worst = std::max(worst, std::abs(integral[s] - eq.source[s] - want[s]) / mesh.volume(c));
    }
    return worst;
  };
  const double vl =
      truncation(16, fv::Convection::van_leer) / truncation(32, fv::Convection::van_leer);
  const double skew =
      truncation(16, fv::Convection::van_leer_skew) / truncation(32, fv::Convection::van_leer_skew);
  EXPECT_LT(std::log2(vl), 0.3);
  EXPECT_GT(std::log2(skew), 0.8);
  // Linear upwind evaluates at the face centre too; its limiter leaves a smooth monotone field's
  // gradient alone away from extrema.
  const double lub = truncation(16, fv::Convection::linear_upwind_limited) /
                     truncation(32, fv::Convection::linear_upwind_limited);
  EXPECT_GT(std::log2(lub), 0.8);
}
