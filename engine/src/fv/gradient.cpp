// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/gradient.hpp"

#include <stdexcept>

#include <Eigen/LU>

#include "parallel.hpp"

namespace auvloop::engine::fv {

namespace {
std::vector<Eigen::Vector3d> face_vectors(const mesher::Grid& grid,
                                          const mesher::GridGeometry& geometry) {
  std::vector<Eigen::Vector3d> d(static_cast<std::size_t>(grid.faces()));
  for (std::size_t f = 0; f < d.size(); ++f) {
    const auto P = static_cast<std::size_t>(grid.owner[f]);
    d[f] = f < static_cast<std::size_t>(grid.internal_faces())
               ? Eigen::Vector3d(geometry.cell_centre[static_cast<std::size_t>(grid.neighbour[f])] -
                                 geometry.cell_centre[P])
               : Eigen::Vector3d(geometry.face_centre[f] - geometry.cell_centre[P]);
  }
  return d;
}
}  // namespace

LeastSquaresGradient::LeastSquaresGradient(const mesher::Grid& grid,
                                           const mesher::GridGeometry& geometry)
    : LeastSquaresGradient(grid, geometry, face_vectors(grid, geometry)) {}

LeastSquaresGradient::LeastSquaresGradient(const mesher::Grid& grid,
                                           const mesher::GridGeometry& /*geometry*/,
                                           std::span<const Eigen::Vector3d> d)
    : grid_(grid),
      d_(d.begin(), d.end()),
      inverse_(static_cast<std::size_t>(grid.cells), Eigen::Matrix3d::Zero()) {
  auto add = [&](int cell, const Eigen::Vector3d& dk) {
    inverse_[static_cast<std::size_t>(cell)] += dk * dk.transpose() / dk.squaredNorm();
  };
  for (int f = 0; f < grid.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    add(grid.owner[fs], d_[fs]);
    if (f < grid.internal_faces()) add(grid.neighbour[fs], -d_[fs]);
  }
  offsets_.assign(static_cast<std::size_t>(grid.cells) + 1, 0);
  for (int f = 0; f < grid.faces(); ++f) {
    ++offsets_[static_cast<std::size_t>(grid.owner[static_cast<std::size_t>(f)]) + 1];
    if (f < grid.internal_faces())
      ++offsets_[static_cast<std::size_t>(grid.neighbour[static_cast<std::size_t>(f)]) + 1];
  }
  for (std::size_t i = 0; i < static_cast<std::size_t>(grid.cells); ++i)
    offsets_[i + 1] += offsets_[i];
  faces_.resize(static_cast<std::size_t>(offsets_.back()));
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (int f = 0; f < grid.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    faces_[static_cast<std::size_t>(fill[static_cast<std::size_t>(grid.owner[fs])]++)] = f;
    if (f < grid.internal_faces())
      faces_[static_cast<std::size_t>(fill[static_cast<std::size_t>(grid.neighbour[fs])]++)] = f;
  }
  for (std::size_t i = 0; i < inverse_.size(); ++i) {
    Eigen::FullPivLU<Eigen::Matrix3d> lu(inverse_[i]);
    if (!lu.isInvertible()) {
      throw std::runtime_error("least-squares gradient: the neighbours of cell " +
                               std::to_string(i) + " do not span three dimensions");
    }
    inverse_[i] = lu.inverse();
  }
  weights_.resize(faces_.size());
  other_.resize(faces_.size());
  for (int cell = 0; cell < grid.cells; ++cell) {
    const auto P = static_cast<std::size_t>(cell);
    for (int k = offsets_[P]; k < offsets_[P + 1]; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      const int f = faces_[ks];
      const auto fs = static_cast<std::size_t>(f);
      Eigen::Vector3d dk = d_[fs];
      if (f < grid.internal_faces()) {
        const bool own = grid.owner[fs] == cell;
        other_[ks] = own ? grid.neighbour[fs] : grid.owner[fs];
        if (!own) dk = -dk;
      } else {
        other_[ks] = -1 - (f - grid.internal_faces());
      }
      weights_[ks] = inverse_[P] * dk / dk.squaredNorm();
    }
  }
}

void LeastSquaresGradient::compute(std::span<const double> phi, std::span<const double> boundary,
                                   std::span<Eigen::Vector3d> gradient) const {
  parallel_for(grid_.cells, [&](int cell) {
    gradient[static_cast<std::size_t>(cell)] = at(cell, phi, boundary);
  });
}

Eigen::Vector3d LeastSquaresGradient::at(int cell, std::span<const double> phi,
                                         std::span<const double> boundary) const {
  const auto P = static_cast<std::size_t>(cell);
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (int k = offsets_[P]; k < offsets_[P + 1]; ++k) {
    const auto ks = static_cast<std::size_t>(k);
    const int o = other_[ks];
    const double other =
        o >= 0 ? phi[static_cast<std::size_t>(o)] : boundary[static_cast<std::size_t>(-1 - o)];
    g += weights_[ks] * (other - phi[P]);
  }
  return g;
}

}  // namespace auvloop::engine::fv
