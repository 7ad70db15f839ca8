// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::laplacian with over-relaxed deferred non-orthogonal correction (Jasak 1996, section 3.3.1).
#include "auvloop/engine/fv/operators.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

// Two passes: per face in parallel (coefficients and the explicit corrections), then the
// diagonal and source summed per cell in ascending face order (accumulate_faces: a parallel
// gather, or the face scatter on one thread), so the result does not depend on the thread count.
Matrix laplacian(const Mesh& mesh, std::span<const double> gamma, const ScalarField& phi) {
  Matrix m(mesh);
  const auto g = grad(mesh, phi);  // for the explicit correction only
  const int internal = mesh.internal_faces();
  std::vector<double> correction(static_cast<std::size_t>(mesh.faces()), 0.0);
  std::vector<double> boundary_diag(static_cast<std::size_t>(mesh.boundary_faces()), 0.0);
  parallel_for(mesh.faces(), [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    const double c = gamma[fs] * mesh.alpha(f);
    if (f < internal) {
      m.upper[fs] = c;
      m.lower[fs] = c;
      correction[fs] = gamma[fs] * mesh.k(f).dot(interpolate(mesh, g, f));
      return;
    }
    const int b = f - internal;
    if (phi.is_empty(mesh, b)) return;
    const auto [a, v] = phi.value_coeffs(mesh, b);
    if (a == 1.0 && v == 0.0) return;  // zero gradient: no diffusive flux
    // Flux gamma alpha (phi_b - phi_P) + gamma k . grad(phi)_P with phi_b = a phi_P + v.
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    boundary_diag[static_cast<std::size_t>(b)] = c * (a - 1);
    correction[fs] = c * v + gamma[fs] * mesh.k(f).dot(g[P]);
  });
  accumulate_faces(mesh, m.diag, m.source, [&](int f, bool owner_side) {
    const auto fs = static_cast<std::size_t>(f);
    if (f >= internal)
      return std::array<double, 2>{boundary_diag[static_cast<std::size_t>(f - internal)],
                                   -correction[fs]};
    // The flux leaves the owner and enters the neighbour.
    return std::array<double, 2>{-gamma[fs] * mesh.alpha(f),
                                 owner_side ? -correction[fs] : correction[fs]};
  });
  return m;
}

Matrix laplacian(const Mesh& mesh, double gamma, const ScalarField& phi) {
  const std::vector<double> g(static_cast<std::size_t>(mesh.faces()), gamma);
  return laplacian(mesh, g, phi);
}

}  // namespace auvloop::engine::fv
