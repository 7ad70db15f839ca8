// SPDX-License-Identifier: GPL-3.0-or-later
#include "amg_pcg.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Dense>

namespace auvloop::engine::fv {

namespace {
// Below this many cells a level is solved directly (dense Cholesky: n^3 / 3 flops per setup).
constexpr int kCoarsestCells = 64;
// Coarsening (two pairings) that keeps more than this fraction of the cells no longer pays for a
// level; with about a quarter of the cells per level the K-cycle costs about twice a V-cycle.
constexpr double kMinReduction = 0.6;
// The K-cycle skips its second Krylov step when the first reduced the residual this much.
constexpr double kKcycleTolerance = 0.25;
constexpr int kMaxLevels = 40;
// A cell pairs only with a free neighbour coupled at least this strongly relative to its
// strongest coupling (Notay's beta): on stretched cells, pairs across the weak direction make
// coarse levels that correct nothing (measured on a graded, sheared 32^3 box with zero-gradient
// boundaries: 134 iterations without the test, 51 with it).
constexpr double kStrongCoupling = 0.25;

double dot(std::span<const double> a, std::span<const double> b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// One level: a symmetric matrix in LDU form on its own face list, with the cell adjacency for
// Gauss-Seidel sweeps, the map to the next coarser level and work vectors.
struct Level {
  int n = 0;
  std::vector<int> lo, hi;                         // the two cells of each face
  std::vector<int> row_start, adj_cell, adj_face;  // per cell: neighbours and shared faces
  std::vector<double> diag, upper;
  std::vector<double> row_value,
      inv_diag;                  // the same by rows (load_rows)                 // coefficients
  std::vector<int> agg;          // cell -> coarser cell
  std::vector<int> coarse_face;  // face -> coarser face; -1 inside a pair
  std::vector<double> x, b, r;   // work
  std::vector<double> r0, c1, v1, v2;  // work of the K-cycle on this level

  void build_adjacency() {
    row_start.assign(static_cast<std::size_t>(n) + 1, 0);
    for (std::size_t f = 0; f < lo.size(); ++f) {
      ++row_start[static_cast<std::size_t>(lo[f]) + 1];
      ++row_start[static_cast<std::size_t>(hi[f]) + 1];
    }
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) row_start[i + 1] += row_start[i];
    adj_cell.resize(2 * lo.size());
    adj_face.resize(2 * lo.size());
    std::vector<int> next(row_start.begin(), row_start.end() - 1);
    for (std::size_t f = 0; f < lo.size(); ++f) {
      for (const auto& [from, to] : {std::pair{lo[f], hi[f]}, std::pair{hi[f], lo[f]}}) {
        const auto k = static_cast<std::size_t>(next[static_cast<std::size_t>(from)]++);
        adj_cell[k] = to;
        adj_face[k] = static_cast<int>(f);
      }
    }
    for (auto* v : {&x, &b, &r, &r0, &c1, &v1, &v2}) {
      v->assign(static_cast<std::size_t>(n), 0.0);
    }
  }

  // The coefficients by rows (compressed rows in adjacency order) and the inverse diagonal, from
  // diag and upper: the sweeps and products then read memory in order.
  void load_rows() {
    row_value.resize(adj_face.size());
    for (std::size_t k = 0; k < adj_face.size(); ++k) {
      row_value[k] = upper[static_cast<std::size_t>(adj_face[k])];
    }
    inv_diag.resize(diag.size());
    for (std::size_t i = 0; i < diag.size(); ++i) inv_diag[i] = 1.0 / diag[i];
  }

  // sum_j a_ij v_j over the neighbours j of cell i
  [[nodiscard]] double off_diagonal(std::size_t i, std::span<const double> v) const {
    double s = 0;
    const auto end = static_cast<std::size_t>(row_start[i + 1]);
    for (auto k = static_cast<std::size_t>(row_start[i]); k < end; ++k) {
      s += row_value[k] * v[static_cast<std::size_t>(adj_cell[k])];
    }
    return s;
  }

  // y = A v
  void multiply(std::span<const double> v, std::span<double> y) const {
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      y[i] = diag[i] * v[i] + off_diagonal(i, v);
    }
  }

