// SPDX-License-Identifier: GPL-3.0-or-later
#include "amg_pcg.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "krylov.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

namespace {
// Below this many rows a level is solved directly (dense Cholesky: n^3 / 3 flops per setup).
constexpr int kCoarsestCells = 64;
// Coarsening (two pairings) that keeps more than this fraction of the rows no longer pays for a
// level; with about a quarter of the rows per level the K-cycle costs about twice a V-cycle.
constexpr double kMinReduction = 0.6;
// The K-cycle skips its second Krylov step when the first reduced the residual this much.
constexpr double kKcycleTolerance = 0.25;
constexpr int kMaxLevels = 40;
// Passes of pairwise aggregation per level: three give aggregates of about eight rows. Measured
// against two (aggregates of about four; Notay's default in AGMG) on the 64^3 cavity: 19.0
// against 19.2 pressure iterations per step and 0.50 against 0.62 s per one-thread step; on the
// coarse hull grid 126 against 109 iterations and 0.209 against 0.239 s per step: the K-cycle
// visits level l up to 2^l times, so its coarse levels cost (2/8)^l instead of (2/4)^l of the
// finest level's work, and they are the part of the cycle two threads speed up least.
constexpr int kPairingPasses = 3;
// A row pairs only with a free neighbour coupled at least this strongly relative to its
// strongest coupling (Notay's beta): on stretched cells, pairs across the weak direction make
// coarse levels that correct nothing (measured on a graded, sheared 32^3 box with zero-gradient
// boundaries: 134 iterations without the test, 51 with it).
constexpr double kStrongCoupling = 0.25;

// Pairs each row with its most strongly coupled free neighbour (ties: the first in the row's
// entry order, so the result is deterministic) if that coupling is strong; a row whose
// neighbours are all taken joins the pair of its strongest neighbour. Returns the number of
// aggregates; agg[i] is row i's.
int pair_rows(const BlockCsr& A, std::vector<int>& agg) {
  const int n = A.rows();
  agg.assign(static_cast<std::size_t>(n), -1);
  int count = 0;
  std::vector<int> order;
  for (int i = 0; i < n; ++i) {
    if (agg[static_cast<std::size_t>(i)] >= 0) continue;
    int free_best = -1, any_best = -1;
    double free_w = -1, any_w = -1;
    // The entries in the order the pattern was given (the faces' order on the finest level):
    // which of equally strong neighbours pairs decides the aggregates' shapes on uniform grids,
    // and this order measured twice as good as by column (17 against 35 iterations per step on
    // the 64^3 cavity).
    order.clear();
    for (int k = A.row_begin(i); k < A.row_end(i); ++k) order.push_back(k);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return A.permutation()[static_cast<std::size_t>(a)] <
             A.permutation()[static_cast<std::size_t>(b)];
    });
    for (int k : order) {
      const int j = A.column(k);
      const double w = std::abs(A.value[static_cast<std::size_t>(k)]);
      if (agg[static_cast<std::size_t>(j)] < 0 && w > free_w) {
        free_w = w;
        free_best = j;
      }
      if (w > any_w) {
        any_w = w;
        any_best = j;
      }
    }
    auto& a = agg[static_cast<std::size_t>(i)];
    if (free_best >= 0 && free_w >= kStrongCoupling * any_w) {
      a = agg[static_cast<std::size_t>(free_best)] = count++;
    } else if (free_best >= 0) {
      a = count++;  // only weakly coupled to what is free: a pair would coarsen badly
    } else if (any_best >= 0) {
      a = agg[static_cast<std::size_t>(any_best)];
    } else {
      a = count++;  // an isolated row
    }
  }
  return count;
}

// The map from a level to the next coarser one: the aggregates, their members, and per fine
// entry the coarse entry it adds to (-1: the coarse diagonal).
struct Restriction {
  std::vector<int> agg, member_start, member, target;

