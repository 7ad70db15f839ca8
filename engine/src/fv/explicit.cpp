// SPDX-License-Identifier: GPL-3.0-or-later
// Explicit operators (fvc): cell gradient, face interpolation, divergence of a face flux.
#include "auvloop/engine/fv/operators.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

std::vector<Eigen::Vector3d> grad(const Mesh& mesh, const ScalarField& phi) {
  std::vector<Eigen::Vector3d> g(static_cast<std::size_t>(mesh.cells()));
  mesh.gradient(phi.cells, phi.boundary, g);
  return g;
}

Eigen::Vector3d interpolate(const Mesh& mesh, std::span<const Eigen::Vector3d> cells, int f) {
  const double w = mesh.weight(f);
  return w * cells[static_cast<std::size_t>(mesh.owner(f))] +
         (1 - w) * cells[static_cast<std::size_t>(mesh.neighbour(f))];
}

double interpolate(const Mesh& mesh, std::span<const double> cells,
                   std::span<const Eigen::Vector3d> gradients, int f) {
  const double w = mesh.weight(f);
  const auto P = static_cast<std::size_t>(mesh.owner(f));
  const auto N = static_cast<std::size_t>(mesh.neighbour(f));
  const Eigen::Vector3d g = w * gradients[P] + (1 - w) * gradients[N];
  return w * cells[P] + (1 - w) * cells[N] + g.dot(mesh.skew(f));
}

std::vector<double> div(const Mesh& mesh, std::span<const double> face_flux) {
  std::vector<double> d(static_cast<std::size_t>(mesh.cells()));
  div(mesh, face_flux, d);
  return d;
}

void div(const Mesh& mesh, std::span<const double> face_flux, std::span<double> out) {
  sum_faces(
      mesh, out, [&](int f) { return face_flux[static_cast<std::size_t>(f)]; }, -1.0);
  parallel_for(mesh.cells(), [&](int c) { out[static_cast<std::size_t>(c)] /= mesh.volume(c); });
}

}  // namespace auvloop::engine::fv
