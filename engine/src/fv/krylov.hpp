// SPDX-License-Identifier: GPL-3.0-or-later
// Single-level iterative solvers on a BlockCsr, private to engine/src; every vector operation and
// product is parallel with fixed-block sums (parallel.hpp), so the iterates do not depend on the
// number of threads. All stop when the Tolerance (linear_solver.hpp) is met, report OpenFOAM's
// normalised residuals at the start and end, and throw std::runtime_error
// when the iteration limit is reached or the residual stops being finite.
//
//   gauss_seidel_solve  symmetric hybrid Gauss-Seidel sweeps (a forward sweep, then a backward one;
//                       sparse.hpp), the residual checked after each pair: the momentum solver
//                       (OpenFOAM's smoothSolver with symGaussSeidel). Diagonally dominant
//                       matrices only; when `max_sweeps` pairs have not converged it reports
//                       false in `converged` instead of throwing, for the caller to go on with a
//                       Krylov method from the current x.
//   bicgstab            van der Vorst's BiCGSTAB, right-preconditioned by the inverse diagonal
//                       (Jacobi) or by one symmetric hybrid Gauss-Seidel sweep pair from zero,
//                       restarted with a new shadow residual when it breaks down.
//   jacobi_cg           conjugate gradients with the Jacobi preconditioner (symmetric positive
//                       definite A).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "sparse.hpp"

namespace auvloop::engine::fv {

// Work vectors of a solver, sized on first use and kept (a solve then allocates nothing).
struct KrylovWork {
  std::vector<double> r, r_hat, p, v, s, t, y, z;
  void resize(int n);
};

// The start of an iterative solve: r = b - A x, the normalised residual (initial and, so far,
// final), OpenFOAM's normalisation for the later ones (`normalisation` if > 0: a solve that goes
// on from another method's, whose normalisation it keeps), |b| and |r|.
struct SolveStart {
  SolveStats stats;
  double normalisation = 0, bnorm = 0, rnorm = 0;
  [[nodiscard]] bool converged(const Tolerance& tolerance) const {
    return tolerance.met(rnorm, bnorm, stats.initial_residual);
  }
};
SolveStart start_solve(const BlockCsr& A, std::span<const double> b, std::span<const double> x,
                       std::span<double> r, double normalisation = 0);

// y = A x (or z = P r): a linear map on vectors of the system's size n.
using LinearMap = std::function<void(std::span<const double>, std::span<double>)>;

// The same start for a matrix known only as a product (FGMRES's coupled systems, a bordered
// matrix): r = b - A x and OpenFOAM's normalisation sum |A x - A xbar| + |b - A xbar| with
// A xbar = xbar A 1. `Ax` and `ones` are scratch vectors of size n.
SolveStart start_solve(int n, const LinearMap& A, std::span<const double> b,
                       std::span<const double> x, std::span<double> r, std::span<double> Ax,
                       std::span<double> ones);

struct SmootherResult {
  SolveStats stats;
  bool converged = false;
  double normalisation = 0;  // of its residuals, for a method that goes on from its x
};

SmootherResult gauss_seidel_solve(const BlockCsr& A, std::span<const double> b, std::span<double> x,
                                  const Tolerance& tolerance, int max_sweeps, KrylovWork& work);
enum class Preconditioner { jacobi, gauss_seidel };
SolveStats bicgstab(const BlockCsr& A, std::span<const double> b, std::span<double> x,
                    const Tolerance& tolerance, int max_iterations, KrylovWork& work,
                    Preconditioner preconditioner, double normalisation = 0);
SolveStats jacobi_cg(const BlockCsr& A, std::span<const double> b, std::span<double> x,
                     const Tolerance& tolerance, int max_iterations, KrylovWork& work);

}  // namespace auvloop::engine::fv
