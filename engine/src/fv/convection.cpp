// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::div(F, phi): upwind in the matrix, the higher-order scheme as a deferred correction
// F (phi_f^scheme - phi_f^upwind) from the current iterate (Khosla and Rubin 1974), so the matrix
// stays an M-matrix and the converged solution is the scheme's.
#include <algorithm>
#include <cmath>

#include "auvloop/engine/fv/operators.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

namespace {
// Face value of phi on the face between upwind cell C and downwind cell D.
double high_order(const Mesh& mesh, Convection scheme, int f, double phiC, double phiD,
                  const Eigen::Vector3d& gradC, const Eigen::Vector3d& xC,
                  const Eigen::Vector3d& xD) {
  switch (scheme) {
    case Convection::upwind:
      return phiC;
    case Convection::linear_upwind:
      return phiC + gradC.dot(mesh.face_centre(f) - xC);
    case Convection::van_leer: {
      const double delta = phiD - phiC;
      if (std::abs(delta) < 1e-300) return phiC;
      const double r = 2 * gradC.dot(xD - xC) / delta - 1;
      const double psi = (r + std::abs(r)) / (1 + std::abs(r));
      return phiC + 0.5 * psi * delta;
    }
  }
  return phiC;
}
}  // namespace

// Two passes as in laplacian(): per face in parallel, then accumulate_faces, so the sums are
// those of a serial face loop whatever the number of threads.
Matrix div(const Mesh& mesh, std::span<const double> flux, const ScalarField& phi,
           Convection scheme) {
  Matrix m(mesh);
  std::vector<Eigen::Vector3d> g;
  if (scheme != Convection::upwind) g = grad(mesh, phi);
  const auto& v = phi.cells;
  const int internal = mesh.internal_faces();
  // Internal faces: the deferred correction; boundary faces: F phi_b = F (a phi_P + value).
  std::vector<double> correction(static_cast<std::size_t>(mesh.faces()), 0.0);
  std::vector<double> boundary_diag(static_cast<std::size_t>(mesh.boundary_faces()), 0.0);
  parallel_for(mesh.faces(), [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    const double F = flux[fs];
    if (f >= internal) {
      const int b = f - internal;
      if (phi.is_empty(mesh, b)) return;
      const auto [a, value] = phi.value_coeffs(mesh, b);
      boundary_diag[static_cast<std::size_t>(b)] = F * a;
      correction[fs] = F * value;
      return;
    }
    m.upper[fs] = std::min(F, 0.0);
    m.lower[fs] = -std::max(F, 0.0);
    if (scheme == Convection::upwind) return;
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    const auto N = static_cast<std::size_t>(mesh.neighbour(f));
    const bool fromP = F >= 0;
    const auto C = fromP ? P : N, D = fromP ? N : P;
    // Centres in the owner's frame (a periodic neighbour is seen at its image).
    const Eigen::Vector3d& xP = mesh.centre(static_cast<int>(P));
    const Eigen::Vector3d xN = mesh.neighbour_centre(f);
    correction[fs] =
        F *
        (high_order(mesh, scheme, f, v[C], v[D], g[C], fromP ? xP : xN, fromP ? xN : xP) - v[C]);
  });
  accumulate_faces(mesh, m.diag, m.source, [&](int f, bool owner_side) {
    const auto fs = static_cast<std::size_t>(f);
    const double F = flux[fs];
    if (f >= internal)
      return std::array<double, 2>{boundary_diag[static_cast<std::size_t>(f - internal)],
                                   -correction[fs]};
    return owner_side ? std::array<double, 2>{std::max(F, 0.0), -correction[fs]}
                      : std::array<double, 2>{std::max(-F, 0.0), correction[fs]};
  });
  return m;
}

}  // namespace auvloop::engine::fv
