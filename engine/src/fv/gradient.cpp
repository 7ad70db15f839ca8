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
}

void LeastSquaresGradient::compute(std::span<const double> phi, std::span<const double> boundary,
                                   std::span<Eigen::Vector3d> gradient) const {
  const int internal = grid_.internal_faces();
  parallel_for(grid_.cells, [&](int cell) {
    const auto P = static_cast<std::size_t>(cell);
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (int k = offsets_[P]; k < offsets_[P + 1]; ++k) {
      const int f = faces_[static_cast<std::size_t>(k)];
      const auto fs = static_cast<std::size_t>(f);
      Eigen::Vector3d d;
      double other;
      if (f < internal) {
        const bool own = grid_.owner[fs] == cell;
        const int n = own ? grid_.neighbour[fs] : grid_.owner[fs];
        d = own ? d_[fs] : Eigen::Vector3d(-d_[fs]);
        other = phi[static_cast<std::size_t>(n)];
      } else {
        d = d_[fs];
        other = boundary[fs - static_cast<std::size_t>(internal)];
      }
      rhs += d * (other - phi[P]) / d.squaredNorm();
    }
    gradient[P] = inverse_[P] * rhs;
  });
}

}  // namespace auvloop::engine::fv
