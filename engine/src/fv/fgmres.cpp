// SPDX-License-Identifier: GPL-3.0-or-later
// Flexible GMRES (fgmres.hpp states the algorithm).
#include "fgmres.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "parallel.hpp"
#include "sparse.hpp"

namespace auvloop::engine::fv {

void FgmresWork::resize(int n, int restart) {
  const auto nu = static_cast<std::size_t>(n);
  const auto m = static_cast<std::size_t>(restart);
  if (V.size() != m + 1) V.resize(m + 1);
  if (Z.size() != m) Z.resize(m);
  for (auto& v : V) v.resize(nu);
  for (auto& z : Z) z.resize(nu);
  for (auto* v : {&r, &w, &ones}) v->resize(nu);
}

namespace {
// {sum |r|, sum r^2} of r = b - Ax, written to r.
std::array<double, 2> residual(int n, std::span<const double> b, std::span<const double> Ax,
                               std::span<double> r) {
  return parallel_sum<2>(n, [&](int lo, int hi, std::array<double, 2>& s) {
    for (int i = lo; i < hi; ++i) {
      const auto k = static_cast<std::size_t>(i);
      r[k] = b[k] - Ax[k];
      s[0] += std::abs(r[k]);
      s[1] += r[k] * r[k];
    }
  });
}
}  // namespace

SolveStats fgmres(int n, const LinearMap& A, const LinearMap& precondition,
                  std::span<const double> b, std::span<double> x, const Tolerance& tolerance,
                  int max_iterations, int restart, FgmresWork& W) {
  W.resize(n, restart);
  const auto m = static_cast<std::size_t>(restart);
  // 1. The start: r = b - A x and OpenFOAM's normalisation (krylov.hpp).
  const auto start = start_solve(n, A, b, x, W.r, W.w, W.ones);
  const double norm = start.normalisation, bnorm = start.bnorm;
  SolveStats stats = start.stats;
  double rnorm = start.rnorm;
  double l1 = stats.initial_residual * norm;
  std::vector<double> H((m + 1) * m), cs(m), sn(m), g(m + 1), y(m);
  const auto h = [&](std::size_t i, std::size_t j) -> double& { return H[j * (m + 1) + i]; };
  while (!tolerance.met(rnorm, bnorm, stats.final_residual)) {
    if (!std::isfinite(rnorm) || stats.iterations >= max_iterations)
      throw std::runtime_error(fmt::format(
          "FGMRES did not converge in {} iterations: relative residual {:.3g}, normalised {:.3g} "
          "({} tolerance {:.3g})",
          stats.iterations, rnorm / bnorm, stats.final_residual, to_string(tolerance.norm),
          tolerance.value));
    // 2. Arnoldi from v_1 = r / |r|.
    const double target = tolerance.norm == ResidualNorm::relative
                              ? tolerance.value * bnorm
                              : tolerance.value * norm * rnorm / std::max(l1, 1e-300);
    parallel_for(n, [&](int i) {
      const auto k = static_cast<std::size_t>(i);
      W.V[0][k] = W.r[k] / rnorm;
    });
    std::fill(g.begin(), g.end(), 0.0);
    g[0] = rnorm;
    std::size_t k = 0;
    while (k < m && stats.iterations < max_iterations) {
      const std::size_t j = k;
      precondition(W.V[j], W.Z[j]);
      A(W.Z[j], W.w);
      for (std::size_t i = 0; i <= j; ++i) {
        const double hij = dot(W.w, W.V[i]);
        h(i, j) = hij;
        parallel_for(n, [&](int q) {
          const auto s = static_cast<std::size_t>(q);
          W.w[s] -= hij * W.V[i][s];
        });
      }
      const double next = std::sqrt(dot(W.w, W.w));
      h(j + 1, j) = next;
      if (next > 0)
        parallel_for(n, [&](int q) {
          const auto s = static_cast<std::size_t>(q);
          W.V[j + 1][s] = W.w[s] / next;
        });
      for (std::size_t i = 0; i < j; ++i) {  // the earlier rotations on the new column
        const double a = h(i, j), c = h(i + 1, j);
        h(i, j) = cs[i] * a + sn[i] * c;
        h(i + 1, j) = -sn[i] * a + cs[i] * c;
      }
      const double a = h(j, j), c = h(j + 1, j), d = std::hypot(a, c);
      cs[j] = d > 0 ? a / d : 1.0;
      sn[j] = d > 0 ? c / d : 0.0;
      h(j, j) = d;
      h(j + 1, j) = 0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      ++k;
      ++stats.iterations;
      if (std::abs(g[k]) <= target || !(next > 0) || !std::isfinite(g[k])) break;
    }
    // 3. x += Z y, then the true residual.
    for (std::size_t i = k; i-- > 0;) {
      double s = g[i];
      for (std::size_t q = i + 1; q < k; ++q) s -= h(i, q) * y[q];
      y[i] = h(i, i) != 0 ? s / h(i, i) : 0.0;
    }
    parallel_for(n, [&](int q) {
      const auto s = static_cast<std::size_t>(q);
      double dx = 0;
      for (std::size_t i = 0; i < k; ++i) dx += y[i] * W.Z[i][s];
      x[s] += dx;
    });
    A(x, W.w);
    const auto norms = residual(n, b, W.w, W.r);
    l1 = norms[0];
    rnorm = std::sqrt(norms[1]);
    stats.final_residual = l1 / norm;
  }
  return stats;
}

}  // namespace auvloop::engine::fv
