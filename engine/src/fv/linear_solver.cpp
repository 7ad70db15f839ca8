// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/linear_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "amg_pcg.hpp"
#include "dic_pcg.hpp"
#include "fgmres.hpp"
#include "krylov.hpp"
#include "parallel.hpp"

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

const char* to_string(AsymmetricMethod m) {
  switch (m) {
    case AsymmetricMethod::gauss_seidel:
      return "gauss-seidel";
    case AsymmetricMethod::bicgstab_jacobi:
      return "bicgstab";
    case AsymmetricMethod::bicgstab_gs:
      return "bicgstab-gs";
    case AsymmetricMethod::bicgstab_ilut:
      return "bicgstab-ilut";
  }
  return "?";
}

AsymmetricMethod asymmetric_method_from_string(const std::string& s) {
  for (auto m : {AsymmetricMethod::gauss_seidel, AsymmetricMethod::bicgstab_jacobi,
                 AsymmetricMethod::bicgstab_gs, AsymmetricMethod::bicgstab_ilut})
    if (s == to_string(m)) return m;
  throw std::invalid_argument("unknown momentum solver '" + s +
                              "' (gauss-seidel, bicgstab, bicgstab-gs, bicgstab-ilut)");
}

const char* to_string(ResidualNorm n) {
  return n == ResidualNorm::relative ? "relative" : "normalised";
}

ResidualNorm residual_norm_from_string(const std::string& s) {
  for (auto n : {ResidualNorm::relative, ResidualNorm::normalised})
    if (s == to_string(n)) return n;
  throw std::invalid_argument("unknown residual norm '" + s + "' (relative, normalised)");
}

SymmetricMethod symmetric_method_from_string(const std::string& s) {
  for (auto m : {SymmetricMethod::cholmod, SymmetricMethod::cholmod_pcg,
                 SymmetricMethod::cg_incomplete_cholesky, SymmetricMethod::cg_dic,
                 SymmetricMethod::cg_jacobi, SymmetricMethod::cg_amg})
    if (s == to_string(m)) return m;
  throw std::invalid_argument("unknown pressure solver '" + s +
                              "' (cholmod, cholmod-pcg, cg-ic, cg-dic, cg-jacobi, cg-amg)");
}

// The matrix in the form of Eigen and CHOLMOD (compressed columns, both triangles) with the map
// from the LDU coefficients: the direct and Eigen-based methods only.
struct EigenCopy {
  Sparse A;
  std::vector<int> diag_pos, upper_pos, lower_pos;  // positions in A.valuePtr()
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> cholmod;
  bool analysed = false;
  std::vector<double> factorised_values;  // the coefficients of the current factorisation
  int last_pcg_iterations = 0;
  double tolerance;

  EigenCopy(const Mesh& mesh, double tol) : tolerance(tol) {
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

  void load(const Matrix& m, double sign) {
    double* v = A.valuePtr();
    for (std::size_t c = 0; c < diag_pos.size(); ++c) v[diag_pos[c]] = sign * m.diag[c];
    for (std::size_t f = 0; f < upper_pos.size(); ++f) {
      v[upper_pos[f]] = sign * m.upper[f];
      v[lower_pos[f]] = sign * m.lower[f];
    }
  }
};

struct LinearSolver::Impl {
  const Mesh& mesh;
  Tolerance tolerance;
  // The iterative methods' copy of the matrix, shared by every equation solved here (momentum
  // and pressure have the same pattern); once cg-amg has run it keeps its single-precision copy
  // too, refreshed by every load that changes a coefficient (one more pass over the entries).
  BlockCsr csr;
  std::vector<int> entry_face;  // per csr entry: f where the row owns face f (upper), else ~f
  std::vector<double> b;        // the right-hand side as loaded
  bool loaded = false;
  KrylovWork work;
  FgmresWork fgmres_work;                      // solve_coupled's
  std::vector<double> bordered_b, bordered_x;  // solve_bordered's system: n + K values
  // solve_coupled's matrix: the face pattern and the extra entries' pattern it was built for
  // (an overset assembly: rebuilt, with its multigrid, when the assembly changes).
  struct Coupled {
    std::vector<int> rows, start, columns;
    BlockCsr csr;
    std::vector<int> entry_face;   // per csr entry: f (row owns face f), ~f, or kNoFace
    std::vector<int> entry_extra;  // per csr entry: the extra entry that adds to it, or -1
    std::vector<double> b;
    bool loaded = false;
    std::unique_ptr<AmgPcg> amg;
    static constexpr int kNoFace = std::numeric_limits<int>::min();