  void relax_cell(std::size_t i) { x[i] = (b[i] - off_diagonal(i, x)) * inv_diag[i]; }
  void sweep_forward() {
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) relax_cell(i);
  }
  void sweep_backward() {
    for (std::size_t i = static_cast<std::size_t>(n); i-- > 0;) relax_cell(i);
  }

  // Pairs each cell with its most strongly coupled free neighbour (ties: the first in face
  // order, so the result is deterministic) if that coupling is strong; a cell whose neighbours
  // are all taken joins the pair of its strongest neighbour. Returns the number of aggregates.
  int pair_cells() {
    agg.assign(static_cast<std::size_t>(n), -1);
    int count = 0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      if (agg[i] >= 0) continue;
      int free_best = -1, any_best = -1;
      double free_w = -1, any_w = -1;
      for (auto k = static_cast<std::size_t>(row_start[i]);
           k < static_cast<std::size_t>(row_start[i + 1]); ++k) {
        const int j = adj_cell[k];
        const double w = std::abs(upper[static_cast<std::size_t>(adj_face[k])]);
        if (agg[static_cast<std::size_t>(j)] < 0 && w > free_w) {
          free_w = w;
          free_best = j;
        }
        if (w > any_w) {
          any_w = w;
          any_best = j;
        }
      }
      if (free_best >= 0 && free_w >= kStrongCoupling * any_w) {
        agg[i] = agg[static_cast<std::size_t>(free_best)] = count++;
      } else if (free_best >= 0) {
        agg[i] = count++;  // only weakly coupled to what is free: a pair would coarsen badly
      } else if (any_best >= 0) {
        agg[i] = agg[static_cast<std::size_t>(any_best)];
      } else {
        agg[i] = count++;  // an isolated cell
      }
    }
    return count;
  }

  // The coarse level's faces (one per pair of adjacent aggregates) and this level's map to them.
  Level coarsen(int coarse_cells) {
    Level c;
    c.n = coarse_cells;
    coarse_face.assign(lo.size(), -1);
    std::unordered_map<std::uint64_t, int> index;
    index.reserve(lo.size());
    for (std::size_t f = 0; f < lo.size(); ++f) {
      int a = agg[static_cast<std::size_t>(lo[f])], z = agg[static_cast<std::size_t>(hi[f])];
      if (a == z) continue;
      if (a > z) std::swap(a, z);
      const auto key = (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(z);
      const auto [it, added] = index.try_emplace(key, static_cast<int>(c.lo.size()));
      if (added) {
        c.lo.push_back(a);
        c.hi.push_back(z);
      }
      coarse_face[f] = it->second;
    }
    c.build_adjacency();
    return c;
  }

  // Follows this level's maps with those of `mid` (to the level below it): two pairings in a row
  // make aggregates of about four cells.
  void compose(const Level& mid) {
    for (int& a : agg) a = mid.agg[static_cast<std::size_t>(a)];
    for (int& f : coarse_face) f = f < 0 ? -1 : mid.coarse_face[static_cast<std::size_t>(f)];
  }

  // Galerkin coarse coefficients P^T A P for piecewise-constant P.
  void restrict_matrix(Level& c) const {
    c.diag.assign(static_cast<std::size_t>(c.n), 0.0);
    c.upper.assign(c.lo.size(), 0.0);
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      c.diag[static_cast<std::size_t>(agg[i])] += diag[i];
    }
    for (std::size_t f = 0; f < lo.size(); ++f) {
      if (coarse_face[f] < 0) {
        c.diag[static_cast<std::size_t>(agg[static_cast<std::size_t>(lo[f])])] += 2 * upper[f];
      } else {
        c.upper[static_cast<std::size_t>(coarse_face[f])] += upper[f];
      }
    }
  }
};
}  // namespace

