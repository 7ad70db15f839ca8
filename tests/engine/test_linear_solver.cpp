// SPDX-License-Identifier: GPL-3.0-or-later
// The stopping test of the iterative linear solvers: each stops on the norm it is given, the
// relative 2-norm |b - A x| / |b| or OpenFOAM's normalised residual, and reports the normalised
// residual of the x it returns. Both norms are recomputed here from the fv::Matrix itself, the
// normalised one by OpenFOAM's definition (lduMatrix::normFactor: sum |A x0 - A xbar| +
// |b - A xbar| with x0 the initial guess and xbar its mean, taken once at the start of a solve,
// as its solvers do), not by the solvers' code.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

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

// The bordered system (an overset pressure equation with its mass balance, overset_mass.cpp):
// a negative definite matrix m with two extra unknowns, each coupled to a slab of cells as one
// more cell of a Laplacian (off-diagonals a > 0 to its cells, diagonal -sum a, and the cells'
// diagonals made as much stronger). Against Eigen's sparse LU of the assembled (n + 2) system,
// not the solver's code; and bitwise the same on one and two threads.
TEST(LinearSolver, BorderedSystemMatchesADirectSolveOfTheAssembledMatrix) {
  const auto grid = test::sheared_box(10);
  const fv::Mesh mesh(grid);
  const auto n = static_cast<std::size_t>(mesh.cells());
  fv::Matrix m = -transport(mesh, true);
  fv::Border border;
  border.columns.resize(2);
  for (int c = 0; c < mesh.cells(); ++c) {
    const double x = mesh.centre(c).x();
    const int k = x < 0.25 ? 0 : (x > 0.75 ? 1 : -1);
    if (k < 0) continue;
    auto& col = border.columns[static_cast<std::size_t>(k)];
    const double a = 0.2 * std::abs(m.diag[static_cast<std::size_t>(c)]) * (1 + 0.5 * k);
    col.rows.push_back(c);
    col.values.push_back(a);
    col.diag -= a;
    m.diag[static_cast<std::size_t>(c)] -= a;
  }
  border.columns[0].rhs = 0.7;
  border.columns[1].rhs = -1.3;
  // The assembled matrix and Eigen's solution.
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t c = 0; c < n; ++c)
    t.emplace_back(static_cast<int>(c), static_cast<int>(c), m.diag[c]);
  for (int f = 0; f < mesh.internal_faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    t.emplace_back(mesh.owner(f), mesh.neighbour(f), m.upper[fs]);
    t.emplace_back(mesh.neighbour(f), mesh.owner(f), m.lower[fs]);
  }
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(n + 2));
  for (std::size_t c = 0; c < n; ++c) rhs[static_cast<Eigen::Index>(c)] = m.source[c];
  for (int k = 0; k < 2; ++k) {
    const auto& col = border.columns[static_cast<std::size_t>(k)];
    const int row = static_cast<int>(n) + k;
    for (std::size_t e = 0; e < col.rows.size(); ++e) {
      t.emplace_back(col.rows[e], row, col.values[e]);
      t.emplace_back(row, col.rows[e], col.values[e]);
    }
    t.emplace_back(row, row, col.diag);
    rhs[row] = col.rhs;
  }
  const auto size = static_cast<Eigen::Index>(n + 2);
  Eigen::SparseMatrix<double> A(size, size);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXd exact = lu.solve(rhs);
  double scale = 0;
  for (Eigen::Index i = 0; i < size; ++i) scale = std::max(scale, std::abs(exact[i]));
  const auto solve = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(threads));
    fv::LinearSolver solver(mesh, fv::Tolerance(1e-12));
    std::vector<double> x(n, 0.0), lambda(2, 0.0);
    const auto s = solver.solve_bordered(m, border, x, lambda, fv::SymmetricMethod::cg_amg);
    EXPECT_GT(s.iterations, 0);
    x.insert(x.end(), lambda.begin(), lambda.end());
    return x;
  };
  const auto x = solve(1);
  double error = 0;
  for (Eigen::Index i = 0; i < size; ++i)
    error = std::max(error, std::abs(x[static_cast<std::size_t>(i)] - exact[i]));
  std::printf("bordered: max |x - x_LU| = %.3g of max |x| %.3g; lambda %.6g %.6g\n", error, scale,
              x[n], x[n + 1]);
  EXPECT_LT(error, 1e-9 * scale);
  EXPECT_GT(std::abs(x[n]), 1e-3 * scale);  // the border is not idle
  EXPECT_EQ(x, solve(2));
  // The border rides through the multigrid (amg_pcg.hpp, steps B): about the iterations of the
  // matrix alone, and a plain solve on the same hierarchy afterwards is unchanged.
  fv::LinearSolver solver(mesh, fv::Tolerance(1e-12));
  std::vector<double> plain(n, 0.0), again(n, 0.0), xb(n, 0.0), lb(2, 0.0);
  const auto alone = solver.solve_symmetric(m, plain, fv::SymmetricMethod::cg_amg);
  const auto bordered = solver.solve_bordered(m, border, xb, lb, fv::SymmetricMethod::cg_amg);
  const auto after = solver.solve_symmetric(m, again, fv::SymmetricMethod::cg_amg);
  std::printf("iterations: matrix alone %d, bordered %d\n", alone.iterations, bordered.iterations);
  EXPECT_LE(bordered.iterations, alone.iterations + 2);
  EXPECT_EQ(after.iterations, alone.iterations);
  EXPECT_EQ(again, plain);
  // The levels keep a border between solves with the same columns and coefficients (B1 skipped):
  // the same bits as a new solver's; a column that changes is taken up.
  const auto bordered_solve = [&](fv::LinearSolver& s, const fv::Border& b) {
    std::vector<double> xs(n, 0.0), ls(2, 0.0);
    s.solve_bordered(m, b, xs, ls, fv::SymmetricMethod::cg_amg);
    xs.insert(xs.end(), ls.begin(), ls.end());
    return xs;
  };
  EXPECT_EQ(bordered_solve(solver, border), x);
  EXPECT_EQ(bordered_solve(solver, border), x);
  fv::Border halved = border;
  for (double& v : halved.columns[1].values) v *= 0.5;
  halved.columns[1].diag *= 0.5;
  fv::LinearSolver fresh(mesh, fv::Tolerance(1e-12));
  const auto expected = bordered_solve(fresh, halved);
  EXPECT_NE(expected, x);
  EXPECT_EQ(bordered_solve(solver, halved), expected);
  EXPECT_EQ(bordered_solve(solver, border), x);
  std::vector<double> x0(n), lambda(2);
  EXPECT_THROW(solver.solve_bordered(m, border, x0, lambda, fv::SymmetricMethod::cholmod),
               std::invalid_argument);
  lambda.resize(1);
  EXPECT_THROW(solver.solve_bordered(m, border, x0, lambda, fv::SymmetricMethod::cg_amg),
               std::invalid_argument);
}
