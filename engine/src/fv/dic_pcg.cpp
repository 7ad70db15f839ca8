// SPDX-License-Identifier: GPL-3.0-or-later
#include "dic_pcg.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "parallel.hpp"

namespace auvloop::engine::fv {

namespace {
constexpr int kBlock = 4096;  // rows per partial sum: fixed, independent of the thread count

// Sum of a[i] b[i] in fixed blocks, summed in block order: deterministic for any thread count.
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  const int n = static_cast<int>(a.size());
  std::vector<double> partial(static_cast<std::size_t>((n + kBlock - 1) / kBlock));
  parallel_for(
      static_cast<int>(partial.size()),
      [&](int k) {
        double s = 0;
        for (int i = k * kBlock; i < std::min(n, (k + 1) * kBlock); ++i)
          s += a[static_cast<std::size_t>(i)] * b[static_cast<std::size_t>(i)];
        partial[static_cast<std::size_t>(k)] = s;
      },
      1);
  double s = 0;
  for (double p : partial) s += p;
  return s;
}

// w = (L + D) D^-1 (D + U) preconditioner applied to r, with D the DIC diagonal (stored inverted).
void precondition(const Mesh& mesh, const Matrix& A, const std::vector<double>& rD,
                  const std::vector<double>& r, std::vector<double>& w) {
  for (std::size_t c = 0; c < w.size(); ++c) w[c] = rD[c] * r[c];
  const int nf = mesh.internal_faces();
  for (int f = 0; f < nf; ++f) {
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    const auto N = static_cast<std::size_t>(mesh.neighbour(f));
    w[N] -= rD[N] * A.upper[static_cast<std::size_t>(f)] * w[P];
  }
  for (int f = nf - 1; f >= 0; --f) {
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    const auto N = static_cast<std::size_t>(mesh.neighbour(f));
    w[P] -= rD[P] * A.upper[static_cast<std::size_t>(f)] * w[N];
  }
}
// The matrix by rows (CSR) for the products of one solve: built once per solve, then each product
// is a contiguous per-row gather, in parallel, with the terms of each row in ascending face order
// (Mesh::cell_faces), as Matrix::multiply adds them: the same bits.
struct Rows {
  std::vector<int> start, column;
  std::vector<double> value;

  Rows(const Mesh& mesh, const Matrix& A) : start(A.diag.size() + 1, 0) {
    const int internal = mesh.internal_faces();
    column.reserve(2 * static_cast<std::size_t>(internal));
    value.reserve(2 * static_cast<std::size_t>(internal));
    for (int c = 0; c < mesh.cells(); ++c) {
      for (int f : mesh.cell_faces(c)) {
        if (f >= internal) break;  // boundary faces come last
        const bool owner = mesh.owner(f) == c;
        column.push_back(owner ? mesh.neighbour(f) : mesh.owner(f));
        value.push_back(owner ? A.upper[static_cast<std::size_t>(f)]
                              : A.lower[static_cast<std::size_t>(f)]);
      }
      start[static_cast<std::size_t>(c) + 1] = static_cast<int>(column.size());
    }
  }

  void multiply(const std::vector<double>& diag, std::span<const double> x,
                std::vector<double>& y) const {
    parallel_for(static_cast<int>(diag.size()), [&](int c) {
      const auto C = static_cast<std::size_t>(c);
      double sum = diag[C] * x[C];
      for (int k = start[C]; k < start[C + 1]; ++k)
        sum += value[static_cast<std::size_t>(k)] *
               x[static_cast<std::size_t>(column[static_cast<std::size_t>(k)])];
      y[C] = sum;
    });
  }
};
}  // namespace

int dic_pcg(const Mesh& mesh, const Matrix& A, std::span<double> x, double tolerance,
            int max_iterations) {
  const std::size_t n = A.diag.size();
  std::vector<double> rD = A.diag;
  for (int f = 0; f < mesh.internal_faces(); ++f) {
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    const auto N = static_cast<std::size_t>(mesh.neighbour(f));
    const double a = A.upper[static_cast<std::size_t>(f)];
    rD[N] -= a * a / rD[P];
  }
  for (double& d : rD) d = 1.0 / d;
  std::vector<double> r(n), w(n), p(n), Ap(n);
  const Rows rows(mesh, A);
  rows.multiply(A.diag, x, Ap);
  for (std::size_t i = 0; i < n; ++i) r[i] = A.source[i] - Ap[i];
  const double bnorm = std::max(std::sqrt(dot(A.source, A.source)), 1e-300);
  double rnorm = std::sqrt(dot(r, r));
  if (rnorm <= tolerance * bnorm) return 0;
  precondition(mesh, A, rD, r, w);
  p = w;
  double rw = dot(r, w);
  for (int it = 1; it <= max_iterations; ++it) {
    rows.multiply(A.diag, p, Ap);
    const double alpha = rw / dot(p, Ap);
    parallel_for(static_cast<int>(n), [&](int k) {
      const auto i = static_cast<std::size_t>(k);
      x[i] += alpha * p[i];
      r[i] -= alpha * Ap[i];
    });
    rnorm = std::sqrt(dot(r, r));
    if (rnorm <= tolerance * bnorm) return it;
    precondition(mesh, A, rD, r, w);
    const double rw_new = dot(r, w);
    const double beta = rw_new / rw;
    rw = rw_new;
    parallel_for(static_cast<int>(n), [&](int k) {
      const auto i = static_cast<std::size_t>(k);
      p[i] = w[i] + beta * p[i];
    });
  }
  throw std::runtime_error("DIC-CG did not converge in " + std::to_string(max_iterations) +
                           " iterations: relative residual " + std::to_string(rnorm / bnorm));
}

}  // namespace auvloop::engine::fv