  // The coarse matrix's pattern for the aggregates `agg` of A's rows (nc of them).
  BlockCsr build(const BlockCsr& A, std::vector<int> aggregates, int nc) {
    agg = std::move(aggregates);
    const int n = A.rows();
    member_start.assign(static_cast<std::size_t>(nc) + 1, 0);
    for (int a : agg) ++member_start[static_cast<std::size_t>(a) + 1];
    for (std::size_t I = 0; I < static_cast<std::size_t>(nc); ++I)
      member_start[I + 1] += member_start[I];
    member.resize(static_cast<std::size_t>(n));
    std::vector<int> fill(member_start.begin(), member_start.end() - 1);
    for (int i = 0; i < n; ++i)
      member[static_cast<std::size_t>(
          fill[static_cast<std::size_t>(agg[static_cast<std::size_t>(i)])]++)] = i;
    std::vector<int> row_start(static_cast<std::size_t>(nc) + 1, 0), columns, row;
    for (int I = 0; I < nc; ++I) {
      row.clear();
      for (int m = member_start[static_cast<std::size_t>(I)];
           m < member_start[static_cast<std::size_t>(I) + 1]; ++m) {
        const int i = member[static_cast<std::size_t>(m)];
        for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
          const int J = agg[static_cast<std::size_t>(A.column(k))];
          if (J != I && std::find(row.begin(), row.end(), J) == row.end()) row.push_back(J);
        }
      }
      columns.insert(columns.end(), row.begin(), row.end());
      row_start[static_cast<std::size_t>(I) + 1] = static_cast<int>(columns.size());
    }
    BlockCsr C(nc, row_start, columns);
    target.assign(static_cast<std::size_t>(A.entries()), -1);
    for (int i = 0; i < n; ++i) {
      const int I = agg[static_cast<std::size_t>(i)];
      for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
        const int J = agg[static_cast<std::size_t>(A.column(k))];
        if (J == I) continue;
        int t = C.row_begin(I);
        while (C.column(t) != J) ++t;
        target[static_cast<std::size_t>(k)] = t;
      }
    }
    return C;
  }

  // C = P^T A P, coarse row by coarse row (members and their entries in a fixed order).
  void restrict_matrix(const BlockCsr& A, BlockCsr& C) const {
    parallel_for(
        C.rows(),
        [&](int I) {
          const auto Is = static_cast<std::size_t>(I);
          for (int t = C.row_begin(I); t < C.row_end(I); ++t)
            C.value[static_cast<std::size_t>(t)] = 0;
          double d = 0;
          for (int m = member_start[Is]; m < member_start[Is + 1]; ++m) {
            const int i = member[static_cast<std::size_t>(m)];
            d += A.diag[static_cast<std::size_t>(i)];
            for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
              const int t = target[static_cast<std::size_t>(k)];
              const double a = A.value[static_cast<std::size_t>(k)];
              if (t < 0) {
                d += a;
              } else {
                C.value[static_cast<std::size_t>(t)] += a;
              }
            }
          }
          C.diag[Is] = d;
        },
        kRowGrain);
    C.coefficients_changed();
  }
};

struct Level {
  BlockCsr own;                        // the matrix of a coarse level
  const BlockCsr* A = nullptr;         // own, or the caller's finest matrix
  Restriction to_coarse;               // empty on the coarsest level
  std::vector<double> x, b, scratch;   // the cycle's iterate and right-hand side, sweep scratch
  std::vector<double> r;               // the cycle's residual after its first sweep
  std::vector<double> r1, c1, v1, v2;  // the K-cycle's work on this level
  void allocate(int n) {
    for (auto* v : {&x, &b, &scratch, &r, &r1, &c1, &v1, &v2})
      v->assign(static_cast<std::size_t>(n), 0.0);
  }
};
}  // namespace

