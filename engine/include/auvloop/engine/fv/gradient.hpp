// SPDX-License-Identifier: GPL-3.0-or-later
// Cell-centred gradients on a mesher::Grid.
//
// Weighted least squares: for cell P, minimise sum_k w_k (phi_k - phi_P - g . d_k)^2 over the
// face neighbours k (d_k = x_k - x_P, w_k = 1 / |d_k|^2), boundary faces contributing their face
// value at their face centre. The 3 x 3 normal matrices depend on the grid only and are inverted
// once. Exact for linear fields on any grid, which Green-Gauss with linear face interpolation is
// not on skewed cells. compute() runs in parallel over cells (oneTBB) with thread-count
// independent results.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::engine::fv {

class LeastSquaresGradient {
 public:
  LeastSquaresGradient(const mesher::Grid& grid, const mesher::GridGeometry& geometry);
  // With the face vectors d given per face (internal: neighbour centre - owner centre, which for
  // a periodic face is the neighbour's image; boundary: face centre - owner centre).
  LeastSquaresGradient(const mesher::Grid& grid, const mesher::GridGeometry& geometry,
                       std::span<const Eigen::Vector3d> d);

  // phi: one value per cell; boundary: one value per boundary face (face index - internal faces).
  void compute(std::span<const double> phi, std::span<const double> boundary,
               std::span<Eigen::Vector3d> gradient) const;
  // The same for one cell (the same sums in the same order: the same bits as compute()).
  [[nodiscard]] Eigen::Vector3d at(int cell, std::span<const double> phi,
                                   std::span<const double> boundary) const;

 private:
  const mesher::Grid& grid_;
  std::vector<Eigen::Vector3d> d_;        // per face, as in the constructor
  std::vector<Eigen::Matrix3d> inverse_;  // per cell
  // Faces of each cell (CSR, ascending face index): the per-cell gather in compute() sums in
  // this fixed order, in parallel, so the result does not depend on the number of threads.
  std::vector<int> offsets_, faces_;
  // Per entry of faces_: the weight vector inverse_P d_k / |d_k|^2 (precomputed, so compute() is
  // a weighted sum of differences) and the other value's index: a cell (>= 0) or boundary face b
  // encoded as -1 - b.
  std::vector<Eigen::Vector3d> weights_;
  std::vector<int> other_;
};

}  // namespace auvloop::engine::fv
