// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/mesh.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "periodic.hpp"

namespace auvloop::engine::fv {

Mesh::Mesh(const mesher::Grid& source)
    : source_(source), grid_(&source), geo_(mesher::compute_geometry(source)) {
  if (auto coupled = couple_periodic(source, geo_)) {
    coupled_ = std::make_unique<mesher::Grid>(std::move(coupled->grid));
    geo_ = std::move(coupled->geometry);
    shift_ = std::move(coupled->shift);
    grid_ = coupled_.get();
  }
  const mesher::Grid& grid = *grid_;
  const auto nf = static_cast<std::size_t>(grid.faces());
  weight_.assign(nf, 1.0);
  alpha_.assign(nf, 0.0);
  d_.resize(nf);
  k_.resize(nf);
  skew_.assign(nf, Eigen::Vector3d::Zero());
  patch_of_.assign(nf - static_cast<std::size_t>(grid.internal_faces()), -1);
  for (int f = 0; f < faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const Eigen::Vector3d& S = area(f);
    const Eigen::Vector3d& xP = centre(owner(f));
    if (f < internal_faces()) {
      const Eigen::Vector3d xN = neighbour_centre(f);
      d_[fs] = xN - xP;
      const double dP = std::abs(S.dot(face_centre(f) - xP));
      const double dN = std::abs(S.dot(xN - face_centre(f)));
      weight_[fs] = dN / (dP + dN);
      skew_[fs] = face_centre(f) - (weight_[fs] * xP + (1 - weight_[fs]) * xN);
      skewed_ = skewed_ || skew_[fs].norm() > 1e-12 * d_[fs].norm();
    } else {
      d_[fs] = face_centre(f) - xP;
    }
    const double Sd = S.dot(d_[fs]);
    if (!(Sd > 0)) {
      throw std::runtime_error("fv::Mesh: face " + std::to_string(f) + " of grid '" + grid.name +
                               "' has its cell centres on the same side (S . d <= 0)");
    }
    alpha_[fs] = S.squaredNorm() / Sd;
    k_[fs] = S - alpha_[fs] * d_[fs];
    orthogonal_ = orthogonal_ && k_[fs].norm() <= 1e-12 * S.norm();
  }
  for (std::size_t p = 0; p < grid.patches.size(); ++p) {
    const auto& patch = grid.patches[p];
    for (int i = 0; i < patch.size; ++i)
      patch_of_[static_cast<std::size_t>(patch.start + i - internal_faces())] = static_cast<int>(p);
  }
  for (double v : geo_.cell_volume) total_volume_ += v;
  cell_face_offsets_.assign(static_cast<std::size_t>(cells()) + 1, 0);
  for (int f = 0; f < faces(); ++f) {
    ++cell_face_offsets_[static_cast<std::size_t>(owner(f)) + 1];
    if (f < internal_faces()) ++cell_face_offsets_[static_cast<std::size_t>(neighbour(f)) + 1];
  }
  for (std::size_t c = 0; c < static_cast<std::size_t>(cells()); ++c)
    cell_face_offsets_[c + 1] += cell_face_offsets_[c];
  cell_face_list_.resize(static_cast<std::size_t>(cell_face_offsets_.back()));
  std::vector<int> fill(cell_face_offsets_.begin(), cell_face_offsets_.end() - 1);
  for (int f = 0; f < faces(); ++f) {
    cell_face_list_[static_cast<std::size_t>(fill[static_cast<std::size_t>(owner(f))]++)] = f;
    if (f < internal_faces())
      cell_face_list_[static_cast<std::size_t>(fill[static_cast<std::size_t>(neighbour(f))]++)] = f;
  }
  gradient_ = std::make_unique<LeastSquaresGradient>(grid, geo_, d_);
  face_blocks_ = FaceBlocks(grid);
  for (int f = internal_faces(); f < faces(); ++f) boundary_cells_.push_back(owner(f));
  std::sort(boundary_cells_.begin(), boundary_cells_.end());
  boundary_cells_.erase(std::unique(boundary_cells_.begin(), boundary_cells_.end()),
                        boundary_cells_.end());
}

// A power of two of blocks (two threads share them evenly; three within a block), at most 16 and
// of at least 1024 cells each: few enough that the faces shared by two blocks (listed twice) stay
// a small share.
FaceBlocks::FaceBlocks(const mesher::Grid& grid) {
  const int n = grid.cells;
  int blocks = 1;
  while (2 * blocks <= std::min(16, n / 1024)) blocks *= 2;
  cell_start_.resize(static_cast<std::size_t>(blocks) + 1);
  for (int k = 0; k <= blocks; ++k)
    cell_start_[static_cast<std::size_t>(k)] =
        static_cast<int>(static_cast<long long>(n) * k / blocks);
  std::vector<int> block_of(static_cast<std::size_t>(n));
  for (int k = 0; k < blocks; ++k)
    for (int c = cell_begin(k); c < cell_end(k); ++c) block_of[static_cast<std::size_t>(c)] = k;
  std::vector<std::vector<int>> lists(static_cast<std::size_t>(blocks));
  for (int f = 0; f < grid.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const int bo = block_of[static_cast<std::size_t>(grid.owner[fs])];
    const int bn =
        f < grid.internal_faces() ? block_of[static_cast<std::size_t>(grid.neighbour[fs])] : -1;
    if (bo == bn) {
      lists[static_cast<std::size_t>(bo)].push_back(f << 2 | kOwner | kNeighbour);
      continue;
    }
    lists[static_cast<std::size_t>(bo)].push_back(f << 2 | kOwner);
    if (bn >= 0) lists[static_cast<std::size_t>(bn)].push_back(f << 2 | kNeighbour);
  }
  face_start_.assign(1, 0);
  for (const auto& l : lists) {
    tagged_.insert(tagged_.end(), l.begin(), l.end());
    face_start_.push_back(static_cast<int>(tagged_.size()));
  }
}

Eigen::Vector3d Mesh::gradient_at(int cell, std::span<const double> cells,
                                  std::span<const double> boundary) const {
  return gradient_->at(cell, cells, boundary);
}

void Mesh::gradient(std::span<const double> cells, std::span<const double> boundary,
                    std::span<Eigen::Vector3d> out) const {
  const auto t0 = std::chrono::steady_clock::now();
  gradient_->compute(cells, boundary, out);
  gradient_seconds_.fetch_add(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
      std::memory_order_relaxed);
}

}  // namespace auvloop::engine::fv