struct AmgPcg::Hierarchy {
  bool symmetric = true;
  std::vector<Level> levels;
  Eigen::LLT<Eigen::MatrixXd> coarsest;
  Eigen::PartialPivLU<Eigen::MatrixXd> coarsest_lu;  // not symmetric
  Eigen::MatrixXd coarsest_dense;
  Eigen::VectorXd coarsest_x;
  std::vector<double> r, z, p, q;  // flexible CG on the finest level
  // The border of a bordered solve (steps B): K columns per level (rows ascending), E's
  // diagonal, the coarsest level's bordered factor. K == 0 outside solve_bordered; every level's
  // vectors hold n_l + K values.
  struct BorderColumns {
    std::vector<std::vector<int>> rows;
    std::vector<std::vector<double>> values;
  };
  std::size_t K = 0;
  std::vector<BorderColumns> border;  // per level
  std::vector<double> border_diag;
  Eigen::LLT<Eigen::MatrixXd> coarsest_bordered;
  std::vector<double> border_sum;  // B1's scratch: one value per row of level 1
  std::vector<char> border_seen;
  // The border the levels hold (B1 is skipped when a solve brings the same one with the same
  // coefficients); `border_loaded` false after new coefficients or a plain solve.
  Border loaded;
  double loaded_sign = 0;
  bool border_loaded = false;
  std::vector<double> saved_b;  // B2's values of b at the border's rows

  Hierarchy(const BlockCsr& A, bool is_symmetric) : symmetric(is_symmetric) {
    levels.reserve(kMaxLevels);  // no reallocation: the levels' matrix pointers stay valid
    levels.emplace_back();
    levels[0].A = &A;
    while (levels.back().A->rows() > kCoarsestCells &&
           static_cast<int>(levels.size()) < kMaxLevels) {
      Level& fine = levels.back();
      const BlockCsr& F = *fine.A;
      // kPairingPasses passes of pairing, each on the matrix of the previous pass's aggregates.
      std::vector<int> agg(static_cast<std::size_t>(F.rows())), pairs;
      std::iota(agg.begin(), agg.end(), 0);
      int nc = F.rows();
      BlockCsr mid;
      for (int pass = 0; pass < kPairingPasses && nc > kCoarsestCells; ++pass) {
        if (pass > 0) {
          Restriction map;
          mid = map.build(F, agg, nc);
          map.restrict_matrix(F, mid);
        }
        nc = pair_rows(pass > 0 ? mid : F, pairs);
        for (int& a : agg) a = pairs[static_cast<std::size_t>(a)];
      }
      if (nc > kMinReduction * F.rows()) break;
      BlockCsr coarse = fine.to_coarse.build(F, std::move(agg), nc);
      levels.emplace_back();
      levels.back().own = std::move(coarse);
      levels.back().own.keep_single();
      levels.back().A = &levels.back().own;
    }
    size_vectors();
  }

  // Every level's vectors for n_l + K values (no allocation once they have held as many).
  void size_vectors() {
    for (Level& L : levels) L.allocate(L.A->rows() + static_cast<int>(K));
    const auto n = static_cast<std::size_t>(levels[0].A->rows()) + K;
    for (auto* v : {&r, &z, &p, &q}) v->assign(n, 0.0);
  }

