// SPDX-License-Identifier: GPL-3.0-or-later
// The overset coupling's bookkeeping (overset.hpp): the cell lists, the face mask, the
// interpolation of a field into fringe cells and the interface flux per component.
#include "auvloop/engine/fv/overset.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "parallel.hpp"

namespace auvloop::engine::fv {

using mesher::CellStatus;

Overset::Overset(const Mesh& mesh, mesher::CompositeStencils stencils, std::vector<int> cell_offset)
    : mesh_(mesh), cell_offset_(std::move(cell_offset)) {
  if (cell_offset_.empty() || cell_offset_.front() != 0 ||
      !std::is_sorted(cell_offset_.begin(), cell_offset_.end()) ||
      cell_offset_.back() >= mesh.cells())
    throw std::invalid_argument("Overset: component offsets must start at 0 and ascend");
  assign(std::move(stencils));
  set_orientation(std::vector<Eigen::Matrix3d>(cell_offset_.size(), Eigen::Matrix3d::Identity()));
}

void Overset::update(mesher::CompositeStencils stencils) {
  assign(std::move(stencils));
}

void Overset::assign(mesher::CompositeStencils stencils) {
  const auto& mesh = mesh_;
  const auto n = static_cast<std::size_t>(mesh.cells());
  const auto& s = stencils;
  if (s.status.size() != n || s.offsets.size() != n + 1 ||
      s.donors.size() != static_cast<std::size_t>(s.offsets.back()) ||
      s.weights.size() != s.donors.size())
    throw std::invalid_argument(
        fmt::format("Overset: the stencils are for {} cells, the mesh has {}", s.status.size(), n));
  std::vector<int> fixed, fringe, active_cells;
  double active_volume = 0;
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto cu = static_cast<std::size_t>(c);
    switch (s.status[cu]) {
      case CellStatus::active:
        active_cells.push_back(c);
        active_volume += mesh.volume(c);
        break;
      case CellStatus::hole:
        fixed.push_back(c);
        break;
      case CellStatus::orphan:
        throw std::invalid_argument(
            fmt::format("Overset: cell {} (component {}) is an orphan: a fringe cell without "
                        "donors",
                        c, component_of(c)));
      case CellStatus::fringe: {
        fixed.push_back(c);
        fringe.push_back(c);
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
  stencils_ = std::move(stencils);
  donor_component_.resize(stencils_.donors.size());
  for (std::size_t k = 0; k < donor_component_.size(); ++k)
    donor_component_[k] = component_of(stencils_.donors[k]);
  fixed_ = std::move(fixed);
  fringe_ = std::move(fringe);
  active_cells_ = std::move(active_cells);
  active_volume_ = active_volume;
  live_.assign(static_cast<std::size_t>(mesh.faces()), 0);
  for (int f = 0; f < mesh.faces(); ++f) {
    const bool own = active(mesh.owner(f));
    live_[static_cast<std::size_t>(f)] =
        own || (f < mesh.internal_faces() && active(mesh.neighbour(f))) ? 1 : 0;
  }
  list_coupled_rows();
  ++generation_;
}

void Overset::set_orientation(std::vector<Eigen::Matrix3d> orientation) {
  const auto K = cell_offset_.size();
  if (orientation.size() != K)
    throw std::invalid_argument(
        fmt::format("Overset::set_orientation: {} orientations for {} "
                    "components",
                    orientation.size(), K));
  for (std::size_t k = 0; k < K; ++k) {
    const auto& R = orientation[k];
    if (!R.allFinite() || !(R.transpose() * R).isIdentity(1e-12) || !(R.determinant() > 0))
      throw std::invalid_argument(
          fmt::format("Overset::set_orientation: component {}'s orientation is not a rotation", k));
  }
  orientation_ = std::move(orientation);
  rotation_.resize(K * K);
  turned_ = false;
  for (std::size_t h = 0; h < K; ++h)
    for (std::size_t g = 0; g < K; ++g) {
      rotation_[h * K + g] = orientation_[h].transpose() * orientation_[g];
      turned_ = turned_ || orientation_[h] != orientation_[g];
    }
}

int Overset::component_of(int c) const {
  const auto it = std::upper_bound(cell_offset_.begin(), cell_offset_.end(), c);
  return static_cast<int>(it - cell_offset_.begin()) - 1;
}

double Overset::interpolate(std::span<const double> field, int c, Bound bound) const {
  const auto cu = static_cast<std::size_t>(c);
  double v = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int k = stencils_.offsets[cu]; k < stencils_.offsets[cu + 1]; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const double d = field[static_cast<std::size_t>(stencils_.donors[ku])];
    v += stencils_.weights[ku] * d;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return bound == Bound::donors ? std::clamp(v, lo, hi) : v;
}

Eigen::Vector3d Overset::interpolate(const Vector& u, int c) const {
  const auto cu = static_cast<std::size_t>(c);
  const int h = component_of(c);
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int k = stencils_.offsets[cu]; k < stencils_.offsets[cu + 1]; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const auto du = static_cast<std::size_t>(stencils_.donors[ku]);
    const Eigen::Vector3d ud(u[0][du], u[1][du], u[2][du]);
    const int g = donor_component_[ku];
    v += stencils_.weights[ku] * (g == h ? ud : Eigen::Vector3d(rotation(h, g) * ud));
  }
  return v;
}

Eigen::Matrix3d Overset::interpolate_gradient(const Vector& u, const Vector& boundary,
                                              int c) const {
  const auto cu = static_cast<std::size_t>(c);
  const int h = component_of(c);
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  for (int k = stencils_.offsets[cu]; k < stencils_.offsets[cu + 1]; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const int d = stencils_.donors[ku];
    Eigen::Matrix3d Gd;
    for (std::size_t i = 0; i < 3; ++i)
      Gd.row(static_cast<Eigen::Index>(i)) = mesh_.gradient_at(d, u[i], boundary[i]).transpose();
    const int g = donor_component_[ku];
    if (g != h) {
      const Eigen::Matrix3d& R = rotation(h, g);
      Gd = R * Gd * R.transpose();
    }
    G += stencils_.weights[ku] * Gd;
  }
  return G;
}

double Overset::interpolate(const Vector& u, int c, std::size_t i) const {
  const auto cu = static_cast<std::size_t>(c);
  const int h = component_of(c);
  const auto e = static_cast<Eigen::Index>(i);
  double v = 0;
  for (int k = stencils_.offsets[cu]; k < stencils_.offsets[cu + 1]; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const auto du = static_cast<std::size_t>(stencils_.donors[ku]);
    const int g = donor_component_[ku];
    // (row i of R_hg) . u_d: the sums in the order of interpolate(u, c)'s, so the same bits
    const double ui = g == h ? u[i][du]
                             : (rotation(h, g)(e, 0) * u[0][du] + rotation(h, g)(e, 1) * u[1][du]) +
                                   rotation(h, g)(e, 2) * u[2][du];
    v += stencils_.weights[ku] * ui;
  }
  return v;
}

void Overset::fixed_values(const Vector& u, std::size_t i, std::vector<double>& out) const {
  if (!turned_) {
    fixed_values(u[i], std::numeric_limits<double>::quiet_NaN(), out);
    return;
  }
  out.resize(fixed_.size());
  parallel_for(static_cast<int>(fixed_.size()), [&](int j) {
    const int c = fixed_[static_cast<std::size_t>(j)];
    out[static_cast<std::size_t>(j)] =
        status(c) == CellStatus::fringe ? interpolate(u, c, i) : u[i][static_cast<std::size_t>(c)];
  });
}

void Overset::apply(const std::array<std::span<double>, 3>& u) const {
  if (!turned_) {
    for (const auto& ui : u) apply(ui, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  // The donors are active, so writing the fringe cells after all are interpolated is the same
  // as in place; kept apart for clarity.
  const Vector in{u[0], u[1], u[2]};
  const int m = static_cast<int>(fringe_.size());
  scratch_.resize(fringe_.size());
  parallel_for(m, [&](int j) {
    const int c = fringe_[static_cast<std::size_t>(j)];  // as fixed_values(u, i): the same bits
    scratch_[static_cast<std::size_t>(j)] =
        Eigen::Vector3d(interpolate(in, c, 0), interpolate(in, c, 1), interpolate(in, c, 2));
  });
  parallel_for(m, [&](int j) {
    const auto ju = static_cast<std::size_t>(j);
    for (std::size_t i = 0; i < 3; ++i)
      u[i][static_cast<std::size_t>(fringe_[ju])] = scratch_[ju][static_cast<Eigen::Index>(i)];
  });
}

void Overset::fixed_values(std::span<const double> field, double hole, std::vector<double>& out,
                           Bound bound) const {
  out.resize(fixed_.size());
  parallel_for(static_cast<int>(fixed_.size()), [&](int j) {
    const auto i = static_cast<std::size_t>(j);
    const int c = fixed_[i];
    if (status(c) == CellStatus::fringe) {
      out[i] = interpolate(field, c, bound);
    } else {
      out[i] = std::isnan(hole) ? field[static_cast<std::size_t>(c)] : hole;
    }
  });
}

void Overset::apply(std::span<double> field, double hole, Bound bound) const {
  // In place: a fringe cell reads only active donors, which no iteration writes.
  parallel_for(static_cast<int>(fixed_.size()), [&](int j) {
    const int c = fixed_[static_cast<std::size_t>(j)];
    if (status(c) == CellStatus::fringe) {
      field[static_cast<std::size_t>(c)] = interpolate(field, c, bound);
    } else if (!std::isnan(hole)) {
      field[static_cast<std::size_t>(c)] = hole;
    }
  });
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