    [[nodiscard]] bool matches(const ExtraEntries& e) const {
      return loaded && e.rows == rows && e.start == start && e.columns == columns;
    }
    void build(const Mesh& mesh, const ExtraEntries& e) {
      rows = e.rows;
      start = e.start;
      columns = e.columns;
      const int n = mesh.cells();
      std::vector<int> row_start(static_cast<std::size_t>(n) + 1, 0), cols, tags, where;
      where.assign(e.columns.size(), -1);
      std::size_t next = 0;  // the next extra row
      for (int c = 0; c < n; ++c) {
        const auto begin = cols.size();
        for (int f : mesh.cell_faces(c)) {
          if (f >= mesh.internal_faces()) break;  // boundary faces come last
          const bool owner = mesh.owner(f) == c;
          cols.push_back(owner ? mesh.neighbour(f) : mesh.owner(f));
          tags.push_back(owner ? f : ~f);
        }
        if (next < e.rows.size() && e.rows[next] == c) {
          for (int k = e.start[next]; k < e.start[next + 1]; ++k) {
            const int col = e.columns[static_cast<std::size_t>(k)];
            const auto it =
                std::find(cols.begin() + static_cast<std::ptrdiff_t>(begin), cols.end(), col);
            if (it != cols.end()) {
              where[static_cast<std::size_t>(k)] = static_cast<int>(it - cols.begin());
            } else {
              where[static_cast<std::size_t>(k)] = static_cast<int>(cols.size());
              cols.push_back(col);
              tags.push_back(kNoFace);
            }
          }
          ++next;
        }
        row_start[static_cast<std::size_t>(c) + 1] = static_cast<int>(cols.size());
      }
      csr = BlockCsr(n, row_start, cols);
      std::vector<int> inverse(cols.size());
      for (std::size_t k = 0; k < cols.size(); ++k)
        inverse[static_cast<std::size_t>(csr.permutation()[k])] = static_cast<int>(k);
      entry_face.resize(cols.size());
      for (std::size_t k = 0; k < cols.size(); ++k)
        entry_face[k] = tags[static_cast<std::size_t>(csr.permutation()[k])];
      entry_extra.assign(cols.size(), -1);
      for (std::size_t k = 0; k < where.size(); ++k)
        entry_extra[static_cast<std::size_t>(inverse[static_cast<std::size_t>(where[k])])] =
            static_cast<int>(k);
      b.assign(static_cast<std::size_t>(n), 0.0);
      amg.reset();  // a new pattern: a new hierarchy
      loaded = false;
    }
    // sign * (m + e) into csr and b; whether any coefficient differs from the last load.
    bool load(const Matrix& m, const ExtraEntries& e, double sign) {
      const double changes =
          parallel_sum<1>(csr.rows(), [&](int lo, int hi, std::array<double, 1>& s) {
            for (int i = lo; i < hi; ++i) {
              const auto is = static_cast<std::size_t>(i);
              bool differs = csr.diag[is] != sign * m.diag[is];
              csr.diag[is] = sign * m.diag[is];
              b[is] = sign * m.source[is];
              for (int k = csr.row_begin(i); k < csr.row_end(i); ++k) {
                const auto ku = static_cast<std::size_t>(k);
                const int t = entry_face[ku], x = entry_extra[ku];
                double a = t == kNoFace ? 0.0
                           : t >= 0     ? m.upper[static_cast<std::size_t>(t)]
                                        : m.lower[static_cast<std::size_t>(~t)];
                if (x >= 0) a += e.values[static_cast<std::size_t>(x)];
                differs = differs || csr.value[ku] != sign * a;
                csr.value[ku] = sign * a;
              }
              s[0] += differs ? 1.0 : 0.0;
            }
          })[0];
      const bool changed = changes > 0 || !loaded;
      loaded = true;
      if (changed) csr.coefficients_changed();
      return changed;
    }
  };
  Coupled coupled;
  std::unique_ptr<AmgPcg> amg;       // built on the first cg-amg solve
  std::unique_ptr<EigenCopy> eigen;  // built on the first solve that needs it

  Impl(const Mesh& m, Tolerance tol)
      : mesh(m), tolerance(tol), b(static_cast<std::size_t>(m.cells())) {
    std::vector<int> row_start(static_cast<std::size_t>(mesh.cells()) + 1, 0), columns, tags;
    for (int c = 0; c < mesh.cells(); ++c) {
      for (int f : mesh.cell_faces(c)) {
        if (f >= mesh.internal_faces()) break;  // boundary faces come last
        const bool owner = mesh.owner(f) == c;
        columns.push_back(owner ? mesh.neighbour(f) : mesh.owner(f));
        tags.push_back(owner ? f : ~f);
      }
      row_start[static_cast<std::size_t>(c) + 1] = static_cast<int>(columns.size());
    }
    csr = BlockCsr(mesh.cells(), row_start, columns);
    entry_face.resize(tags.size());
    for (std::size_t k = 0; k < tags.size(); ++k)
      entry_face[k] = tags[static_cast<std::size_t>(csr.permutation()[k])];
  }