  // B1: the border on every level (sign * the caller's values), and the coarsest bordered factor
  // (after load_coefficients, from coarsest_dense).
  void set_border(const Border& given, double sign) {
    if (border_loaded && sign == loaded_sign && same_border(given)) return;
    if (given.columns.size() != K) {
      K = given.columns.size();
      size_vectors();
    }
    border.resize(levels.size());
    border_diag.resize(K);
    for (std::size_t k = 0; k < K; ++k) {
      const auto& col = given.columns[k];
      border_diag[k] = sign * col.diag;
      auto& rows0 = border[0].rows;
      auto& values0 = border[0].values;
      rows0.resize(K);
      values0.resize(K);
      rows0[k] = col.rows;
      values0[k].resize(col.values.size());
      for (std::size_t e = 0; e < col.values.size(); ++e) values0[k][e] = sign * col.values[e];
    }
    for (std::size_t l = 0; l + 1 < levels.size(); ++l) {
      const Restriction& R = levels[l].to_coarse;
      const auto nc = static_cast<std::size_t>(levels[l + 1].A->rows());
      border_sum.resize(std::max(border_sum.size(), nc));
      border_seen.resize(std::max(border_seen.size(), nc), 0);
      auto& fine = border[l];
      auto& coarse = border[l + 1];
      coarse.rows.resize(K);
      coarse.values.resize(K);
      for (std::size_t k = 0; k < K; ++k) {
        auto& rows = coarse.rows[k];
        rows.clear();
        // Sums in ascending fine row order per aggregate, aggregates listed in ascending order.
        for (std::size_t e = 0; e < fine.rows[k].size(); ++e) {
          const auto I = static_cast<std::size_t>(R.agg[static_cast<std::size_t>(fine.rows[k][e])]);
          if (!border_seen[I]) {
            border_seen[I] = 1;
            border_sum[I] = 0;
            rows.push_back(static_cast<int>(I));
          }
          border_sum[I] += fine.values[k][e];
        }
        std::sort(rows.begin(), rows.end());
        auto& values = coarse.values[k];
        values.resize(rows.size());
        for (std::size_t e = 0; e < rows.size(); ++e) {
          const auto I = static_cast<std::size_t>(rows[e]);
          values[e] = border_sum[I];
          border_seen[I] = 0;
        }
      }
    }
    const auto nc = coarsest_dense.rows();
    const auto Ki = static_cast<Eigen::Index>(K);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(nc + Ki, nc + Ki);
    dense.topLeftCorner(nc, nc) = coarsest_dense;
    const auto& last = border.back();
    for (std::size_t k = 0; k < K; ++k) {
      const auto j = nc + static_cast<Eigen::Index>(k);
      dense(j, j) = border_diag[k];
      for (std::size_t e = 0; e < last.rows[k].size(); ++e) {
        dense(last.rows[k][e], j) = last.values[k][e];
        dense(j, last.rows[k][e]) = last.values[k][e];
      }
    }
    coarsest_bordered.compute(dense);
    if (coarsest_bordered.info() != Eigen::Success)
      throw std::runtime_error("AMG: the coarsest bordered matrix is not positive definite");
    coarsest_x.resize(nc + Ki);
    loaded.columns.resize(K);
    for (std::size_t k = 0; k < K; ++k) {
      const auto& col = given.columns[k];
      loaded.columns[k].rows.assign(col.rows.begin(), col.rows.end());
      loaded.columns[k].values.assign(col.values.begin(), col.values.end());
      loaded.columns[k].diag = col.diag;
    }
    loaded_sign = sign;
    border_loaded = true;
  }

  // The columns' rows, values and diagonals as loaded (the right side g does not enter B1).
  [[nodiscard]] bool same_border(const Border& given) const {
    if (given.columns.size() != loaded.columns.size()) return false;
    for (std::size_t k = 0; k < K; ++k) {
      const auto &a = given.columns[k], &b = loaded.columns[k];
      if (a.diag != b.diag || a.rows != b.rows || a.values != b.values) return false;
    }
    return true;
  }

  void clear_border() {
    if (K == 0) return;
    border_loaded = false;
    K = 0;
    size_vectors();
    coarsest_x.resize(levels.back().A->rows());
  }

  // B2: lambda_k = (g_k - C_k . x) / E_k on level l (x, b: n_l + K values).
  void relax_border(std::size_t l, std::span<const double> b, std::span<double> x) const {
    if (K == 0) return;
    const auto n = static_cast<std::size_t>(levels[l].A->rows());
    const auto& B = border[l];
    for (std::size_t k = 0; k < K; ++k) {
      double s = b[n + k];
      for (std::size_t e = 0; e < B.rows[k].size(); ++e)
        s -= B.values[k][e] * x[static_cast<std::size_t>(B.rows[k][e])];
      x[n + k] = s / border_diag[k];
    }
  }

