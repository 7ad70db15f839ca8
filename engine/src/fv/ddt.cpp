// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::ddt: backward differences on a fixed time step (BDF2, or Euler to start).
#include "auvloop/engine/fv/operators.hpp"

namespace auvloop::engine::fv {

Matrix ddt(const Mesh& mesh, const TimeScheme& ts, std::span<const double> old,
           std::span<const double> oldold) {
  Matrix m(mesh);
  const auto c = ts.coeffs();
  for (int i = 0; i < mesh.cells(); ++i) {
    const auto s = static_cast<std::size_t>(i);
    const double vdt = mesh.volume(i) / ts.dt;
    m.diag[s] = c[0] * vdt;
    m.source[s] = -vdt * (c[1] * old[s] + (c[2] != 0.0 ? c[2] * oldold[s] : 0.0));
  }
  return m;
}

}  // namespace auvloop::engine::fv
