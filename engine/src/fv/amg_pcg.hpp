// SPDX-License-Identifier: GPL-3.0-or-later
// Conjugate gradients preconditioned by an aggregation algebraic multigrid K-cycle, private to
// engine/src. The pressure equation dominates the cost of a PIMPLE step, and single-level
// preconditioners (DIC) need O(N^(1/3)) more iterations as a 3D grid is refined; a multigrid
// cycle removes the smooth error that those iterations spend their time on.
//
// The method (after Notay's AGMG: "An aggregation-based algebraic multigrid method", ETNA 37,
// 2010, and Notay and Vassilevski's K-cycle, Numer. Linear Algebra Appl. 15, 2008):
//   1. setup, once per grid (from the first matrix, or the one given to plan()): three passes of
//   pairwise aggregation per level, each pairing a row
//      with its most strongly coupled free neighbour (largest |a_ij|, if at least a quarter of
//      its largest coupling), give aggregates of about eight rows (AGMG's two passes give four:
//      amg_pcg.cpp says why three); coarse levels until 64 rows or until a level keeps more
//      than 0.6 of its rows;
//   2. coefficients, whenever the matrix changed since the last solve (the correctors of one
//      outer iteration share it): the Galerkin product P^T A P with piecewise-constant P (sums of
//      the fine coefficients: symmetric positive definite when A is), row by coarse row, and the
//      Cholesky factor of the coarsest (dense) matrix;
//   3. the cycle on level l, from x = 0: one forward hybrid Gauss-Seidel sweep (sparse.hpp), the
//      residual restricted (summed over each aggregate), the coarse correction (exact on the
//      coarsest level; elsewhere the K-cycle: two steps of flexible CG preconditioned by the next
//      cycle, the second only when the first left more than a quarter of the residual),
//      prolonged (added to every row of the aggregate), one backward sweep;
//   4. flexible CG on the finest level (Polak-Ribiere beta, since the K-cycle is a nonlinear
//      preconditioner; Notay, SIAM J. Sci. Comput. 22, 2000), stopping at |b - A x| <= tol |b|.
// A bordered system (solve_bordered: an overset mesh's pressure equation with its mass balance,
// K Lagrange multipliers lambda_k, each coupled to a sparse column C_k):
//   B1. per level l the columns restricted with the rows, C_{l+1} = P^T C_l (summed over each
//       aggregate), E unchanged: lambda stays a row of its own on every level, so the Galerkin
//       matrix of level l+1 is the bordered P^T A_l P;
//   B2. the smoother on level l: the row sweep (step 3), then per k the Gauss-Seidel update
//       lambda_k = (g_k - C_k . x) / E_k; the backward sweep in the reverse order (lambda first,
//       then the rows with b - C lambda, b shifted at the columns' rows and restored after):
//       a symmetric smoother;
//   B3. the coarsest level's dense Cholesky factor of the bordered matrix; the K-cycle's and the
//       outer CG's products and dot products over the n + K values. B1 and B3's factor are
//       redone only when the coefficients or the columns change.
// Without a border every step is the plain one, bit for bit.
// The cycle (steps 3) reads every level's coefficients in single precision (BlockCsr::keep_single:
// 8 instead of 12 bytes per entry, a third less memory traffic in the smoother and restriction,
// where the solve spends its time) with every vector and sum in double; the Galerkin products
// and the outer CG are in double. Every loop is parallel over rows with fixed partitions and
// fixed-block sums (parallel.hpp), so the iterates do not depend on the number of threads. Work
// vectors live with the hierarchy: a solve allocates nothing.
#pragma once

#include <memory>
#include <span>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "krylov.hpp"
#include "sparse.hpp"

namespace auvloop::engine::fv {

class AmgPcg {
 public:
  // `symmetric` false: a matrix that is not symmetric (an implicitly coupled overset system,
  // with its interpolation rows): the K-cycle's two Krylov steps are GCR's (Notay's AGMG for
  // nonsymmetric matrices), the coarsest level an LU factor; only precondition() applies then.
  explicit AmgPcg(bool symmetric = true);
  ~AmgPcg();
  AmgPcg(const AmgPcg&) = delete;
  AmgPcg& operator=(const AmgPcg&) = delete;

  // Solves A x = b for a symmetric positive definite A that keeps its single-precision copy
  // (BlockCsr::keep_single); x holds the initial guess. The pattern of A must be that of the
  // first call; `changed`: its coefficients differ from the last call's.
  // Stops when `tolerance` is met; throws std::runtime_error after max_iterations.
  SolveStats solve(const BlockCsr& A, bool changed, std::span<const double> b, std::span<double> x,
                   const Tolerance& tolerance, int max_iterations);
  // Step 1 from this matrix (the one later solves pass, holding other coefficients then) instead
  // of from the first solve's: aggregates from a matrix that depends on the grid alone make
  // every solve independent of the run's history, so that a restart continues bitwise.
  void plan(const BlockCsr& A);
  // Solves the bordered system [A C; C^T E] [x; lambda] = [b; g] (linear_solver.hpp's Border:
  // K sparse columns C_k = sign * values, E = sign * diag, with `sign` the one A was loaded with,
  // so that the whole matrix is positive definite); b and x hold n + K values, x the guess. The
  // border rides through the hierarchy as K rows of their own on every level, never aggregated
  // (step B of amg_pcg.cpp), so the cycle sees the border's mode and the plain flexible CG of
  // solve() applies, with about the iterations of A alone. `changed` as for solve.
  SolveStats solve_bordered(const BlockCsr& A, bool changed, const Border& border, double sign,
                            std::span<const double> b, std::span<double> x,
                            const Tolerance& tolerance, int max_iterations);
  // One cycle from zero as the preconditioner of another Krylov method: z ~ A^-1 r (the K-cycle
  // makes it a nonlinear map, hence flexible GMRES, fgmres.cpp). `changed` as for solve: pass it
  // with a solve's first call, false after.
  void precondition(const BlockCsr& A, bool changed, std::span<const double> r,
                    std::span<double> z);

  [[nodiscard]] int levels() const;
  [[nodiscard]] int cells(int level) const;

 private:
  struct Hierarchy;
  // Step 4 from the start's residual (in the hierarchy's r) on the n + K values of the system.
  SolveStats fcg(const SolveStart& start, std::span<double> x, const Tolerance& tolerance,
                 int max_iterations);
  // The hierarchy for A, planned if there is none, with A's coefficients if `changed`.
  void prepare(const BlockCsr& A, bool changed);
  std::unique_ptr<Hierarchy> h_;
  bool symmetric_ = true;
  bool fresh_ = false;  // planned, no coefficients loaded yet
};

}  // namespace auvloop::engine::fv
