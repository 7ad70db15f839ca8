// SPDX-License-Identifier: GPL-3.0-or-later
// Conjugate gradients preconditioned by an aggregation algebraic multigrid V-cycle, private to
// engine/src. The pressure equation dominates the cost of a PIMPLE step, and single-level
// preconditioners (DIC) need O(N^(1/3)) more iterations as a 3D grid is refined; a multigrid
// cycle removes the smooth error that those iterations spend their time on.
//
// The method (after Notay's AGMG: "An aggregation-based algebraic multigrid method", ETNA 37,
// 2010, and Notay and Vassilevski's K-cycle, Numer. Linear Algebra Appl. 15, 2008):
//   - two passes of pairwise aggregation per level, each pairing a cell with its most strongly
//     coupled free neighbour (largest |a_ij|, if at least a quarter of its largest coupling),
//     give aggregates of about four cells; the coarse matrix is the Galerkin product P^T A P
//     with piecewise-constant P (sums of the fine coefficients, so it is symmetric positive
//     definite when A is, and keeps the LDU face structure);
//   - a cycle with one forward Gauss-Seidel sweep before and one backward sweep after the coarse
//     correction, a dense Cholesky solve on the coarsest level, and on every other level the
//     K-cycle: the coarse problem is solved by two steps of flexible CG preconditioned by the
//     next cycle. Unsmoothed aggregation in a plain V-cycle loses accuracy with every level; the
//     K-cycle keeps the iteration count nearly independent of the grid size, at about twice a
//     V-cycle's cost with four-to-one coarsening. It is a nonlinear preconditioner, so the
//     outer iteration is flexible CG (Polak-Ribiere beta; Notay, SIAM J. Sci. Comput. 22, 2000).
// The aggregates depend only on the matrix given to the first solve and are kept (the pattern is
// the grid's and does not change); the coarse coefficients are recomputed when the matrix has
// changed since the last solve (the correctors of one outer iteration share one matrix). All
// loops run in a fixed order, so results do not depend on the thread count.
#pragma once

#include <memory>
#include <span>

#include "auvloop/engine/fv/matrix.hpp"

namespace auvloop::engine::fv {

class AmgPcg {
 public:
  explicit AmgPcg(const Mesh& mesh);
  ~AmgPcg();
  AmgPcg(const AmgPcg&) = delete;
  AmgPcg& operator=(const AmgPcg&) = delete;

  // Solves A x = A.source for a symmetric positive definite A on the mesh's pattern
  // (upper == lower); x holds the initial guess. Stops at |b - A x| <= tolerance |b|; returns
  // the iterations, throws std::runtime_error after max_iterations.
  int solve(const Matrix& A, std::span<double> x, double tolerance, int max_iterations);

  [[nodiscard]] int levels() const;
  [[nodiscard]] int cells(int level) const;

 private:
  struct Hierarchy;
  const Mesh& mesh_;
  std::unique_ptr<Hierarchy> h_;
};

}  // namespace auvloop::engine::fv
