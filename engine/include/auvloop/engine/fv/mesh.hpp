// SPDX-License-Identifier: GPL-3.0-or-later
// The finite-volume view of a mesher::Grid: its geometry plus the per-face factors every operator
// needs, computed once per grid (docs/cfd.md, "Discretisation").
//
// Per face f with owner P (and neighbour N for internal faces):
//   d      = x_N - x_P (internal) or x_f - x_P (boundary)
//   weight = owner weight of linear interpolation, phi_f = w phi_P + (1 - w) phi_N, from the
//            distances of the two centres to the face plane (exactly 1/2 on uniform grids)
//   alpha  = |S|^2 / (S . d): the implicit part of the face-normal gradient, over-relaxed:
//            grad(phi)_f . S = alpha (phi_N - phi_P) + k . grad(phi)_f with k = S - alpha d
//   k      = the non-orthogonal correction vector (zero on orthogonal faces), treated explicitly.
//   skew   = x_f - x_f' (internal faces), x_f' = w x_P + (1 - w) x_N the point where the line
//            between the centres crosses the face plane: linear interpolation is second order
//            at x_f', so at the face centre it needs phi_f = w phi_P + (1 - w) phi_N
//            + grad(phi)_f . skew (Ferziger and Peric, section 8.6). Without it the error is
//            O(|skew|), first order wherever |skew| / |d| does not shrink under refinement
//            (kinked grid lines, e.g. the corners of an O-grid). Zero on boundary faces.
// Boundary faces are numbered by their position after the internal faces (b = f - internal).
//
// Periodic patches (translational) are coupled: each matched pair of faces becomes one internal
// face whose neighbour centre is the neighbour cell's image across the translation
// (neighbour_centre), so every operator treats it like any other internal face. grid() is then a
// copy with the pairs among the internal faces and the periodic patches empty; source_grid() is
// the grid as given (same cells, for output).
#pragma once

#include <atomic>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "auvloop/engine/fv/gradient.hpp"
#include "auvloop/mesher/grid.hpp"

namespace auvloop::engine::fv {

// The faces grouped by blocks of consecutive cells, for parallel scatters of face terms into
// cells (engine/src/fv/parallel.hpp, scatter_faces). Block k holds cells [cell_begin(k),
// cell_end(k)); its list holds, in ascending face order, every face whose owner or neighbour lies
// in the block, as (f << 2) | kOwner if the owner does | kNeighbour if the neighbour does. A face
// between two blocks is in both lists. The blocking does not change any result (each cell's
// contributions are summed in ascending face order either way); it only spreads the work.
class FaceBlocks {
 public:
  static constexpr int kOwner = 1, kNeighbour = 2;
  FaceBlocks() = default;
  explicit FaceBlocks(const mesher::Grid& grid);
  [[nodiscard]] int blocks() const { return static_cast<int>(cell_start_.size()) - 1; }
  [[nodiscard]] int cell_begin(int k) const { return cell_start_[static_cast<std::size_t>(k)]; }
  [[nodiscard]] int cell_end(int k) const { return cell_start_[static_cast<std::size_t>(k) + 1]; }
  [[nodiscard]] std::span<const int> faces(int k) const {
    const auto b = static_cast<std::size_t>(face_start_[static_cast<std::size_t>(k)]);
    const auto e = static_cast<std::size_t>(face_start_[static_cast<std::size_t>(k) + 1]);
    return std::span<const int>(tagged_).subspan(b, e - b);
  }

 private:
  std::vector<int> cell_start_, face_start_, tagged_;
};

class Mesh {
 public:
  explicit Mesh(const mesher::Grid& grid);
  Mesh(const Mesh&) = delete;  // the gradient holds references into the mesh
  Mesh& operator=(const Mesh&) = delete;

