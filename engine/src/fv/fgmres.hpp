// SPDX-License-Identifier: GPL-3.0-or-later
// Flexible GMRES (Saad, "A flexible inner-outer preconditioned GMRES algorithm", SIAM J. Sci.
// Comput. 14, 1993), private to engine/src: the solver of an overset mesh's implicitly coupled
// equations (docs/overset-flow.md), whose matrix is the face-pattern matrix M plus the
// interpolation entries E, preconditioned by a solver of M alone (a multigrid cycle, a direct
// factor, Gauss-Seidel sweeps): the Krylov acceleration of the Schwarz iteration between the
// grids, which converges where the plain iteration (the explicit coupling) may not.
//   1. r = b - A x; stop if the Tolerance (linear_solver.hpp) holds;
//   2. Arnoldi with right preconditioning, v_1 = r / |r|, for j = 1 .. m:
//        z_j = P(v_j)  (P may change from call to call: the z_j are kept),
//        w = A z_j, modified Gram-Schmidt against v_1 .. v_j into the Hessenberg column h_j,
//        v_{j+1} = w / h_{j+1,j}; Givens rotations keep the least-squares residual |g_{j+1}|,
//      until |g_{j+1}| meets the 2-norm equivalent of the tolerance (for the normalised norm
//      scaled by |r|_2 / |r|_1 at the cycle's start);
//   3. x += Z y with y the triangular solve of the rotated system; r = b - A x exactly; back to 1
//      (a restart) until the tolerance holds on the true residual.
// Every vector operation is parallel with fixed-block sums (parallel.hpp): the iterates do not
// depend on the number of threads. Work vectors are kept between solves.
#pragma once

#include <span>
#include <vector>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "krylov.hpp"

namespace auvloop::engine::fv {

struct FgmresWork {
  std::vector<std::vector<double>> V, Z;  // the Krylov basis, its preconditioned vectors
  std::vector<double> r, w, ones;
  void resize(int n, int restart);
};

// Solves A x = b from the guess in x; `restart` the basis size m. Throws std::runtime_error
// after max_iterations or when the residual stops being finite.
SolveStats fgmres(int n, const LinearMap& A, const LinearMap& precondition,
                  std::span<const double> b, std::span<double> x, const Tolerance& tolerance,
                  int max_iterations, int restart, FgmresWork& work);

}  // namespace auvloop::engine::fv