  // y = A_l x with the border, and x . y (B3).
  template <bool Single>
  double multiply_dot(std::size_t l, std::span<const double> x, std::span<double> y) const {
    const BlockCsr& A = *levels[l].A;
    const auto n = static_cast<std::size_t>(A.rows());
    double d = A.multiply_dot<Single>(x.first(n), y.first(n));
    if (K == 0) return d;
    const auto& B = border[l];
    for (std::size_t k = 0; k < K; ++k) {
      const double lambda = x[n + k];
      double cx = 0;
      for (std::size_t e = 0; e < B.rows[k].size(); ++e) {
        const auto i = static_cast<std::size_t>(B.rows[k][e]);
        cx += B.values[k][e] * x[i];
        y[i] += B.values[k][e] * lambda;
      }
      y[n + k] = cx + border_diag[k] * lambda;
      d += lambda *
           (2 * cx + border_diag[k] * lambda);  // x_p.C lambda + lambda.(C^T x_p + E lambda)
    }
    return d;
  }

  // New coefficients of the finest matrix: every coarse level's and the coarsest factor.
  void load_coefficients() {
    for (std::size_t l = 0; l + 1 < levels.size(); ++l)
      levels[l].to_coarse.restrict_matrix(*levels[l].A, levels[l + 1].own);
    const BlockCsr& C = *levels.back().A;
    coarsest_dense.setZero(C.rows(), C.rows());
    for (int i = 0; i < C.rows(); ++i) {
      coarsest_dense(i, i) = C.diag[static_cast<std::size_t>(i)];
      for (int k = C.row_begin(i); k < C.row_end(i); ++k)
        coarsest_dense(i, C.column(k)) = C.value[static_cast<std::size_t>(k)];
    }
    if (!symmetric) {
      coarsest_lu.compute(coarsest_dense);
      if (!(std::abs(coarsest_lu.determinant()) > 0))
        throw std::runtime_error("AMG: the coarsest matrix is singular");
    } else {
      coarsest.compute(coarsest_dense);
      if (coarsest.info() != Eigen::Success)
        throw std::runtime_error("AMG: the coarsest matrix is not positive definite");
    }
    coarsest_x.resize(C.rows());
    border_loaded = false;
  }

  // Approximately solves levels[l].A x = b, from x = 0 (step 3 of the header).
  void cycle(std::size_t l, std::span<const double> b, std::span<double> x) {
    Level& L = levels[l];
    const BlockCsr& A = *L.A;
    const auto n = static_cast<std::size_t>(A.rows());
    if (l + 1 == levels.size()) {
      const auto N = static_cast<Eigen::Index>(n + K);
      const Eigen::Map<const Eigen::VectorXd> bv(b.data(), N);
      if (K > 0) {
        coarsest_x = coarsest_bordered.solve(bv);
      } else {
        coarsest_x = symmetric ? Eigen::VectorXd(coarsest.solve(bv)) : coarsest_lu.solve(bv);
      }
      std::copy(coarsest_x.data(), coarsest_x.data() + N, x.begin());
      return;
    }
    Level& C = levels[l + 1];
    const Restriction& R = L.to_coarse;
    const auto nc = static_cast<std::size_t>(C.A->rows());
    A.sweep<true>(b.first(n), x.first(n), false, true, L.scratch);  // from x = 0
    relax_border(l, b, x);
    // The restricted residual: the fine residual in one pass in row order (the matrix streams
    // from memory), then summed over each aggregate's members (a gather of one vector).
    parallel_for(
        A.rows(), [&](int i) { L.r[static_cast<std::size_t>(i)] = A.row_residual<true>(i, b, x); },
        kRowGrain);
    border_residual(l, b, x, L.r);
    parallel_for(
        C.A->rows(),
        [&](int I) {
          const auto Is = static_cast<std::size_t>(I);
          double s = 0;
          for (int m = R.member_start[Is]; m < R.member_start[Is + 1]; ++m)
            s += L.r[static_cast<std::size_t>(R.member[static_cast<std::size_t>(m)])];
          C.b[Is] = s;
        },
        kVectorGrain);
    for (std::size_t k = 0; k < K; ++k) C.b[nc + k] = L.r[n + k];
    if (l + 2 == levels.size()) {
      cycle(l + 1, C.b, C.x);
    } else if (symmetric) {
      kcycle(l + 1);
    } else {
      kcycle_gcr(l + 1);
    }
    parallel_for(
        A.rows(),
        [&](int i) {
          const auto is = static_cast<std::size_t>(i);
          x[is] += C.x[static_cast<std::size_t>(R.agg[is])];
        },
        kVectorGrain);
    if (K == 0) {
      A.sweep<true>(b, x, true, false, L.scratch);
      return;
    }
    for (std::size_t k = 0; k < K; ++k) x[n + k] += C.x[nc + k];
    relax_border(l, b, x);
    // B2 backward: the rows' sweep with b - C lambda, b shifted in place at the columns' rows and
    // restored bit for bit (in reverse, for a row two columns share). With a border, b is always
    // one of the hierarchy's own vectors (the finest r, a level's b or r1), never the caller's.
    if (b.data() != (l == 0 ? r.data() : L.b.data()) && b.data() != L.r1.data())
      throw std::logic_error("AMG: a bordered cycle on a vector the hierarchy does not own");
    const std::span<double> shifted(const_cast<double*>(b.data()), b.size());
    const auto& B = border[l];
    saved_b.clear();
    for (std::size_t k = 0; k < K; ++k)
      for (std::size_t e = 0; e < B.rows[k].size(); ++e) {
        double& v = shifted[static_cast<std::size_t>(B.rows[k][e])];
        saved_b.push_back(v);
        v -= B.values[k][e] * x[n + k];
      }
    A.sweep<true>(b.first(n), x.first(n), true, false, L.scratch);
    auto saved = saved_b.end();
    for (std::size_t k = K; k-- > 0;)
      for (std::size_t e = B.rows[k].size(); e-- > 0;)
        shifted[static_cast<std::size_t>(B.rows[k][e])] = *--saved;
  }

