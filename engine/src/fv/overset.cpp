// SPDX-License-Identifier: GPL-3.0-or-later
// The overset coupling's bookkeeping (overset.hpp): the cell lists, the face mask, the
// interpolation of a field into fringe cells and the interface flux per component.
#include "auvloop/engine/fv/overset.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace auvloop::engine::fv {

using mesher::CellStatus;

Overset::Overset(const Mesh& mesh, mesher::CompositeStencils stencils, std::vector<int> cell_offset)
    : mesh_(mesh), stencils_(std::move(stencils)), cell_offset_(std::move(cell_offset)) {
  const auto n = static_cast<std::size_t>(mesh.cells());
  const auto& s = stencils_;
  if (s.status.size() != n || s.offsets.size() != n + 1 ||
      s.donors.size() != static_cast<std::size_t>(s.offsets.back()) ||
      s.weights.size() != s.donors.size())
    throw std::invalid_argument(
        fmt::format("Overset: the stencils are for {} cells, the mesh has {}", s.status.size(), n));
  if (cell_offset_.empty() || cell_offset_.front() != 0 ||
      !std::is_sorted(cell_offset_.begin(), cell_offset_.end()) ||
      cell_offset_.back() >= mesh.cells())
    throw std::invalid_argument("Overset: component offsets must start at 0 and ascend");
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto cu = static_cast<std::size_t>(c);
    switch (s.status[cu]) {
      case CellStatus::active:
        active_cells_.push_back(c);
        active_volume_ += mesh.volume(c);
        break;
      case CellStatus::hole:
        fixed_.push_back(c);
        break;
      case CellStatus::orphan:
        throw std::invalid_argument(
            fmt::format("Overset: cell {} (component {}) is an orphan: a fringe cell without "
                        "donors",
                        c, component_of(c)));
      case CellStatus::fringe: {
        fixed_.push_back(c);
        fringe_.push_back(c);
        double sum = 0;
        for (int k = s.offsets[cu]; k < s.offsets[cu + 1]; ++k) {
          const int d = s.donors[static_cast<std::size_t>(k)];
          if (d < 0 || d >= mesh.cells() ||
              s.status[static_cast<std::size_t>(d)] != CellStatus::active)
            throw std::invalid_argument(fmt::format(
                "Overset: fringe cell {} has donor {} that is not an active cell", c, d));
          sum += s.weights[static_cast<std::size_t>(k)];
        }
        if (s.offsets[cu + 1] == s.offsets[cu] || std::abs(sum - 1) > 1e-9)
          throw std::invalid_argument(
              fmt::format("Overset: fringe cell {} has {} donors with weights summing to {}", c,
                          s.offsets[cu + 1] - s.offsets[cu], sum));
        break;
      }
    }
  }
  live_.assign(static_cast<std::size_t>(mesh.faces()), 0);
  for (int f = 0; f < mesh.faces(); ++f) {
    const bool own = active(mesh.owner(f));
    live_[static_cast<std::size_t>(f)] =
        own || (f < mesh.internal_faces() && active(mesh.neighbour(f))) ? 1 : 0;
  }
}

int Overset::component_of(int c) const {
  const auto it = std::upper_bound(cell_offset_.begin(), cell_offset_.end(), c);
  return static_cast<int>(it - cell_offset_.begin()) - 1;
}

double Overset::interpolate(std::span<const double> field, int c) const {
  const auto cu = static_cast<std::size_t>(c);
  double v = 0;
  for (int k = stencils_.offsets[cu]; k < stencils_.offsets[cu + 1]; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    v += stencils_.weights[ku] * field[static_cast<std::size_t>(stencils_.donors[ku])];
  }
  return v;
}

void Overset::fixed_values(std::span<const double> field, double hole,
                           std::vector<double>& out) const {
  out.resize(fixed_.size());
  for (std::size_t i = 0; i < fixed_.size(); ++i) {
    const int c = fixed_[i];
    if (status(c) == CellStatus::fringe) {
      out[i] = interpolate(field, c);
    } else {
      out[i] = std::isnan(hole) ? field[static_cast<std::size_t>(c)] : hole;
    }
  }
}

void Overset::apply(std::span<double> field, double hole) const {
  for (int c : fixed_) {
    if (status(c) == CellStatus::fringe) {
      field[static_cast<std::size_t>(c)] = interpolate(field, c);  // donors are active: unchanged
    } else if (!std::isnan(hole)) {
      field[static_cast<std::size_t>(c)] = hole;
    }
  }
}

std::vector<double> interface_flux(const Overset& overset, const Mesh& mesh,
                                   std::span<const double> phi) {
  std::vector<double> q(static_cast<std::size_t>(overset.components()), 0.0);
  for (int f = 0; f < mesh.internal_faces(); ++f) {
    const int P = mesh.owner(f), N = mesh.neighbour(f);
    const bool a = overset.active(P), b = overset.active(N);
    if (a == b) continue;
    const double out = a ? phi[static_cast<std::size_t>(f)] : -phi[static_cast<std::size_t>(f)];
    q[static_cast<std::size_t>(overset.component_of(a ? P : N))] += out;
  }
  return q;
}

}  // namespace auvloop::engine::fv
