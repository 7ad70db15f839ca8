// SPDX-License-Identifier: GPL-3.0-or-later
// Conjugate gradients with a diagonal incomplete Cholesky (DIC) preconditioner on an LDU matrix,
// private to engine/src. DIC keeps the off-diagonal coefficients and only modifies the diagonal,
// D_N -= a_f^2 / D_P over the faces in upper-triangular order (Meijerink and van der Vorst's
// IC(0) for matrices whose off-diagonals are those of the mesh): no storage beyond one vector,
// and the sweeps follow the face order (serial). The matrix product, updates and dot products
// (fixed 4096-row blocks) run in parallel; the result does not depend on the thread count.
#pragma once

#include <span>

#include "auvloop/engine/fv/matrix.hpp"

namespace auvloop::engine::fv {

// Solves A x = A.source for a symmetric positive definite A (upper == lower); x holds the
// initial guess. Stops at |b - A x| <= tolerance |b|; returns the iterations, throws
// std::runtime_error after max_iterations.
int dic_pcg(const Mesh& mesh, const Matrix& A, std::span<double> x, double tolerance,
            int max_iterations);

}  // namespace auvloop::engine::fv