  // r_p -= C lambda at the columns' rows, r_lambda = g - C^T x_p - E lambda (r_p holds b - A x).
  void border_residual(std::size_t l, std::span<const double> b, std::span<const double> x,
                       std::span<double> res) const {
    if (K == 0) return;
    const auto n = static_cast<std::size_t>(levels[l].A->rows());
    const auto& B = border[l];
    for (std::size_t k = 0; k < K; ++k) {
      double s = b[n + k] - border_diag[k] * x[n + k];
      for (std::size_t e = 0; e < B.rows[k].size(); ++e) {
        const auto i = static_cast<std::size_t>(B.rows[k][e]);
        res[i] -= B.values[k][e] * x[n + k];
        s -= B.values[k][e] * x[i];
      }
      res[n + k] = s;
    }
  }

  // Two flexible-CG steps on level l (its b to its x) preconditioned by cycle(l), the second
  // only when the first left more than a quarter of the residual (Notay and Vassilevski's
  // K-cycle). It minimises the error in the energy norm over the two directions, which makes a
  // cycle of unsmoothed aggregation about as good as a two-grid method at any depth.
  void kcycle(std::size_t l) {
    Level& L = levels[l];
    const int n = L.A->rows() + static_cast<int>(K);  // with the border's values (B3)
    const auto each = [&](auto&& fn) { parallel_for(n, fn, kVectorGrain); };
    cycle(l, L.b, L.c1);
    const double rho1 = multiply_dot<true>(l, L.c1, L.v1);
    const auto [alpha1, b_squared] = dot2(L.b, L.c1, L.b);
    if (!(rho1 > 0)) {  // keep the plain cycle
      L.x = L.c1;
      return;
    }
    const double a = alpha1 / rho1;
    const double r1_squared =  // r1: the residual after the first step
        parallel_sum<1>(
            n,
            [&](int lo, int hi, std::array<double, 1>& s) {
              for (int i = lo; i < hi; ++i) {
                const auto is = static_cast<std::size_t>(i);
                L.r1[is] = L.b[is] - a * L.v1[is];
                s[0] += L.r1[is] * L.r1[is];
              }
            },
            kVectorGrain)[0];
    if (std::sqrt(r1_squared) <= kKcycleTolerance * std::sqrt(b_squared)) {
      each(
          [&](int i) { L.x[static_cast<std::size_t>(i)] = a * L.c1[static_cast<std::size_t>(i)]; });
      return;
    }
    cycle(l, L.r1, L.x);  // c2 = L.x
    const double beta = multiply_dot<true>(l, L.x, L.v2);
    const auto [gamma, alpha2] = dot2(L.x, L.v1, L.r1);
    const double rho2 = beta - gamma * gamma / rho1;
    if (!(rho2 > 0)) {
      each(
          [&](int i) { L.x[static_cast<std::size_t>(i)] = a * L.c1[static_cast<std::size_t>(i)]; });
      return;
    }
    const double a1 = a - gamma * alpha2 / (rho1 * rho2), a2 = alpha2 / rho2;
    each([&](int i) {
      const auto is = static_cast<std::size_t>(i);
      L.x[is] = a1 * L.c1[is] + a2 * L.x[is];
    });
  }

