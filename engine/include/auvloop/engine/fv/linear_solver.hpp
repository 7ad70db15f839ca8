// SPDX-License-Identifier: GPL-3.0-or-later
// Linear solvers for fv::Matrix equations. The matrix pattern is the grid's face addressing, so
// the compressed-column copy and its index map are built once per grid; a symbolic Cholesky
// analysis is done once and only the numeric factorisation is repeated (and skipped when the
// coefficients have not changed, as for the pressure matrix on a fixed grid and time step).
#pragma once

#include <memory>
#include <span>
#include <string>

#include "auvloop/engine/fv/matrix.hpp"

namespace auvloop::engine::fv {

enum class SymmetricMethod {
  cholmod,      // sparse Cholesky (SuiteSparse CHOLMOD, supernodal), exact
  cholmod_pcg,  // CG preconditioned by the Cholesky factor of an earlier matrix, refactorised
                // only when the iterations exceed a limit
  cg_incomplete_cholesky,  // Eigen CG with its IncompleteCholesky (threshold, with fill)
  cg_dic,     // conjugate gradients, diagonal incomplete Cholesky (OpenFOAM's DIC), serial sweeps
  cg_jacobi,  // conjugate gradients, diagonal preconditioner, parallel (oneTBB)
  cg_amg,     // flexible CG, aggregation algebraic multigrid V-cycle (engine/src/fv/amg_pcg.hpp)
};
enum class AsymmetricMethod {
  bicgstab_jacobi,  // Eigen BiCGSTAB with a diagonal preconditioner
  bicgstab_ilut,    // Eigen BiCGSTAB with incomplete LU (threshold)
};

const char* to_string(SymmetricMethod m);
SymmetricMethod symmetric_method_from_string(const std::string& s);

struct SolveStats {
  int iterations = 0;
  double initial_residual = 0;  // |b - A x0| / normalisation (OpenFOAM style)
  double final_residual = 0;
  bool factorised = false;  // a numeric factorisation was (re)computed in this call
};

class LinearSolver {
 public:
  LinearSolver(const Mesh& mesh, double tolerance);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Solves A x = source for a symmetric matrix (upper == lower); x holds the initial guess.
  SolveStats solve_symmetric(const Matrix& m, std::span<double> x, SymmetricMethod method);
  SolveStats solve_asymmetric(const Matrix& m, std::span<double> x, AsymmetricMethod method);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// OpenFOAM's normalised residual: sum |b - A x| / sum (|A x - A xbar| + |b - A xbar|), xbar the
// mean of x; scale-free, so one tolerance fits every equation.
double normalised_residual(const Mesh& mesh, const Matrix& m, std::span<const double> x);

}  // namespace auvloop::engine::fv
