// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::laplacian with over-relaxed deferred non-orthogonal correction (Jasak 1996, section 3.3.1).
#include "auvloop/engine/fv/operators.hpp"

namespace auvloop::engine::fv {

Matrix laplacian(const Mesh& mesh, std::span<const double> gamma, const ScalarField& phi) {
  Matrix m(mesh);
  const auto g = grad(mesh, phi);  // for the explicit correction only
  for (int f = 0; f < mesh.internal_faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    const auto N = static_cast<std::size_t>(mesh.neighbour(f));
    const double c = gamma[fs] * mesh.alpha(f);
    m.diag[P] -= c;
    m.diag[N] -= c;
    m.upper[fs] += c;
    m.lower[fs] += c;
    const double correction = gamma[fs] * mesh.k(f).dot(interpolate(mesh, g, f));
    m.source[P] -= correction;  // the flux leaves P ...
    m.source[N] += correction;  // ... and enters N
  }
  for (int b = 0; b < mesh.boundary_faces(); ++b) {
    const int f = b + mesh.internal_faces();
    const auto fs = static_cast<std::size_t>(f);
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    if (phi.is_empty(mesh, b)) continue;
    const auto [a, v] = phi.value_coeffs(mesh, b);
    if (a == 1.0 && v == 0.0) continue;  // zero gradient: no diffusive flux
    // Flux gamma alpha (phi_b - phi_P) + gamma k . grad(phi)_P with phi_b = a phi_P + v.
    const double c = gamma[fs] * mesh.alpha(f);
    m.diag[P] += c * (a - 1);
    m.source[P] -= c * v + gamma[fs] * mesh.k(f).dot(g[P]);
  }
  return m;
}

Matrix laplacian(const Mesh& mesh, double gamma, const ScalarField& phi) {
  const std::vector<double> g(static_cast<std::size_t>(mesh.faces()), gamma);
  return laplacian(mesh, g, phi);
}

}  // namespace auvloop::engine::fv