  // The K-cycle of a matrix that is not symmetric (Notay's AGMG): two steps of GCR instead of
  // flexible CG, x = a1 c1 + a2 c2 minimising |b - A x| over the two directions, the second only
  // when the first left more than a quarter of the residual.
  void kcycle_gcr(std::size_t l) {
    Level& L = levels[l];
    const BlockCsr& A = *L.A;
    const int n = A.rows();
    const auto each = [&](auto&& fn) { parallel_for(n, fn, kVectorGrain); };
    cycle(l, L.b, L.c1);
    A.multiply_dot<true>(L.c1, L.v1);  // v1 = A c1
    const auto [v1v1, v1b] = dot2(L.v1, L.v1, L.b);
    const double b_squared = dot(L.b, L.b);
    if (!(v1v1 > 0)) {
      L.x = L.c1;
      return;
    }
    const double a = v1b / v1v1;
    const double r1_squared = parallel_sum<1>(
        n,
        [&](int lo, int hi, std::array<double, 1>& s) {
          for (int i = lo; i < hi; ++i) {
            const auto is = static_cast<std::size_t>(i);
            L.r1[is] = L.b[is] - a * L.v1[is];
            s[0] += L.r1[is] * L.r1[is];
          }
        },
        kVectorGrain)[0];
    if (std::sqrt(r1_squared) <= kKcycleTolerance * std::sqrt(b_squared)) {
      each(
          [&](int i) { L.x[static_cast<std::size_t>(i)] = a * L.c1[static_cast<std::size_t>(i)]; });
      return;
    }
    cycle(l, L.r1, L.x);              // c2 = L.x
    A.multiply_dot<true>(L.x, L.v2);  // v2 = A c2
    const auto [v2v1, v2r1] = dot2(L.v2, L.v1, L.r1);
    const double g = v2v1 / v1v1;  // v2 - g v1 is orthogonal to v1
    const double w_squared = dot(L.v2, L.v2) - 2 * g * v2v1 + g * g * v1v1;
    if (!(w_squared > 1e-30 * dot(L.v2, L.v2))) {
      each(
          [&](int i) { L.x[static_cast<std::size_t>(i)] = a * L.c1[static_cast<std::size_t>(i)]; });
      return;
    }
    const double a2 = (v2r1 - g * dot(L.v1, L.r1)) / w_squared;
    each([&](int i) {
      const auto is = static_cast<std::size_t>(i);
      L.x[is] = (a - a2 * g) * L.c1[is] + a2 * L.x[is];
    });
  }
};

AmgPcg::AmgPcg(bool symmetric) : symmetric_(symmetric) {}
AmgPcg::~AmgPcg() = default;

int AmgPcg::levels() const {
  return h_ ? static_cast<int>(h_->levels.size()) : 0;
}
int AmgPcg::cells(int level) const {
  return h_->levels.at(static_cast<std::size_t>(level)).A->rows();
}

void AmgPcg::plan(const BlockCsr& A) {
  h_ = std::make_unique<Hierarchy>(A, symmetric_);
  fresh_ = true;
}

void AmgPcg::prepare(const BlockCsr& A, bool changed) {
  if (!h_) plan(A);  // aggregates from the first matrix, kept for the grid's lifetime
  if (fresh_) changed = true;
  fresh_ = false;
  if (&A != h_->levels[0].A) throw std::logic_error("AmgPcg: solve with another matrix");
  if (!A.keeps_single())
    throw std::logic_error("AmgPcg: the matrix must keep its single-precision copy (keep_single)");
  if (changed) h_->load_coefficients();
}