  // The addressing the operators use (periodic pairs coupled).
  const mesher::Grid& grid() const { return *grid_; }
  // The grid as given (periodic faces still boundary faces): the cells are the same.
  const mesher::Grid& source_grid() const { return source_; }
  [[nodiscard]] bool periodic() const { return coupled_ != nullptr; }
  const mesher::GridGeometry& geometry() const { return geo_; }
  int cells() const { return grid_->cells; }
  int faces() const { return grid_->faces(); }
  int internal_faces() const { return grid_->internal_faces(); }
  int boundary_faces() const { return faces() - internal_faces(); }
  int owner(int f) const { return grid_->owner[static_cast<std::size_t>(f)]; }
  int neighbour(int f) const { return grid_->neighbour[static_cast<std::size_t>(f)]; }
  const Eigen::Vector3d& area(int f) const { return geo_.face_area[static_cast<std::size_t>(f)]; }
  const Eigen::Vector3d& face_centre(int f) const {
    return geo_.face_centre[static_cast<std::size_t>(f)];
  }
  const Eigen::Vector3d& centre(int c) const {
    return geo_.cell_centre[static_cast<std::size_t>(c)];
  }
  // Centre of the neighbour of internal face f as seen from its owner: the cell centre, or for a
  // periodic face its image across the translation.
  Eigen::Vector3d neighbour_centre(int f) const {
    const Eigen::Vector3d& x = centre(neighbour(f));
    return shift_.empty() ? x : Eigen::Vector3d(x + shift_[static_cast<std::size_t>(f)]);
  }
  double volume(int c) const { return geo_.cell_volume[static_cast<std::size_t>(c)]; }
  double weight(int f) const { return weight_[static_cast<std::size_t>(f)]; }
  double alpha(int f) const { return alpha_[static_cast<std::size_t>(f)]; }
  const Eigen::Vector3d& d(int f) const { return d_[static_cast<std::size_t>(f)]; }
  const Eigen::Vector3d& k(int f) const { return k_[static_cast<std::size_t>(f)]; }
  const Eigen::Vector3d& skew(int f) const { return skew_[static_cast<std::size_t>(f)]; }
  // Whether any face has a skewness |skew| / |d| above 1e-12 (false: skewness corrections,
  // and the gradients they need, can be skipped).
  bool skewed() const { return skewed_; }
  // Patch index of boundary face b (b = f - internal_faces()).
  int patch_of(int b) const { return patch_of_[static_cast<std::size_t>(b)]; }
  double total_volume() const { return total_volume_; }
  // The faces of cell c in a fixed order (ascending face index): per-cell gathers in this order
  // make face sums independent of the number of threads.
  std::span<const int> cell_faces(int c) const {
    const auto b = static_cast<std::size_t>(cell_face_offsets_[static_cast<std::size_t>(c)]);
    const auto e = static_cast<std::size_t>(cell_face_offsets_[static_cast<std::size_t>(c) + 1]);
    return std::span<const int>(cell_face_list_).subspan(b, e - b);
  }
  const FaceBlocks& face_blocks() const { return face_blocks_; }
  // The cells with at least one boundary face (periodic pairs coupled: not those), ascending.
  std::span<const int> boundary_cells() const { return boundary_cells_; }
  // Whether every face is orthogonal (|k| <= 1e-12 |S|): the non-orthogonal corrections, and the
  // gradients they need, are then skipped.
  bool orthogonal() const { return orthogonal_; }
  // Least-squares cell gradient of cell values with their boundary-face values.
  void gradient(std::span<const double> cells, std::span<const double> boundary,
                std::span<Eigen::Vector3d> out) const;
  // The same for one cell (the same bits as its entry of gradient()).
  [[nodiscard]] Eigen::Vector3d gradient_at(int cell, std::span<const double> cells,
                                            std::span<const double> boundary) const;
  // Wall-clock seconds spent in gradient() so far (profiling: the solver's phase split).
  [[nodiscard]] double gradient_seconds() const {
    return gradient_seconds_.load(std::memory_order_relaxed);
  }

 private:
  const mesher::Grid& source_;
  std::unique_ptr<mesher::Grid> coupled_;  // periodic grids only
  const mesher::Grid* grid_;               // coupled_ or source_
  mesher::GridGeometry geo_;
  std::vector<Eigen::Vector3d> shift_;  // per internal face (periodic grids only)
  std::vector<double> weight_, alpha_;
  std::vector<Eigen::Vector3d> d_, k_, skew_;
  std::vector<int> patch_of_;
  std::vector<int> cell_face_offsets_, cell_face_list_;
  FaceBlocks face_blocks_;
  std::vector<int> boundary_cells_;
  double total_volume_ = 0;
  bool skewed_ = false, orthogonal_ = true;
  std::unique_ptr<LeastSquaresGradient> gradient_;
  mutable std::atomic<double> gradient_seconds_{0.0};
};

}  // namespace auvloop::engine::fv