struct AmgPcg::Hierarchy {
  std::vector<Level> levels;
  Eigen::LLT<Eigen::MatrixXd> coarsest;

  // The rows of every level and the coarsest factor, after new coefficients.
  void load_coefficients() {
    for (Level& L : levels) L.load_rows();
    factorise_coarsest();
  }

  void factorise_coarsest() {
    const Level& L = levels.back();
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(L.n, L.n);
    for (int i = 0; i < L.n; ++i) A(i, i) = L.diag[static_cast<std::size_t>(i)];
    for (std::size_t f = 0; f < L.lo.size(); ++f) {
      A(L.lo[f], L.hi[f]) += L.upper[f];
      A(L.hi[f], L.lo[f]) += L.upper[f];
    }
    coarsest.compute(A);
    if (coarsest.info() != Eigen::Success) {
      throw std::runtime_error("AMG: the coarsest matrix is not positive definite");
    }
  }

  // Solves approximately levels[l].A x = levels[l].b, from x = 0: Gauss-Seidel, the coarse
  // correction (exact on the coarsest level, a K-cycle elsewhere), Gauss-Seidel backwards.
  void cycle(std::size_t l) {
    Level& L = levels[l];
    if (l + 1 == levels.size()) {
      Eigen::Map<const Eigen::VectorXd> b(L.b.data(), L.n);
      Eigen::Map<Eigen::VectorXd>(L.x.data(), L.n) = coarsest.solve(b);
      return;
    }
    Level& C = levels[l + 1];
    std::fill(L.x.begin(), L.x.end(), 0.0);
    L.sweep_forward();
    L.multiply(L.x, L.r);
    for (std::size_t i = 0; i < L.r.size(); ++i) L.r[i] = L.b[i] - L.r[i];
    std::fill(C.b.begin(), C.b.end(), 0.0);
    for (std::size_t i = 0; i < L.r.size(); ++i) C.b[static_cast<std::size_t>(L.agg[i])] += L.r[i];
    if (l + 2 == levels.size()) {
      cycle(l + 1);
    } else {
      kcycle(l + 1);
    }
    for (std::size_t i = 0; i < L.x.size(); ++i) L.x[i] += C.x[static_cast<std::size_t>(L.agg[i])];
    L.sweep_backward();
  }

  // Two flexible-CG steps on level l preconditioned by cycle(l), the second only when the first
  // left more than a quarter of the residual (Notay and Vassilevski's K-cycle). It minimises the
  // error in the energy norm over the two directions, which makes a cycle of unsmoothed
  // aggregation about as good as a two-grid method at any depth.
  void kcycle(std::size_t l) {
    Level& L = levels[l];
    L.r0 = L.b;
    cycle(l);
    L.c1 = L.x;
    L.multiply(L.c1, L.v1);
    const double rho1 = dot(L.c1, L.v1), alpha1 = dot(L.c1, L.r0);
    if (!(rho1 > 0)) return;  // keep the plain cycle
    const double r0_norm = std::sqrt(dot(L.r0, L.r0));
    for (std::size_t i = 0; i < L.b.size(); ++i) L.b[i] = L.r0[i] - alpha1 / rho1 * L.v1[i];
    if (std::sqrt(dot(L.b, L.b)) <= kKcycleTolerance * r0_norm) {
      for (std::size_t i = 0; i < L.x.size(); ++i) L.x[i] = alpha1 / rho1 * L.c1[i];
      return;
    }
    cycle(l);  // c2 = L.x, from the new residual in L.b
    L.multiply(L.x, L.v2);
    const double gamma = dot(L.x, L.v1), beta = dot(L.x, L.v2), alpha2 = dot(L.x, L.b);
    const double rho2 = beta - gamma * gamma / rho1;
    if (!(rho2 > 0)) {
      for (std::size_t i = 0; i < L.x.size(); ++i) L.x[i] = alpha1 / rho1 * L.c1[i];
      return;
    }
    const double a1 = alpha1 / rho1 - gamma * alpha2 / (rho1 * rho2), a2 = alpha2 / rho2;
    for (std::size_t i = 0; i < L.x.size(); ++i) L.x[i] = a1 * L.c1[i] + a2 * L.x[i];
  }
};