void AmgPcg::precondition(const BlockCsr& A, bool changed, std::span<const double> r,
                          std::span<double> z) {
  prepare(A, changed);
  h_->clear_border();
  h_->cycle(0, r, z);
}

SolveStats AmgPcg::solve(const BlockCsr& A, bool changed, std::span<const double> b,
                         std::span<double> x, const Tolerance& tolerance, int max_iterations) {
  prepare(A, changed);
  h_->clear_border();
  return fcg(start_solve(A, b, x, h_->r), x, tolerance, max_iterations);
}

SolveStats AmgPcg::solve_bordered(const BlockCsr& A, bool changed, const Border& border,
                                  double sign, std::span<const double> b, std::span<double> x,
                                  const Tolerance& tolerance, int max_iterations) {
  if (!symmetric_) throw std::logic_error("AmgPcg::solve_bordered: a symmetric matrix only");
  const auto K = border.columns.size();
  const auto N = static_cast<std::size_t>(A.rows()) + K;
  if (b.size() != N || x.size() != N)
    throw std::invalid_argument("AmgPcg::solve_bordered: b and x need n + K values");
  prepare(A, changed);
  auto& H = *h_;
  H.set_border(border, sign);
  // The start on the bordered matrix (n + K values).
  const LinearMap bordered = [&H](std::span<const double> v, std::span<double> Av) {
    H.multiply_dot<false>(0, v, Av);
  };
  const auto start = start_solve(static_cast<int>(N), bordered, b, x, H.r, H.q, H.z);
  return fcg(start, x, tolerance, max_iterations);
}

SolveStats AmgPcg::fcg(const SolveStart& start, std::span<double> x, const Tolerance& tolerance,
                       int max_iterations) {
  auto& H = *h_;
  const int n = H.levels[0].A->rows() + static_cast<int>(H.K);
  SolveStats stats = start.stats;
  const double norm = start.normalisation, bnorm = start.bnorm;
  double rnorm = start.rnorm;
  if (start.converged(tolerance)) return stats;
  H.cycle(0, H.r, H.z);
  parallel_for(n,
               [&](int i) { H.p[static_cast<std::size_t>(i)] = H.z[static_cast<std::size_t>(i)]; });
  double rz = dot(H.r, H.z);
  for (int it = 1; it <= max_iterations; ++it) {
    const double alpha = rz / H.multiply_dot<false>(0, H.p, H.q);
    const auto [r_squared, r_l1] =
        parallel_sum<2>(n, [&](int lo, int hi, std::array<double, 2>& s) {
          for (int i = lo; i < hi; ++i) {
            const auto is = static_cast<std::size_t>(i);
            x[is] += alpha * H.p[is];
            H.r[is] -= alpha * H.q[is];
            s[0] += H.r[is] * H.r[is];
            s[1] += std::abs(H.r[is]);
          }
        });
    rnorm = std::sqrt(r_squared);
    stats.iterations = it;
    stats.final_residual = r_l1 / norm;
    if (tolerance.met(rnorm, bnorm, stats.final_residual)) return stats;
    if (!std::isfinite(rnorm)) break;
    H.cycle(0, H.r, H.z);
    const auto [rz_new, zq] = dot2(H.z, H.r, H.q);
    const double beta = -alpha * zq / rz;  // z . (r_new - r_old) / rz_old
    rz = rz_new;
    parallel_for(n, [&](int i) {
      const auto is = static_cast<std::size_t>(i);
      H.p[is] = H.z[is] + beta * H.p[is];
    });
  }
  throw std::runtime_error(fmt::format(
      "AMG-CG did not converge in {} iterations: relative residual {:.3g}, normalised {:.3g} ({} "
      "tolerance {:.3g})",
      max_iterations, rnorm / bnorm, stats.final_residual, to_string(tolerance.norm),
      tolerance.value));
}

}  // namespace auvloop::engine::fv
