// SPDX-License-Identifier: GPL-3.0-or-later
// A square sparse matrix by rows with a fixed partition of its rows into blocks, and the kernels
// every iterative solver is made of, private to engine/src: products, residual norms and the
// hybrid Gauss-Seidel smoother, all parallel (oneTBB) and bitwise independent of the thread count.
//
// Layout: diag[i], then the off-diagonal entries of row i at [row_start[i], row_start[i + 1]):
// those whose column lies in the row's own block first (up to split[i]), by ascending column
// (below the row up to mid[i]), then those in other blocks. Blocks are contiguous row ranges of
// equal size, a power of two of them (at most 16, each of at least 512 rows), so the partition
// depends on the number of rows only.
//
// Hybrid Gauss-Seidel (sweep): inside a block a Gauss-Seidel sweep, between blocks a Jacobi step
// (Henson and Yang's hybrid smoother of BoomerAMG). One sweep:
//   1. e_i = sum_{j in other blocks} a_ij x_j  for the rows with such entries, from x before the
//   sweep;
//   2. in every block at once, rows in ascending (forward) or descending (backward) order:
//        x_i = (b_i - e_i - sum_{j in the block} a_ij x_j) / a_ii
//      with the x_j of the block as far as the sweep has updated them.
// With one block it is plain Gauss-Seidel. The blocks are fixed, so the result is the same for any
// number of threads; the Jacobi coupling touches only the entries between blocks (a few percent on
// a grid numbered by planes).
#pragma once

#include <array>
#include <span>
#include <vector>

namespace auvloop::engine::fv {

class BlockCsr {
 public:
  // Blocks: a power of two (so that two threads share them evenly), at most 16, of at least 512
  // rows each.
  static constexpr int kMaxBlocks = 16;
  static constexpr int kMinBlockRows = 512;

  BlockCsr() = default;
  // The pattern: n rows, row i's off-diagonal columns at columns[row_start[i] .. row_start[i+1])
  // (no diagonal, no duplicates). Entries are reordered within each row (own block first, order
  // kept otherwise); permutation()[k] is the input position of entry k.
  BlockCsr(int n, std::span<const int> row_start, std::span<const int> columns);

  [[nodiscard]] int rows() const { return n_; }
  [[nodiscard]] int entries() const { return static_cast<int>(column_.size()); }
  [[nodiscard]] int blocks() const { return static_cast<int>(block_start_.size()) - 1; }
  [[nodiscard]] int block_begin(int k) const { return block_start_[static_cast<std::size_t>(k)]; }
  [[nodiscard]] int block_end(int k) const { return block_start_[static_cast<std::size_t>(k) + 1]; }
  [[nodiscard]] int row_begin(int i) const { return row_start_[static_cast<std::size_t>(i)]; }
  [[nodiscard]] int row_end(int i) const { return row_start_[static_cast<std::size_t>(i) + 1]; }
  [[nodiscard]] int column(int k) const { return column_[static_cast<std::size_t>(k)]; }
  [[nodiscard]] std::span<const int> permutation() const { return permutation_; }

  // Coefficients (sized by the constructor): diag per row, value per entry. Call
  // coefficients_changed() after writing them (it refreshes the inverse diagonal, and the
  // single-precision copy when one is kept).
  std::vector<double> diag, value;
  void coefficients_changed();
  [[nodiscard]] const std::vector<double>& inverse_diag() const { return inv_diag_; }

  // Keeps a single-precision copy of the coefficients for the kernels called with Single = true:
  // a preconditioner (the multigrid hierarchy) reads 8 instead of 12 bytes per entry, and the
  // arithmetic stays in double (x, b and every sum). Deterministic as the rest.
  void keep_single();
  [[nodiscard]] bool keeps_single() const { return single_; }

  // y = A x.
  void multiply(std::span<const double> x, std::span<double> y) const;
  // y = A x and returns x . y (one pass).
  template <bool Single = false>
  double multiply_dot(std::span<const double> x, std::span<double> y) const;
  // sum_j a_ij x_j over the off-diagonal entries of row i.
  template <bool Single = false>
  [[nodiscard]] double off_diagonal(int i, std::span<const double> x) const {
    double s = 0;
    for (int k = row_begin(i); k < row_end(i); ++k)
      s += coefficient<Single>(k) * x[static_cast<std::size_t>(column(k))];
    return s;
  }
  // b_i - (A x)_i.
  template <bool Single = false>
  [[nodiscard]] double row_residual(int i, std::span<const double> b,
                                    std::span<const double> x) const {
    const auto s = static_cast<std::size_t>(i);
    const double d = Single ? static_cast<double>(diag_single_[s]) : diag[s];
    return b[s] - d * x[s] - off_diagonal<Single>(i, x);
  }

  // r = b - A x and the norms of a linear solve's start (one pass): sum |r|, sum r^2, sum b^2 and
  // OpenFOAM's normalisation sum (|A x - A xbar| + |b - A xbar|) with xbar the mean of x.
  struct Residual {
    double l1 = 0, l2_squared = 0, b_squared = 0, normalisation = 0;
  };
  Residual residual(std::span<const double> b, std::span<const double> x,
                    std::span<double> r) const;

  // One hybrid Gauss-Seidel sweep on A x = b (above). `zero_x`: the sweep starts from x = 0
  // whatever x holds on entry (the inter-block and not-yet-updated terms vanish, x is only
  // written before it is read). `scratch`: n values.
  template <bool Single = false>
  void sweep(std::span<const double> b, std::span<double> x, bool backward, bool zero_x,
             std::span<double> scratch) const;

 private:
  template <bool Single>
  [[nodiscard]] double coefficient(int k) const {
    if constexpr (Single) {
      return static_cast<double>(value_single_[static_cast<std::size_t>(k)]);
    } else {
      return value[static_cast<std::size_t>(k)];
    }
  }
  int n_ = 0;
  std::vector<int> row_start_, mid_, split_, column_, permutation_, block_start_;
  std::vector<double> inv_diag_;
  bool single_ = false;
  std::vector<float> value_single_, diag_single_, inv_diag_single_;
};

// Deterministic parallel vector kernels (fixed-block sums, parallel.hpp).
double dot(std::span<const double> a, std::span<const double> b);
std::array<double, 2> dot2(std::span<const double> a, std::span<const double> b,
                           std::span<const double> c);  // {a . b, a . c}

}  // namespace auvloop::engine::fv