  // sign * m into csr and b, in parallel; whether any coefficient differs from the last load.
  bool load(const Matrix& m, double sign) {
    const double changes =
        parallel_sum<1>(csr.rows(), [&](int lo, int hi, std::array<double, 1>& s) {
          for (int i = lo; i < hi; ++i) {
            const auto is = static_cast<std::size_t>(i);
            bool differs = csr.diag[is] != sign * m.diag[is];
            csr.diag[is] = sign * m.diag[is];
            b[is] = sign * m.source[is];
            for (int k = csr.row_begin(i); k < csr.row_end(i); ++k) {
              const int t = entry_face[static_cast<std::size_t>(k)];
              const double a = sign * (t >= 0 ? m.upper[static_cast<std::size_t>(t)]
                                              : m.lower[static_cast<std::size_t>(~t)]);
              differs = differs || csr.value[static_cast<std::size_t>(k)] != a;
              csr.value[static_cast<std::size_t>(k)] = a;
            }
            s[0] += differs ? 1.0 : 0.0;
          }
        })[0];
    const bool changed = changes > 0 || !loaded;
    loaded = true;
    if (changed) csr.coefficients_changed();
    return changed;
  }

  EigenCopy& eigen_copy(const Matrix& m, double sign) {
    if (!eigen) eigen = std::make_unique<EigenCopy>(mesh, tolerance.value);
    eigen->load(m, sign);
    return *eigen;
  }

  // The normalised residuals of x for methods that do not report them.
  void residuals(std::span<const double> x, SolveStats& stats, bool initial) {
    work.resize(csr.rows());
    const auto res = csr.residual(b, x, work.r);
    const double value = res.l1 / (res.normalisation + 1e-300);
    (initial ? stats.initial_residual : stats.final_residual) = value;
  }

