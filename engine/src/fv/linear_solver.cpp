// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/linear_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include "amg_pcg.hpp"
#include "dic_pcg.hpp"
#include "parallel_cg.hpp"

namespace auvloop::engine::fv {

namespace {
using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Vec = Eigen::VectorXd;
}  // namespace

const char* to_string(SymmetricMethod m) {
  switch (m) {
    case SymmetricMethod::cholmod:
      return "cholmod";
    case SymmetricMethod::cholmod_pcg:
      return "cholmod-pcg";
    case SymmetricMethod::cg_incomplete_cholesky:
      return "cg-ic";
    case SymmetricMethod::cg_dic:
      return "cg-dic";
    case SymmetricMethod::cg_jacobi:
      return "cg-jacobi";
    case SymmetricMethod::cg_amg:
      return "cg-amg";
  }
  return "?";
}

SymmetricMethod symmetric_method_from_string(const std::string& s) {
  for (auto m : {SymmetricMethod::cholmod, SymmetricMethod::cholmod_pcg,
                 SymmetricMethod::cg_incomplete_cholesky, SymmetricMethod::cg_dic,
                 SymmetricMethod::cg_jacobi, SymmetricMethod::cg_amg})
    if (s == to_string(m)) return m;
  throw std::invalid_argument("unknown pressure solver '" + s +
                              "' (cholmod, cholmod-pcg, cg-ic, cg-dic, cg-jacobi, cg-amg)");
}

struct LinearSolver::Impl {
  const Mesh& mesh;
  double tolerance;
  Sparse A;
  std::vector<int> diag_pos, upper_pos, lower_pos;  // positions in A.valuePtr()
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> cholmod;
  bool analysed = false;
  std::vector<double> factorised_values;  // the coefficients of the current factorisation
  int last_pcg_iterations = 0;
  std::unique_ptr<AmgPcg> amg;  // built on the first cg-amg solve

  Impl(const Mesh& m, double tol) : mesh(m), tolerance(tol) {
    std::vector<Eigen::Triplet<double, int>> t;
    for (int c = 0; c < mesh.cells(); ++c) t.emplace_back(c, c, 1.0);
    for (int f = 0; f < mesh.internal_faces(); ++f) {
      t.emplace_back(mesh.owner(f), mesh.neighbour(f), 1.0);
      t.emplace_back(mesh.neighbour(f), mesh.owner(f), 1.0);
    }
    A.resize(mesh.cells(), mesh.cells());
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    auto position = [&](int row, int col) {
      const int* inner = A.innerIndexPtr();
      for (int k = A.outerIndexPtr()[col]; k < A.outerIndexPtr()[col + 1]; ++k)
        if (inner[k] == row) return k;
      throw std::logic_error("fv::LinearSolver: entry missing from the pattern");
    };
    for (int c = 0; c < mesh.cells(); ++c) diag_pos.push_back(position(c, c));
    for (int f = 0; f < mesh.internal_faces(); ++f) {
      upper_pos.push_back(position(mesh.owner(f), mesh.neighbour(f)));
      lower_pos.push_back(position(mesh.neighbour(f), mesh.owner(f)));
    }
  }

  void factorise(SolveStats& stats) {
    if (!analysed) {
      cholmod.analyzePattern(A);
      analysed = true;
    }
    cholmod.factorize(A);
    if (cholmod.info() != Eigen::Success)
      throw std::runtime_error("CHOLMOD: the pressure matrix is not positive definite");
    factorised_values.assign(A.valuePtr(), A.valuePtr() + A.nonZeros());
    stats.factorised = true;
  }

  // Conjugate gradients on A x = b preconditioned by the current factorisation (of a nearby
  // matrix). Serial, so the result does not depend on the number of threads. Returns the
  // iterations, or -1 when the tolerance is not reached within `max_iterations` (a stale factor,
  // or a tolerance below round-off).
  int pcg(const Vec& b, Eigen::Map<Vec>& x, int max_iterations) {
    Vec r = b - A.selfadjointView<Eigen::Lower>() * x;
    const double bnorm = std::max(b.norm(), 1e-300);
    if (r.norm() <= tolerance * bnorm) return 0;
    Vec z = cholmod.solve(r);
    Vec p = z;
    double rz = r.dot(z);
    for (int it = 1; it <= max_iterations; ++it) {
      const Vec Ap = A.selfadjointView<Eigen::Lower>() * p;
      const double alpha = rz / p.dot(Ap);
      x += alpha * p;
      r -= alpha * Ap;
      if (r.norm() <= tolerance * bnorm) return it;
      z = cholmod.solve(r);
      const double rz_new = r.dot(z);
      p = z + (rz_new / rz) * p;
      rz = rz_new;
    }
    return -1;
  }

