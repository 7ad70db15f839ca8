// SPDX-License-Identifier: GPL-3.0-or-later
// The stopping test of the iterative linear solvers: each stops on the norm it is given, the
// relative 2-norm |b - A x| / |b| or OpenFOAM's normalised residual, and reports the normalised
// residual of the x it returns. Both norms are recomputed here from the fv::Matrix itself, the
// normalised one by OpenFOAM's definition (lduMatrix::normFactor: sum |A x0 - A xbar| +
// |b - A xbar| with x0 the initial guess and xbar its mean, taken once at the start of a solve,
// as its solvers do), not by the solvers' code.
#include <cmath>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "auvloop/engine/fv/operators.hpp"
#include "sheared_box.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {

// A x for the face-addressed matrix: diag x minus (source - H(x)), as h_operator gives
// H(x) = source - sum_nb a_nb x_nb.
std::vector<double> product(const fv::Mesh& mesh, const fv::Matrix& m,
                            const std::vector<double>& x) {
  std::vector<double> h(x.size()), ax(x.size());
  m.h_operator(mesh, x, h);
  for (std::size_t i = 0; i < x.size(); ++i) ax[i] = m.diag[i] * x[i] - (h[i] - m.source[i]);
  return ax;
}

struct Norms {
  double relative = 0, normalised = 0;
};

// The norms of b - A x, normalised with the factor of the initial guess x0.
Norms norms(const fv::Mesh& mesh, const fv::Matrix& m, const std::vector<double>& x,
            const std::vector<double>& x0) {
  const auto ax = product(mesh, m, x), ax0 = product(mesh, m, x0);
  const double mean = std::accumulate(x0.begin(), x0.end(), 0.0) / static_cast<double>(x.size());
  const auto a_mean = product(mesh, m, std::vector<double>(x.size(), mean));
  double r1 = 0, r2 = 0, b2 = 0, factor = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = m.source[i] - ax[i];
    r1 += std::abs(r);
    r2 += r * r;
    b2 += m.source[i] * m.source[i];
    factor += std::abs(ax0[i] - a_mean[i]) + std::abs(m.source[i] - a_mean[i]);
  }
  return {std::sqrt(r2 / b2), r1 / factor};
}

// Diffusion and a time term, with the upper coefficients weakened by 30 % (an asymmetric,
// diagonally dominant matrix like a momentum equation's), and a non-uniform source.
fv::Matrix transport(const fv::Mesh& mesh, bool symmetric) {
  fv::ScalarField phi(mesh, "phi");
  for (auto& bc : phi.bcs) bc.kind = fv::BcKind::zero_gradient;
  const std::vector<double> old(static_cast<std::size_t>(mesh.cells()), 0.0);
  fv::Matrix m =
      fv::ddt(mesh, fv::TimeScheme{0.05, false}, old, old) - fv::laplacian(mesh, 1.0, phi);
  if (!symmetric)
    for (auto& a : m.upper) a *= 0.7;
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto& p = mesh.centre(c);
    m.source[static_cast<std::size_t>(c)] =
        mesh.volume(c) * (std::sin(3 * p.x()) * std::cos(2 * p.y()) + p.z());
  }
  return m;
}

}  // namespace

TEST(LinearSolver, EveryIterativeMethodStopsOnTheNormItIsGiven) {
  const auto grid = test::sheared_box(10);
  const fv::Mesh mesh(grid);
  for (const auto norm : {fv::ResidualNorm::relative, fv::ResidualNorm::normalised}) {
    const double tol = 1e-6;
    // A start away from zero, so that the normalisation's mean term is not trivial.
    std::vector<double> x0(static_cast<std::size_t>(mesh.cells()));
    for (int c = 0; c < mesh.cells(); ++c)
      x0[static_cast<std::size_t>(c)] = 0.3 + 0.1 * mesh.centre(c).y();
    const auto check = [&](const fv::Matrix& m, const std::vector<double>& x,
                           const fv::SolveStats& s, const char* method) {
      const auto n = norms(mesh, m, x, x0);
      SCOPED_TRACE(std::string(method) + ", " + fv::to_string(norm));
      EXPECT_GT(s.iterations, 0);
      EXPECT_LE(norm == fv::ResidualNorm::relative ? n.relative : n.normalised, tol);
      // The Krylov methods report their recursive residual, which drifts from the true one by
      // round-off; the last test of BiCGSTAB and the Gauss-Seidel sweeps use the true one.
      EXPECT_NEAR(s.final_residual, n.normalised, 1e-3 * n.normalised);
      EXPECT_NEAR(s.initial_residual, norms(mesh, m, x0, x0).normalised, 1e-9);
    };
    // The symmetric methods solve the negative definite Laplacian as given (sign flipped inside).
    const fv::Matrix sym = -transport(mesh, true);
    for (const auto method : {fv::SymmetricMethod::cg_amg, fv::SymmetricMethod::cg_jacobi}) {
      fv::LinearSolver solver(mesh, fv::Tolerance(tol, norm));
      std::vector<double> x = x0;
      check(sym, x, solver.solve_symmetric(sym, x, method), fv::to_string(method));
    }
    const fv::Matrix asym = transport(mesh, false);
    for (const auto method :
         {fv::AsymmetricMethod::gauss_seidel, fv::AsymmetricMethod::bicgstab_jacobi,
          fv::AsymmetricMethod::bicgstab_gs}) {
      fv::LinearSolver solver(mesh, fv::Tolerance(1e-12, norm));  // replaced per solve below
      std::vector<double> x = x0;
      check(asym, x, solver.solve_asymmetric(asym, x, method, tol), fv::to_string(method));
    }
  }
}

TEST(LinearSolver, ResidualNormNamesRoundTripAndUnknownOnesAreRejected) {
  for (const auto n : {fv::ResidualNorm::relative, fv::ResidualNorm::normalised})
    EXPECT_EQ(fv::residual_norm_from_string(fv::to_string(n)), n);
  EXPECT_THROW(fv::residual_norm_from_string("l2"), std::invalid_argument);
}
