// SPDX-License-Identifier: GPL-3.0-or-later
// Jacobi-preconditioned conjugate gradients, parallel over rows (oneTBB), private to engine/src.
// Dot products are summed in fixed blocks of rows whose partial sums are added in block order,
// so the iterates are bitwise identical for any number of threads.
#pragma once

#include <Eigen/SparseCore>

namespace auvloop::engine::fv {

// Solves A x = b for a symmetric positive definite A stored in full (both triangles), column
// major; x holds the initial guess. Stops at |b - A x| <= tolerance |b|. Returns the iterations;
// throws std::runtime_error after max_iterations.
int parallel_jacobi_cg(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& A,
                       const Eigen::VectorXd& b, Eigen::Ref<Eigen::VectorXd> x, double tolerance,
                       int max_iterations);

}  // namespace auvloop::engine::fv
