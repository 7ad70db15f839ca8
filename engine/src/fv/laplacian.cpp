// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::laplacian with over-relaxed deferred non-orthogonal correction (Jasak 1996, section 3.3.1):
//   1. on a non-orthogonal grid, grad(phi) from the current phi (for the correction only), or
//      the one the caller supplies;
//   2. per face, with c = gamma_f alpha_f:
//        internal: upper = lower = c, diag_P -= c, diag_N -= c, and the explicit flux
//                  gamma_f k_f . grad(phi)_f to the sources (out of P, into N);
//        boundary: phi_b = a phi_P + v, flux c (phi_b - phi_P) + gamma_f k_f . grad(phi)_P:
//                  diag_P += c (a - 1), source_P -= c v + gamma_f k_f . grad(phi)_P;
//      in one parallel face scatter (scatter_faces): each cell's sums in ascending face order, so
//      the result does not depend on the number of threads.
#include <stdexcept>

#include "auvloop/engine/fv/operators.hpp"
#include "parallel.hpp"
#include "scratch.hpp"

namespace auvloop::engine::fv {

void LaplacianTerm::add_to(Matrix& eq, double sign) const {
  const Mesh& mesh = *m;
  const bool corrected = !mesh.orthogonal();
  const bool own_gradient = corrected && grad.empty();
  Scratch<Eigen::Vector3d> computed(own_gradient ? static_cast<std::size_t>(mesh.cells()) : 0);
  if (own_gradient) mesh.gradient(phi->cells, phi->boundary, *computed);
  if (corrected && !own_gradient && grad.size() != static_cast<std::size_t>(mesh.cells()))
    throw std::invalid_argument("laplacian: a supplied gradient needs one vector per cell");
  const std::span<const Eigen::Vector3d> g =
      own_gradient ? std::span<const Eigen::Vector3d>(*computed) : grad;
  const int internal = mesh.internal_faces();
  const auto gamma = [&](std::size_t f) {
    return gamma_faces.empty() ? gamma_uniform : gamma_faces[f];
  };
  scatter_faces(
      mesh, [](int, int) {},
      [&](int f, bool own, bool nei) {
        const auto fs = static_cast<std::size_t>(f);
        const double gf = sign * gamma(fs);
        const double c = gf * mesh.alpha(f);
        const auto P = static_cast<std::size_t>(mesh.owner(f));
        if (f < internal) {
          const double correction = corrected ? gf * mesh.k(f).dot(interpolate(mesh, g, f)) : 0.0;
          if (own) {
            eq.upper[fs] += c;
            eq.lower[fs] += c;
            eq.diag[P] -= c;
            eq.source[P] -= correction;
          }
          if (nei) {
            const auto N = static_cast<std::size_t>(mesh.neighbour(f));
            eq.diag[N] -= c;
            eq.source[N] += correction;
          }
          return;
        }
        const int b = f - internal;
        if (phi->is_empty(mesh, b)) return;
        const auto [a, v] = phi->value_coeffs(mesh, b);
        if (a == 1.0 && v == 0.0) return;  // zero gradient: no diffusive flux
        eq.diag[P] += c * (a - 1);
        eq.source[P] -= c * v + (corrected ? gf * mesh.k(f).dot(g[P]) : 0.0);
      });
}

}  // namespace auvloop::engine::fv
