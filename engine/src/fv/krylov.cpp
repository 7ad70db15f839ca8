// SPDX-License-Identifier: GPL-3.0-or-later
#include "krylov.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "parallel.hpp"

namespace auvloop::engine::fv {

void KrylovWork::resize(int n) {
  for (auto* w : {&r, &r_hat, &p, &v, &s, &t, &y, &z})
    if (w->size() != static_cast<std::size_t>(n)) w->assign(static_cast<std::size_t>(n), 0.0);
}

namespace {
// {sum |b - A x|, sum (b - A x)^2} without storing the residual.
std::array<double, 2> residual_norms(const BlockCsr& A, std::span<const double> b,
                                     std::span<const double> x) {
  return parallel_sum<2>(A.rows(), [&](int lo, int hi, std::array<double, 2>& s) {
    for (int i = lo; i < hi; ++i) {
      const auto is = static_cast<std::size_t>(i);
      const double r = b[is] - A.diag[is] * x[is] - A.off_diagonal(i, x);
      s[0] += std::abs(r);
      s[1] += r * r;
    }
  });
}

// z = M^-1 r for the symmetric hybrid Gauss-Seidel preconditioner: a forward sweep from zero,
// then a backward one (a fixed linear operator: the same partition every time).
void precondition_gs(const BlockCsr& A, std::span<const double> r, std::span<double> z,
                     std::span<double> scratch) {
  A.sweep(r, z, false, true, scratch);  // from z = 0
  A.sweep(r, z, true, false, scratch);
}

}  // namespace

SolveStart start_solve(const BlockCsr& A, std::span<const double> b, std::span<const double> x,
                       std::span<double> r, double normalisation) {
  const auto res = A.residual(b, x, r);
  SolveStart s;
  s.normalisation = normalisation > 0 ? normalisation : res.normalisation + 1e-300;
  s.stats.initial_residual = s.stats.final_residual = res.l1 / s.normalisation;
  s.bnorm = std::max(std::sqrt(res.b_squared), 1e-300);
  s.rnorm = std::sqrt(res.l2_squared);
  return s;
}

SolveStart start_solve(int n, const LinearMap& A, std::span<const double> b,
                       std::span<const double> x, std::span<double> r, std::span<double> Ax,
                       std::span<double> ones) {
  A(x, Ax);
  const double xbar = parallel_sum<1>(n,
                                      [&](int lo, int hi, std::array<double, 1>& s) {
                                        for (int i = lo; i < hi; ++i)
                                          s[0] += x[static_cast<std::size_t>(i)];
                                      })[0] /
                      std::max(n, 1);
  parallel_for(n, [&](int i) { ones[static_cast<std::size_t>(i)] = 1.0; });
  A(ones, r);  // r holds A 1 until the pass below overwrites it with the residual
  const auto s = parallel_sum<4>(n, [&](int lo, int hi, std::array<double, 4>& sum) {
    for (int i = lo; i < hi; ++i) {
      const auto c = static_cast<std::size_t>(i);
      const double axbar = xbar * r[c];
      r[c] = b[c] - Ax[c];
      sum[0] += std::abs(r[c]);
      sum[1] += r[c] * r[c];
      sum[2] += b[c] * b[c];
      sum[3] += std::abs(Ax[c] - axbar) + std::abs(b[c] - axbar);
    }
  });
  SolveStart start;
  start.normalisation = s[3] + 1e-300;
  start.stats.initial_residual = start.stats.final_residual = s[0] / start.normalisation;
  start.bnorm = std::max(std::sqrt(s[2]), 1e-300);
  start.rnorm = std::sqrt(s[1]);
  return start;
}

namespace {
[[noreturn]] void fail(const char* method, int iterations, double relative, double normalised,
                       const Tolerance& tolerance) {
  throw std::runtime_error(fmt::format(
      "{} did not converge in {} iterations: relative residual {:.3g}, normalised {:.3g} "
      "({} tolerance {:.3g})",
      method, iterations, relative, normalised, to_string(tolerance.norm), tolerance.value));
}
}  // namespace

SmootherResult gauss_seidel_solve(const BlockCsr& A, std::span<const double> b, std::span<double> x,
                                  const Tolerance& tolerance, int max_sweeps, KrylovWork& work) {
  work.resize(A.rows());
  const auto start = start_solve(A, b, x, work.r);
  SmootherResult out;
  out.stats = start.stats;
  out.normalisation = start.normalisation;
  const double norm = start.normalisation, bnorm = start.bnorm;
  double rnorm = start.rnorm;
  for (int sweep = 1; !tolerance.met(rnorm, bnorm, out.stats.final_residual); ++sweep) {
    if (sweep > max_sweeps) return out;
    A.sweep(b, x, false, false, work.s);
    A.sweep(b, x, true, false, work.s);
    const auto [l1, l2] = residual_norms(A, b, x);
    rnorm = std::sqrt(l2);
    out.stats.iterations = sweep;
    out.stats.final_residual = l1 / norm;
    if (!std::isfinite(rnorm))
      fail("Gauss-Seidel", sweep, rnorm / bnorm, out.stats.final_residual, tolerance);
  }
  out.converged = true;
  return out;
}

SolveStats bicgstab(const BlockCsr& A, std::span<const double> b, std::span<double> x,
                    const Tolerance& tolerance, int max_iterations, KrylovWork& w,
                    Preconditioner preconditioner, double normalisation) {
  const int n = A.rows();
  w.resize(n);
  const auto& inv = A.inverse_diag();
  const auto start = start_solve(A, b, x, w.r, normalisation);
  SolveStats stats = start.stats;
  const double norm = start.normalisation, bnorm = start.bnorm;
  double rnorm = start.rnorm;
  if (start.converged(tolerance)) return stats;
  const auto each = [&](auto&& fn) { parallel_for(n, fn); };
  each([&](int i) {
    const auto k = static_cast<std::size_t>(i);
    w.r_hat[k] = w.r[k];
    w.p[k] = w.v[k] = 0;
  });
  double rho = 1, alpha = 1, omega = 1, r_hat_squared = rnorm * rnorm;
  for (int it = 1; it <= max_iterations; ++it) {
    double rho_new = dot(w.r_hat, w.r);
    if (std::abs(rho_new) < 1e-30 * r_hat_squared) {  // breakdown: restart from the residual
      each([&](int i) {
        const auto k = static_cast<std::size_t>(i);
        w.r_hat[k] = w.r[k];
        w.p[k] = w.v[k] = 0;
      });
      r_hat_squared = rho_new = dot(w.r, w.r);
      rho = alpha = omega = 1;
    }
    const double beta = (rho_new / rho) * (alpha / omega);
    rho = rho_new;
    each([&](int i) {
      const auto k = static_cast<std::size_t>(i);
      w.p[k] = w.r[k] + beta * (w.p[k] - omega * w.v[k]);
      w.y[k] = inv[k] * w.p[k];
    });
    if (preconditioner == Preconditioner::gauss_seidel) precondition_gs(A, w.p, w.y, w.t);
    A.multiply(w.y, w.v);
    alpha = rho / dot(w.r_hat, w.v);
    each([&](int i) {
      const auto k = static_cast<std::size_t>(i);
      w.s[k] = w.r[k] - alpha * w.v[k];
      w.z[k] = inv[k] * w.s[k];
    });
    if (preconditioner == Preconditioner::gauss_seidel) precondition_gs(A, w.s, w.z, w.t);
    A.multiply(w.z, w.t);
    const auto [ts, tt] = dot2(w.t, w.s, w.t);
    omega = tt > 0 ? ts / tt : 0;
    const auto [r_squared, r_l1] =
        parallel_sum<2>(n, [&](int lo, int hi, std::array<double, 2>& s) {
          for (int i = lo; i < hi; ++i) {
            const auto k = static_cast<std::size_t>(i);
            x[k] += alpha * w.y[k] + omega * w.z[k];
            w.r[k] = w.s[k] - omega * w.t[k];
            s[0] += w.r[k] * w.r[k];
            s[1] += std::abs(w.r[k]);
          }
        });
    rnorm = std::sqrt(r_squared);
    stats.iterations = it;
    stats.final_residual = r_l1 / norm;
    if (!std::isfinite(rnorm)) break;
    if (tolerance.met(rnorm, bnorm, stats.final_residual) || omega == 0) {
      // The recursive residual drifts from the true one (and can reach zero in a breakdown):
      // converged only if the true residual agrees; otherwise restart from it.
      const auto true_res = A.residual(b, x, w.r);
      rnorm = std::sqrt(true_res.l2_squared);
      stats.final_residual = true_res.l1 / norm;
      if (tolerance.met(rnorm, bnorm, stats.final_residual)) return stats;
      if (!(rnorm > 0) || !std::isfinite(rnorm)) break;
      each([&](int i) {
        const auto k = static_cast<std::size_t>(i);
        w.r_hat[k] = w.r[k];
        w.p[k] = w.v[k] = 0;
      });
      r_hat_squared = true_res.l2_squared;
      rho = alpha = omega = 1;
    }
  }
  fail("BiCGSTAB", stats.iterations, rnorm / bnorm, stats.final_residual, tolerance);
}

SolveStats jacobi_cg(const BlockCsr& A, std::span<const double> b, std::span<double> x,
                     const Tolerance& tolerance, int max_iterations, KrylovWork& w) {
  const int n = A.rows();
  w.resize(n);
  const auto& inv = A.inverse_diag();
  const auto start = start_solve(A, b, x, w.r);
  SolveStats stats = start.stats;
  const double norm = start.normalisation, bnorm = start.bnorm;
  double rnorm = start.rnorm;
  if (start.converged(tolerance)) return stats;
  double rz = parallel_sum<1>(n, [&](int lo, int hi, std::array<double, 1>& s) {
    for (int i = lo; i < hi; ++i) {
      const auto k = static_cast<std::size_t>(i);
      w.p[k] = w.z[k] = inv[k] * w.r[k];
      s[0] += w.r[k] * w.z[k];
    }
  })[0];
  for (int it = 1; it <= max_iterations; ++it) {
    const double alpha = rz / A.multiply_dot(w.p, w.v);
    const auto [r_squared, r_l1, rz_new] =
        parallel_sum<3>(n, [&](int lo, int hi, std::array<double, 3>& s) {
          for (int i = lo; i < hi; ++i) {
            const auto k = static_cast<std::size_t>(i);
            x[k] += alpha * w.p[k];
            w.r[k] -= alpha * w.v[k];
            w.z[k] = inv[k] * w.r[k];
            s[0] += w.r[k] * w.r[k];
            s[1] += std::abs(w.r[k]);
            s[2] += w.r[k] * w.z[k];
          }
        });
    rnorm = std::sqrt(r_squared);
    stats.iterations = it;
    stats.final_residual = r_l1 / norm;
    if (tolerance.met(rnorm, bnorm, stats.final_residual)) return stats;
    if (!std::isfinite(rnorm)) break;
    const double beta = rz_new / rz;
    rz = rz_new;
    parallel_for(n, [&](int i) {
      const auto k = static_cast<std::size_t>(i);
      w.p[k] = w.z[k] + beta * w.p[k];
    });
  }
  fail("Jacobi-CG", stats.iterations, rnorm / bnorm, stats.final_residual, tolerance);
}

}  // namespace auvloop::engine::fv