  AmgPcg& amg_for_csr() {
    if (!amg) {
      amg = std::make_unique<AmgPcg>();
      csr.keep_single();  // the multigrid cycle reads the coefficients in single precision
    }
    return *amg;
  }
};

void ExtraEntries::multiply_add(std::span<const double> x, std::span<double> y, double sign) const {
  parallel_for(size(), [&](int k) {  // each row once: no two iterations write one entry of y
    const auto ku = static_cast<std::size_t>(k);
    double s = 0;
    for (int e = start[ku]; e < start[ku + 1]; ++e)
      s += values[static_cast<std::size_t>(e)] *
           x[static_cast<std::size_t>(columns[static_cast<std::size_t>(e)])];
    y[static_cast<std::size_t>(rows[ku])] += sign * s;
  });
}

LinearSolver::LinearSolver(const Mesh& mesh, Tolerance tolerance)
    : impl_(std::make_unique<Impl>(mesh, tolerance)) {}
LinearSolver::~LinearSolver() = default;

namespace {
template <class Solver>
int iterate(Solver& solver, const Sparse& A, std::span<const double> source, std::span<double> x,
            double tolerance) {
  solver.setTolerance(tolerance);
  solver.setMaxIterations(5000);
  solver.compute(A);
  Eigen::Map<const Vec> b(source.data(), static_cast<Eigen::Index>(source.size()));
  Eigen::Map<Vec> xv(x.data(), static_cast<Eigen::Index>(x.size()));
  Vec guess = xv;
  xv = solver.solveWithGuess(b, guess);
  if (solver.info() != Eigen::Success && !(solver.error() < 1e3 * tolerance))
    throw std::runtime_error(
        fmt::format("Eigen Krylov solver did not converge in {} iterations: relative residual "
                    "{:.3g} (tolerance {:.3g})",
                    solver.iterations(), solver.error(), tolerance));
  return static_cast<int>(solver.iterations());
}
}  // namespace

void LinearSolver::plan_symmetric(const Matrix& m, SymmetricMethod method) {
  if (method != SymmetricMethod::cg_amg) return;
  const Team::Region team(threads());
  auto& I = *impl_;
  I.load(m, -1.0);
  I.amg_for_csr().plan(I.csr);
}

SolveStats LinearSolver::solve_symmetric(const Matrix& m, std::span<double> x,
                                         SymmetricMethod method, double tolerance) {
  const Team::Region team(threads());  // the solve's loops on one team (team.hpp)
  auto& I = *impl_;
  const Tolerance tol = tolerance > 0 ? Tolerance(tolerance, I.tolerance.norm) : I.tolerance;
  // CG and CHOLMOD want a positive definite matrix: the Laplacian is negative definite, so solve
  // (-A) x = -b.
  const bool changed = I.load(m, -1.0);
  if (method == SymmetricMethod::cg_amg)
    return I.amg_for_csr().solve(I.csr, changed, I.b, x, tol, 2000);
  if (method == SymmetricMethod::cg_jacobi) {
    return jacobi_cg(I.csr, I.b, x, tol, 20000, I.work);
  }
  SolveStats stats;
  I.residuals(x, stats, true);
  Eigen::Map<const Vec> b(I.b.data(), static_cast<Eigen::Index>(I.b.size()));
  Eigen::Map<Vec> xv(x.data(), static_cast<Eigen::Index>(x.size()));
  if (method == SymmetricMethod::cholmod) {
    auto& E = I.eigen_copy(m, -1.0);
    if (!std::equal(E.factorised_values.begin(), E.factorised_values.end(), E.A.valuePtr()) ||
        E.factorised_values.empty())
      E.factorise(stats);
    xv = E.cholmod.solve(b);
  } else if (method == SymmetricMethod::cholmod_pcg) {
    // Refactorise when the old factor has become a poor preconditioner (more than 10
    // iterations last time, or no convergence in 30); with a fresh factor the solve is direct.
    auto& E = I.eigen_copy(m, -1.0);
    int iterations = -1;
    if (!E.factorised_values.empty() && E.last_pcg_iterations <= 10) {
      const Vec x0 = xv;
      iterations = E.pcg(b, xv, 30);
      if (iterations < 0) xv = x0;
    }
    if (iterations < 0) {
      E.factorise(stats);
      xv = E.cholmod.solve(b);
      iterations = 0;
    }
    stats.iterations = E.last_pcg_iterations = iterations;
  } else if (method == SymmetricMethod::cg_incomplete_cholesky) {
    auto& E = I.eigen_copy(m, -1.0);
    Eigen::ConjugateGradient<Sparse, Eigen::Lower | Eigen::Upper,
                             Eigen::IncompleteCholesky<double, Eigen::Lower>>
        cg;
    stats.iterations = iterate(cg, E.A, I.b, x, tol.value);
  } else {  // cg_dic
    stats.iterations = dic_pcg(I.mesh, -m, x, tol.value, 20000);
  }
  I.residuals(x, stats, false);
  return stats;
}

SolveStats LinearSolver::solve_asymmetric(const Matrix& m, std::span<double> x,
                                          AsymmetricMethod method, double tolerance) {
  const Team::Region team(threads());
  auto& I = *impl_;
  const Tolerance tol = tolerance > 0 ? Tolerance(tolerance, I.tolerance.norm) : I.tolerance;
  I.load(m, 1.0);
  if (method == AsymmetricMethod::gauss_seidel) {
    constexpr int kSweepPairs = 20;
    auto gs = gauss_seidel_solve(I.csr, I.b, x, tol, kSweepPairs, I.work);
    if (gs.converged) return gs.stats;
    const SolveStats more =
        bicgstab(I.csr, I.b, x, tol, 5000, I.work, Preconditioner::jacobi, gs.normalisation);
    gs.stats.iterations += more.iterations;
    gs.stats.final_residual = more.final_residual;
    return gs.stats;
  }
  if (method == AsymmetricMethod::bicgstab_jacobi || method == AsymmetricMethod::bicgstab_gs) {
    return bicgstab(I.csr, I.b, x, tol, 5000, I.work,
                    method == AsymmetricMethod::bicgstab_gs ? Preconditioner::gauss_seidel
                                                            : Preconditioner::jacobi);
  }
  SolveStats stats;
  I.residuals(x, stats, true);
  auto& E = I.eigen_copy(m, 1.0);
  Eigen::BiCGSTAB<Sparse, Eigen::IncompleteLUT<double>> s;
  stats.iterations = iterate(s, E.A, I.b, x, tol.value);
  I.residuals(x, stats, false);
  return stats;
}

void LinearSolver::plan_coupled(const Matrix& m, const ExtraEntries& extra) {
  const Team::Region team(threads());
  auto& I = *impl_;
  auto& C = I.coupled;
  if (!C.matches(extra)) C.build(I.mesh, extra);
  C.load(m, extra, -1.0);
  if (!C.amg) {
    C.amg = std::make_unique<AmgPcg>(false);
    C.csr.keep_single();
    C.csr.coefficients_changed();
  }
  C.amg->plan(C.csr);
}

SolveStats LinearSolver::solve_bordered(const Matrix& m, const Border& border, std::span<double> x,
                                        std::span<double> lambda, SymmetricMethod method,
                                        double tolerance) {
  // cg-amg's flexible CG with the border on every level of its multigrid (amg_pcg.hpp, steps B).
  // On the REMUS coarse system (remus-overset-sst's set-up, a fin turning) 105-109 pressure
  // iterations a step against 91 without the balance; flexible GMRES preconditioned by a block
  // factorisation (one cycle per column for the border's responses, session 24) took 96-98, but
  // its Gram-Schmidt and responses cost about twice the extra iterations (docs/overset-flow.md,
  // session 25).
  constexpr int kMaxIterations = 2000;
  if (method != SymmetricMethod::cg_amg)
    throw std::invalid_argument(std::string("LinearSolver::solve_bordered: cg-amg only, got ") +
                                to_string(method));
  const auto K = border.columns.size();
  if (K == 0) throw std::invalid_argument("LinearSolver::solve_bordered: no border column");
  if (lambda.size() != K)
    throw std::invalid_argument("LinearSolver::solve_bordered: one lambda per column");
  const Team::Region team(threads());
  auto& I = *impl_;
  // As solve_symmetric: (-m) x + (-C) lambda = -b, (-C^T) x + (-d) lambda = -rhs, positive
  // definite.
  const bool changed = I.load(m, -1.0);
  const auto nu = static_cast<std::size_t>(I.csr.rows());
  auto& b = I.bordered_b;
  auto& xl = I.bordered_x;
  b.resize(nu + K);
  xl.resize(nu + K);
  std::copy(I.b.begin(), I.b.end(), b.begin());
  std::copy(x.begin(), x.end(), xl.begin());
  for (std::size_t k = 0; k < K; ++k) {
    b[nu + k] = -border.columns[k].rhs;
    xl[nu + k] = lambda[k];
  }
  const Tolerance tol = tolerance > 0 ? Tolerance(tolerance, I.tolerance.norm) : I.tolerance;
  const SolveStats stats =
      I.amg_for_csr().solve_bordered(I.csr, changed, border, -1.0, b, xl, tol, kMaxIterations);
  std::copy(xl.begin(), xl.begin() + static_cast<std::ptrdiff_t>(nu), x.begin());
  for (std::size_t k = 0; k < K; ++k) lambda[k] = xl[nu + k];
  return stats;
}

SolveStats LinearSolver::solve_coupled(const Matrix& m, const ExtraEntries& extra,
                                       std::span<double> x,
                                       std::optional<SymmetricMethod> symmetric, double tolerance) {
  constexpr int kRestart = 30, kMaxIterations = 2000;
  const Team::Region team(threads());
  auto& I = *impl_;
  auto& C = I.coupled;
  const Tolerance tol = tolerance > 0 ? Tolerance(tolerance, I.tolerance.norm) : I.tolerance;
  // A pressure equation is a Laplacian (negative definite): solve (-m - extra) x = -b, whose
  // diagonal is positive, as the multigrid's smoother and pairing expect.
  const double sign = symmetric ? -1.0 : 1.0;
  if (!C.matches(extra)) C.build(I.mesh, extra);
  const bool changed = C.load(m, extra, sign);
  const LinearMap A = [&](std::span<const double> in, std::span<double> out) {
    C.csr.multiply(in, out);
  };
  LinearMap P;
  bool first = true;
  if (symmetric) {  // the multigrid of the whole coupled system
    if (!C.amg) {   // no plan_coupled for this pattern: aggregates from this matrix
      C.amg = std::make_unique<AmgPcg>(false);
      C.csr.keep_single();
      C.csr.coefficients_changed();
    }
    P = [&](std::span<const double> r, std::span<double> z) {
      C.amg->precondition(C.csr, changed && first, r, z);
      first = false;
    };
  } else {
    I.work.resize(C.csr.rows());
    P = [&](std::span<const double> r, std::span<double> z) {
      C.csr.sweep(r, z, false, true, I.work.s);  // a symmetric pair from z = 0
      C.csr.sweep(r, z, true, false, I.work.s);
    };
  }
  return fgmres(C.csr.rows(), A, P, C.b, x, tol, kMaxIterations, kRestart, I.fgmres_work);
}

}  // namespace auvloop::engine::fv