  void load(const Matrix& m) {
    double* v = A.valuePtr();
    for (std::size_t c = 0; c < diag_pos.size(); ++c) v[diag_pos[c]] = m.diag[c];
    for (std::size_t f = 0; f < upper_pos.size(); ++f) {
      v[upper_pos[f]] = m.upper[f];
      v[lower_pos[f]] = m.lower[f];
    }
  }
};

LinearSolver::LinearSolver(const Mesh& mesh, double tolerance)
    : impl_(std::make_unique<Impl>(mesh, tolerance)) {}
LinearSolver::~LinearSolver() = default;

namespace {
template <class Solver>
SolveStats iterate(Solver& solver, const Sparse& A, const std::vector<double>& source,
                   std::span<double> x, double tolerance) {
  solver.setTolerance(tolerance);
  solver.setMaxIterations(5000);
  solver.compute(A);
  Eigen::Map<const Vec> b(source.data(), static_cast<Eigen::Index>(source.size()));
  Eigen::Map<Vec> xv(x.data(), static_cast<Eigen::Index>(x.size()));
  Vec guess = xv;
  xv = solver.solveWithGuess(b, guess);
  SolveStats s;
  s.iterations = static_cast<int>(solver.iterations());
  s.final_residual = solver.error();
  if (solver.info() != Eigen::Success && !(solver.error() < 1e3 * tolerance))
    throw std::runtime_error(
        fmt::format("Eigen Krylov solver did not converge in {} iterations: relative residual "
                    "{:.3g} (tolerance {:.3g})",
                    solver.iterations(), solver.error(), tolerance));
  return s;
}
}  // namespace

SolveStats LinearSolver::solve_symmetric(const Matrix& m, std::span<double> x,
                                         SymmetricMethod method) {
  auto& I = *impl_;
  SolveStats stats;
  stats.initial_residual = normalised_residual(I.mesh, m, x);
  // Eigen's CG and CHOLMOD want a positive definite matrix: the Laplacian is negative definite,
  // so solve (-A) x = -b.
  Matrix neg = -m;
  I.load(neg);
  if (method == SymmetricMethod::cholmod) {
    if (!std::equal(I.factorised_values.begin(), I.factorised_values.end(), I.A.valuePtr()) ||
        I.factorised_values.empty())
      I.factorise(stats);
    Eigen::Map<const Vec> b(neg.source.data(), static_cast<Eigen::Index>(neg.source.size()));
    Eigen::Map<Vec>(x.data(), static_cast<Eigen::Index>(x.size())) = I.cholmod.solve(b);
  } else if (method == SymmetricMethod::cholmod_pcg) {
    // Refactorise when the old factor has become a poor preconditioner (more than 10
    // iterations last time, or no convergence in 30); with a fresh factor the solve is direct.
    Eigen::Map<const Vec> b(neg.source.data(), static_cast<Eigen::Index>(neg.source.size()));
    Eigen::Map<Vec> xv(x.data(), static_cast<Eigen::Index>(x.size()));
    int iterations = -1;
    if (!I.factorised_values.empty() && I.last_pcg_iterations <= 10) {
      const Vec x0 = xv;
      iterations = I.pcg(b, xv, 30);
      if (iterations < 0) xv = x0;
    }
    if (iterations < 0) {
      I.factorise(stats);
      xv = I.cholmod.solve(b);
      iterations = 0;
    }
    stats.iterations = I.last_pcg_iterations = iterations;
  } else if (method == SymmetricMethod::cg_incomplete_cholesky) {
    Eigen::ConjugateGradient<Sparse, Eigen::Lower | Eigen::Upper,
                             Eigen::IncompleteCholesky<double, Eigen::Lower>>
        cg;
    const auto s = iterate(cg, I.A, neg.source, x, I.tolerance);
    stats.iterations = s.iterations;
  } else if (method == SymmetricMethod::cg_dic) {
    stats.iterations = dic_pcg(I.mesh, neg, x, I.tolerance, 20000);
  } else if (method == SymmetricMethod::cg_amg) {
    if (!I.amg) I.amg = std::make_unique<AmgPcg>(I.mesh);
    stats.iterations = I.amg->solve(neg, x, I.tolerance, 2000);
  } else {
    const Vec b = Eigen::Map<const Vec>(neg.source.data(), static_cast<Eigen::Index>(x.size()));
    Eigen::Map<Vec> xv(x.data(), static_cast<Eigen::Index>(x.size()));
    stats.iterations = parallel_jacobi_cg(I.A, b, xv, I.tolerance, 20000);
  }
  stats.final_residual = normalised_residual(I.mesh, m, x);
  return stats;
}

SolveStats LinearSolver::solve_asymmetric(const Matrix& m, std::span<double> x,
                                          AsymmetricMethod method) {
  auto& I = *impl_;
  SolveStats stats;
  stats.initial_residual = normalised_residual(I.mesh, m, x);
  I.load(m);
  if (method == AsymmetricMethod::bicgstab_ilut) {
    Eigen::BiCGSTAB<Sparse, Eigen::IncompleteLUT<double>> s;
    stats.iterations = iterate(s, I.A, m.source, x, I.tolerance).iterations;
  } else {
    Eigen::BiCGSTAB<Sparse> s;
    stats.iterations = iterate(s, I.A, m.source, x, I.tolerance).iterations;
  }
  stats.final_residual = normalised_residual(I.mesh, m, x);
  return stats;
}

double normalised_residual(const Mesh& mesh, const Matrix& m, std::span<const double> x) {
  const auto n = static_cast<std::size_t>(mesh.cells());
  double mean = 0;
  for (std::size_t i = 0; i < n; ++i) mean += x[i];
  mean /= static_cast<double>(n);
  std::vector<double> Ax(n), Axbar(n);
  const std::vector<double> xbar(n, mean);
  m.multiply(mesh, x, Ax);
  m.multiply(mesh, xbar, Axbar);
  double r = 0, norm = 0;
  for (std::size_t i = 0; i < n; ++i) {
    r += std::abs(m.source[i] - Ax[i]);
    norm += std::abs(Ax[i] - Axbar[i]) + std::abs(m.source[i] - Axbar[i]);
  }
  return r / (norm + 1e-300);
}

}  // namespace auvloop::engine::fv
