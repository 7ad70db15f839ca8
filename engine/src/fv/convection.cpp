// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::div(F, phi): upwind in the matrix, the higher-order scheme as a deferred correction
// F (phi_f^scheme - phi_f^upwind) from the current iterate (Khosla and Rubin 1974), so the matrix
// stays an M-matrix and the converged solution is the scheme's.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "auvloop/engine/fv/operators.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

namespace {
// van Leer's limited value at the mid-point of the upwind centre C and downwind centre D, with
// the Darwish-Moukalled ratio r = 2 grad(phi)_C . d_CD / (phi_D - phi_C) - 1.
double van_leer(double phiC, double phiD, const Eigen::Vector3d& gradC, const Eigen::Vector3d& xC,
                const Eigen::Vector3d& xD) {
  const double delta = phiD - phiC;
  if (std::abs(delta) < 1e-300) return phiC;
  const double r = 2 * gradC.dot(xD - xC) / delta - 1;
  const double psi = (r + std::abs(r)) / (1 + std::abs(r));
  return phiC + 0.5 * psi * delta;
}

// The range of phi over each cell and its face neighbours (boundary values included).
std::vector<std::pair<double, double>> neighbourhood_range(const Mesh& mesh,
                                                           const ScalarField& phi) {
  std::vector<std::pair<double, double>> r(phi.cells.size());
  for (std::size_t c = 0; c < r.size(); ++c) r[c] = {phi.cells[c], phi.cells[c]};
  auto widen = [&](std::size_t c, double v) {
    r[c] = {std::min(r[c].first, v), std::max(r[c].second, v)};
  };
  for (int f = 0; f < mesh.faces(); ++f) {
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    if (f < mesh.internal_faces()) {
      const auto N = static_cast<std::size_t>(mesh.neighbour(f));
      widen(P, phi.cells[N]);
      widen(N, phi.cells[P]);
    } else if (!phi.is_empty(mesh, f - mesh.internal_faces())) {
      widen(P, phi.boundary[static_cast<std::size_t>(f - mesh.internal_faces())]);
    }
  }
  return r;
}

// Face value of phi on the face between upwind cell C and downwind cell D; rangeC is the range
// of phi around C (van_leer_skew only).
double high_order(const Mesh& mesh, Convection scheme, int f, double phiC, double phiD,
                  const Eigen::Vector3d& gradC, const Eigen::Vector3d& xC,
                  const Eigen::Vector3d& xD, std::pair<double, double> rangeC) {
  switch (scheme) {
    case Convection::upwind:
      return phiC;
    case Convection::linear_upwind:
      return phiC + gradC.dot(mesh.face_centre(f) - xC);
    case Convection::van_leer:
      return van_leer(phiC, phiD, gradC, xC, xD);
    case Convection::van_leer_skew: {
      // The shift is bounded by the range around C, not by [phi_C, phi_D]: on a face whose
      // centre line is nearly normal to grad(phi), phi_C ~ phi_D while the face centre's value
      // differs by O(skewness h), and clipping to [phi_C, phi_D] would keep that error.
      const double mid = van_leer(phiC, phiD, gradC, xC, xD);
      const double shifted = mid + gradC.dot(mesh.face_centre(f) - 0.5 * (xC + xD));
      return std::clamp(shifted, rangeC.first, rangeC.second);
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
  std::vector<std::pair<double, double>> range;
  if (scheme == Convection::van_leer_skew) range = neighbourhood_range(mesh, phi);
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
        F * (high_order(mesh, scheme, f, v[C], v[D], g[C], fromP ? xP : xN, fromP ? xN : xP,
                        range.empty() ? std::pair<double, double>{} : range[C]) -
             v[C]);
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
