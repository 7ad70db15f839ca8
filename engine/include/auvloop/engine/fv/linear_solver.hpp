// SPDX-License-Identifier: GPL-3.0-or-later
// Linear solvers for fv::Matrix equations. The matrix pattern is the grid's face addressing, so
// the row-compressed copy the iterative solvers work on (with its fixed partition for the
// parallel smoother) and its map from faces are built once per grid, and each solve only loads
// the coefficients; work vectors and multigrid hierarchies are kept between solves. A symbolic
// Cholesky analysis is done once and only the numeric factorisation is repeated (and skipped when
// the coefficients have not changed, as for the pressure matrix on a fixed grid and time step).
// Every iterative method runs in parallel on the engine's thread pool with results that are
// bitwise the same for any number of threads; CHOLMOD, cholmod-pcg, cg-ic and cg-dic's sweeps are
// serial.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "auvloop/engine/fv/matrix.hpp"

namespace auvloop::engine::fv {

enum class SymmetricMethod {
  cholmod,      // sparse Cholesky (SuiteSparse CHOLMOD, supernodal), exact
  cholmod_pcg,  // CG preconditioned by the Cholesky factor of an earlier matrix, refactorised
                // only when the iterations exceed a limit
  cg_incomplete_cholesky,  // Eigen CG with its IncompleteCholesky (threshold, with fill)
  cg_dic,     // conjugate gradients, diagonal incomplete Cholesky (OpenFOAM's DIC), serial sweeps
  cg_jacobi,  // conjugate gradients, diagonal preconditioner
  cg_amg,     // flexible CG, aggregation algebraic multigrid K-cycle (engine/src/fv/amg_pcg.hpp)
};
enum class AsymmetricMethod {
  // Symmetric hybrid Gauss-Seidel sweeps (engine/src/fv/sparse.hpp), as OpenFOAM's smoothSolver:
  // for diagonally dominant equations (momentum, transport); after 20 sweep pairs without
  // convergence it goes on with bicgstab_jacobi from where it stands.
  gauss_seidel,
  bicgstab_jacobi,  // BiCGSTAB with a diagonal preconditioner
  bicgstab_gs,      // BiCGSTAB preconditioned by a symmetric hybrid Gauss-Seidel sweep pair
  bicgstab_ilut,    // Eigen BiCGSTAB with incomplete LU (threshold; serial)
};

const char* to_string(SymmetricMethod m);
SymmetricMethod symmetric_method_from_string(const std::string& s);
const char* to_string(AsymmetricMethod m);
AsymmetricMethod asymmetric_method_from_string(const std::string& s);

// What an iterative solve's tolerance bounds.
enum class ResidualNorm {
  relative,    // |b - A x| <= tolerance |b| (2-norms)
  normalised,  // OpenFOAM's normalised residual (SolveStats) <= tolerance, as its solvers'
               // `tolerance` keyword: the like-for-like setting against OpenFOAM
};
const char* to_string(ResidualNorm n);
ResidualNorm residual_norm_from_string(const std::string& s);

// When an iterative solve has converged. The engine's own methods (cg-amg, cg-jacobi, BiCGSTAB
// and Gauss-Seidel) honour `norm`; Eigen's and CHOLMOD's take `value` as a relative tolerance.
struct Tolerance {
  double value = 1e-8;
  ResidualNorm norm = ResidualNorm::relative;
  Tolerance() = default;
  Tolerance(double v, ResidualNorm n = ResidualNorm::relative) : value(v), norm(n) {}  // NOLINT
  // rnorm, bnorm: 2-norms of b - A x and of b; normalised: OpenFOAM's normalised residual.
  [[nodiscard]] bool met(double rnorm, double bnorm, double normalised) const {
    return norm == ResidualNorm::relative ? rnorm <= value * bnorm : normalised <= value;
  }
};

struct SolveStats {
  int iterations = 0;  // Krylov iterations, or Gauss-Seidel sweep pairs
  // OpenFOAM's normalised residual sum |b - A x| / sum (|A x - A xbar| + |b - A xbar|), xbar the
  // mean of x (scale-free, so one tolerance fits every equation), at the start of the solve
  double initial_residual = 0;
  double final_residual = 0;
  bool factorised = false;  // a numeric factorisation was (re)computed in this call
};

// Coefficients of an equation beyond its mesh's face pattern: an overset mesh's implicit
// coupling (overset.hpp), the donors of a fringe cell's row and an active row's fringe
// neighbours. Row rows[k] has the entries columns / values at [start[k], start[k + 1]); rows
// ascending, each once, no column twice in a row, none on the diagonal; an entry in a face
// neighbour's column adds to the Matrix's coefficient there.
struct ExtraEntries {
  std::vector<int> rows, start{0}, columns;
  std::vector<double> values;
  void clear() {
    rows.clear();
    start.assign(1, 0);
    columns.clear();
    values.clear();
  }
  void begin_row(int row) { rows.push_back(row); }
  void add(int column, double value) {
    columns.push_back(column);
    values.push_back(value);
  }
  void end_row() { start.push_back(static_cast<int>(columns.size())); }
  [[nodiscard]] int size() const { return static_cast<int>(rows.size()); }
  // y += sign * E x.
  void multiply_add(std::span<const double> x, std::span<double> y, double sign = 1.0) const;
};

// K extra unknowns lambda bordering a symmetric matrix m of n rows, each coupled symmetrically:
//   m x + sum_k column_k lambda_k = source,   column_k . x + diag_k lambda_k = rhs_k.
// An overset mesh's pressure equation with the mass balance of its open components: each
// component's fringe ring, its values shifted by lambda_k, is one more cell of the Laplacian
// (docs/overset-flow.md). Columns are sparse, rows ascending, each at most once; diag_k < 0 (a
// Laplacian's sign) and the bordered matrix negative definite, as the pressure equation is.
struct Border {
  struct Column {
    std::vector<int> rows;
    std::vector<double> values;
    double diag = 0, rhs = 0;
  };
  std::vector<Column> columns;
};

class LinearSolver {
 public:
  LinearSolver(const Mesh& mesh, Tolerance tolerance);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Solves A x = source for a symmetric matrix (upper == lower); x holds the initial guess.
  // `tolerance` > 0 replaces the solver's own value for this solve (the iterative methods').
  SolveStats solve_symmetric(const Matrix& m, std::span<double> x, SymmetricMethod method,
                             double tolerance = 0);
  // The structure a method builds once from the first matrix it solves (cg-amg's aggregates),
  // built from `m` instead (same pattern, any coefficients); other methods ignore it. A matrix
  // that depends on the grid alone (a geometric Laplacian) makes the later solves independent
  // of the run's history, as an exact restart needs.
  void plan_symmetric(const Matrix& m, SymmetricMethod method);
  // `tolerance` > 0 replaces the solver's own value for this solve (in the solver's norm).
  SolveStats solve_asymmetric(const Matrix& m, std::span<double> x, AsymmetricMethod method,
                              double tolerance = 0);
  // Solves (m + extra) x = source with flexible GMRES (engine/src/fv/fgmres.hpp), preconditioned
  // by a solver of m alone: for a symmetric m (the pressure equation of an implicitly coupled
  // overset mesh) a cycle of cg-amg's multigrid, a CHOLMOD solve for cholmod and cholmod-pcg, a
  // symmetric Gauss-Seidel sweep pair for the others; for an asymmetric m (momentum) the sweep
  // pair. `tolerance` > 0 replaces the solver's own for this solve.
  SolveStats solve_coupled(const Matrix& m, const ExtraEntries& extra, std::span<double> x,
                           std::optional<SymmetricMethod> symmetric, double tolerance = 0);
  // The multigrid of solve_coupled for symmetric m, planned from this matrix (any coefficients
  // of the pattern the later solves pass, as plan_symmetric; a geometric Laplacian makes the
  // solves independent of the run's history, so that a restart continues bitwise).
  void plan_coupled(const Matrix& m, const ExtraEntries& extra);
  // Solves the bordered system (Border) for x (n values, the initial guess) and lambda (one per
  // column, likewise): cg-amg's flexible CG with the border carried through every level of its
  // multigrid as rows of their own (never aggregated). `method` must be cg_amg
  // (std::invalid_argument otherwise).
  SolveStats solve_bordered(const Matrix& m, const Border& border, std::span<double> x,
                            std::span<double> lambda, SymmetricMethod method, double tolerance = 0);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace auvloop::engine::fv
