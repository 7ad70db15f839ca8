// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/gradient.hpp"

#include <stdexcept>

#include <Eigen/LU>

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
  const auto& c = geometry_.cell_centre;
  std::vector<Eigen::Vector3d> rhs(static_cast<std::size_t>(grid_.cells), Eigen::Vector3d::Zero());
  for (int f = 0; f < grid_.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const auto P = static_cast<std::size_t>(grid_.owner[fs]);
    if (f < grid_.internal_faces()) {
      const auto N = static_cast<std::size_t>(grid_.neighbour[fs]);
      const Eigen::Vector3d d = c[N] - c[P];
      const Eigen::Vector3d contribution = d * (phi[N] - phi[P]) / d.squaredNorm();
      rhs[P] += contribution;
      rhs[N] += contribution;  // (-d)(phi_P - phi_N) is the same vector
    } else {
      const Eigen::Vector3d d = geometry_.face_centre[fs] - c[P];
      rhs[P] += d * (boundary[fs - static_cast<std::size_t>(grid_.internal_faces())] - phi[P]) /
                d.squaredNorm();
    }
  }
  for (std::size_t i = 0; i < rhs.size(); ++i) gradient[i] = inverse_[i] * rhs[i];
}

}  // namespace auvloop::engine::fv
