// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/gradient.hpp"

#include <stdexcept>

#include <Eigen/LU>

#include "parallel.hpp"

namespace auvloop::engine::fv {

LeastSquaresGradient::LeastSquaresGradient(const mesher::Grid& grid,
                                           const mesher::GridGeometry& geometry)
    : grid_(grid),
      geometry_(geometry),
      inverse_(static_cast<std::size_t>(grid.cells), Eigen::Matrix3d::Zero()) {
  const auto& c = geometry.cell_centre;
  auto add = [&](int cell, const Eigen::Vector3d& d) {
    inverse_[static_cast<std::size_t>(cell)] += d * d.transpose() / d.squaredNorm();
  };
  for (int f = 0; f < grid.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const int P = grid.owner[fs];
    if (f < grid.internal_faces()) {
      const int N = grid.neighbour[fs];
      const Eigen::Vector3d d = c[static_cast<std::size_t>(N)] - c[static_cast<std::size_t>(P)];
      add(P, d);
      add(N, -d);
    } else {
      add(P, geometry.face_centre[fs] - c[static_cast<std::size_t>(P)]);
    }
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
      const auto fs = static_cast<std::size_t>(faces_[ks]);
      Eigen::Vector3d d;
      if (faces_[ks] < grid.internal_faces()) {
        const int n = grid.owner[fs] == cell ? grid.neighbour[fs] : grid.owner[fs];
        d = c[static_cast<std::size_t>(n)] - c[P];
        other_[ks] = n;
      } else {
        d = geometry.face_centre[fs] - c[P];
        other_[ks] = -1 - (faces_[ks] - grid.internal_faces());
      }
      weights_[ks] = inverse_[P] * d / d.squaredNorm();
    }
  }
}

void LeastSquaresGradient::compute(std::span<const double> phi, std::span<const double> boundary,
                                   std::span<Eigen::Vector3d> gradient) const {
  parallel_for(grid_.cells, [&](int cell) {
    const auto P = static_cast<std::size_t>(cell);
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (int k = offsets_[P]; k < offsets_[P + 1]; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      const int o = other_[ks];
      const double other =
          o >= 0 ? phi[static_cast<std::size_t>(o)] : boundary[static_cast<std::size_t>(-1 - o)];
      g += weights_[ks] * (other - phi[P]);
    }
    gradient[P] = g;
  });
}

}  // namespace auvloop::engine::fv
