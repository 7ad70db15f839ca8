// SPDX-License-Identifier: GPL-3.0-or-later
#include "diagnosis.hpp"

#include <cmath>
#include <vector>

#include <fmt/format.h>

namespace auvloop::engine::fv {

std::string cell_at(const Mesh& mesh, int cell) {
  const auto& x = mesh.centre(cell);
  return fmt::format("cell {} at ({:.4g}, {:.4g}, {:.4g}) m", cell, x.x(), x.y(), x.z());
}

std::string largest_residual_at(const Mesh& mesh, const Matrix& m, std::span<const double> x) {
  std::vector<double> ax(x.size());
  m.multiply(mesh, x, ax);
  int worst = 0;
  double largest = -1;
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto s = static_cast<std::size_t>(c);
    const double r = std::abs(m.source[s] - ax[s]) / mesh.volume(c);
    if (!std::isfinite(r)) return cell_at(mesh, c);  // the first non-finite one is the worst
    if (r > largest) {
      largest = r;
      worst = c;
    }
  }
  return cell_at(mesh, worst);
}

}  // namespace auvloop::engine::fv
