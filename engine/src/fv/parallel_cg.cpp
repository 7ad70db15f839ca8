// SPDX-License-Identifier: GPL-3.0-or-later
#include "parallel_cg.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "parallel.hpp"

namespace auvloop::engine::fv {

namespace {
constexpr int kBlock = 4096;  // rows per partial sum: fixed, independent of the thread count

using Vec = Eigen::VectorXd;

double dot(const Vec& a, const Vec& b) {
  const int n = static_cast<int>(a.size());
  const int blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> partial(static_cast<std::size_t>(blocks));
  parallel_for(
      blocks,
      [&](int k) {
        const int begin = k * kBlock, len = std::min(kBlock, n - begin);
        partial[static_cast<std::size_t>(k)] = a.segment(begin, len).dot(b.segment(begin, len));
      },
      1);
  double s = 0;
  for (double p : partial) s += p;
  return s;
}

// y = A x; column i of the symmetric A is row i.
void multiply(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A, const Vec& x, Vec& y) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* v = A.valuePtr();
  parallel_for(static_cast<int>(A.cols()), [&](int i) {
    double s = 0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) s += v[k] * x[inner[k]];
    y[i] = s;
  });
}
}  // namespace

int parallel_jacobi_cg(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A, const Vec& b,
                       Eigen::Ref<Vec> x, double tolerance, int max_iterations) {
  const int n = static_cast<int>(A.cols());
  Vec inv_diag(n), r(n), z(n), p(n), Ap(n);
  const Vec diag = A.diagonal();
  parallel_for(n, [&](int i) { inv_diag[i] = 1.0 / diag[i]; });
  multiply(A, x, Ap);
  parallel_for(n, [&](int i) { r[i] = b[i] - Ap[i]; });
  const double bnorm = std::max(std::sqrt(dot(b, b)), 1e-300);
  double rnorm = std::sqrt(dot(r, r));
  if (rnorm <= tolerance * bnorm) return 0;
  parallel_for(n, [&](int i) { p[i] = z[i] = inv_diag[i] * r[i]; });
  double rz = dot(r, z);
  for (int it = 1; it <= max_iterations; ++it) {
    multiply(A, p, Ap);
    const double alpha = rz / dot(p, Ap);
    parallel_for(n, [&](int i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * Ap[i];
      z[i] = inv_diag[i] * r[i];
    });
    rnorm = std::sqrt(dot(r, r));
    if (rnorm <= tolerance * bnorm) return it;
    const double rz_new = dot(r, z);
    const double beta = rz_new / rz;
    rz = rz_new;
    parallel_for(n, [&](int i) { p[i] = z[i] + beta * p[i]; });
  }
  throw std::runtime_error("Jacobi-CG did not converge in " + std::to_string(max_iterations) +
                           " iterations: relative residual " + std::to_string(rnorm / bnorm));
}

}  // namespace auvloop::engine::fv