AmgPcg::AmgPcg(const Mesh& mesh) : mesh_(mesh) {}
AmgPcg::~AmgPcg() = default;

int AmgPcg::levels() const {
  return h_ ? static_cast<int>(h_->levels.size()) : 0;
}
int AmgPcg::cells(int level) const {
  return h_->levels.at(static_cast<std::size_t>(level)).n;
}

namespace {
void load_finest(Level& L, const Mesh& mesh, const Matrix& A) {
  if (L.lo.empty() && mesh.internal_faces() > 0) {
    L.n = mesh.cells();
    for (int f = 0; f < mesh.internal_faces(); ++f) {
      L.lo.push_back(mesh.owner(f));
      L.hi.push_back(mesh.neighbour(f));
    }
    L.build_adjacency();
  }
  L.diag = A.diag;
  L.upper = A.upper;
}
}  // namespace

int AmgPcg::solve(const Matrix& A, std::span<double> x, double tolerance, int max_iterations) {
  if (!h_) {  // aggregates from the first matrix, kept for the grid's lifetime
    h_ = std::make_unique<Hierarchy>();
    h_->levels.emplace_back();
    load_finest(h_->levels[0], mesh_, A);
    while (h_->levels.back().n > kCoarsestCells &&
           static_cast<int>(h_->levels.size()) < kMaxLevels) {
      Level& fine = h_->levels.back();
      const int n_mid = fine.pair_cells();
      Level mid = fine.coarsen(n_mid);
      fine.restrict_matrix(mid);
      const int nc = mid.pair_cells();
      if (nc > kMinReduction * fine.n) break;
      Level coarse = mid.coarsen(nc);
      mid.restrict_matrix(coarse);
      fine.compose(mid);
      h_->levels.push_back(std::move(coarse));
    }
    h_->levels.back().agg.clear();
    h_->load_coefficients();
  } else if (A.diag != h_->levels[0].diag || A.upper != h_->levels[0].upper) {
    // New coefficients (not for the later correctors of an outer iteration, which share the
    // matrix: their setup would give the same bits).
    load_finest(h_->levels[0], mesh_, A);
    for (std::size_t l = 0; l + 1 < h_->levels.size(); ++l) {
      h_->levels[l].restrict_matrix(h_->levels[l + 1]);
    }
    h_->load_coefficients();
  }

  // Flexible conjugate gradients: z = M r with M the (nonlinear) K-cycle.
  Level& F = h_->levels[0];
  const auto n = static_cast<std::size_t>(F.n);
  std::vector<double> r(n), r_old(n), z(n), p(n), q(n);
  F.multiply(x, q);
  for (std::size_t i = 0; i < n; ++i) r[i] = A.source[i] - q[i];
  const double bnorm = std::max(std::sqrt(dot(A.source, A.source)), 1e-300);
  double rnorm = std::sqrt(dot(r, r));
  if (rnorm <= tolerance * bnorm) return 0;
  const auto precondition = [&] {
    F.b = r;
    h_->cycle(0);
    z = F.x;
  };
  precondition();
  p = z;
  double rz = dot(r, z);
  for (int it = 1; it <= max_iterations; ++it) {
    F.multiply(p, q);
    const double alpha = rz / dot(p, q);
    r_old = r;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    rnorm = std::sqrt(dot(r, r));
    if (rnorm <= tolerance * bnorm) return it;
    precondition();
    double z_dr = 0;
    for (std::size_t i = 0; i < n; ++i) z_dr += z[i] * (r[i] - r_old[i]);
    const double beta = z_dr / rz;
    rz = dot(r, z);
    for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
  }
  throw std::runtime_error("AMG-CG did not converge in " + std::to_string(max_iterations) +
                           " iterations: relative residual " + std::to_string(rnorm / bnorm));
}

}  // namespace auvloop::engine::fv
