// SPDX-License-Identifier: GPL-3.0-or-later
#include "sparse.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "parallel.hpp"

namespace auvloop::engine::fv {

BlockCsr::BlockCsr(int n, std::span<const int> row_start, std::span<const int> columns)
    : diag(static_cast<std::size_t>(n), 0.0),
      value(columns.size(), 0.0),
      n_(n),
      row_start_(row_start.begin(), row_start.end()),
      split_(static_cast<std::size_t>(n)),
      column_(columns.size()),
      permutation_(columns.size()),
      inv_diag_(static_cast<std::size_t>(n), 0.0) {
  if (row_start.size() != static_cast<std::size_t>(n) + 1 ||
      row_start.back() != static_cast<int>(columns.size()))
    throw std::logic_error("BlockCsr: row_start does not describe the columns");
  int blocks = 1;
  while (2 * blocks <= std::min(kMaxBlocks, n / kMinBlockRows)) blocks *= 2;
  block_start_.resize(static_cast<std::size_t>(blocks) + 1);
  for (int k = 0; k <= blocks; ++k)
    block_start_[static_cast<std::size_t>(k)] =
        static_cast<int>(static_cast<long long>(n) * k / blocks);
  mid_.resize(static_cast<std::size_t>(n));
  std::vector<int> own;
  for (int blk = 0; blk < blocks; ++blk) {
    const int lo = block_begin(blk), hi = block_end(blk);
    for (int i = lo; i < hi; ++i) {
      int out = row_begin(i);
      own.clear();
      for (int k = row_begin(i); k < row_end(i); ++k) {
        const int j = columns[static_cast<std::size_t>(k)];
        if (j >= lo && j < hi) own.push_back(k);
      }
      std::sort(own.begin(), own.end(), [&](int a, int b) {
        return columns[static_cast<std::size_t>(a)] < columns[static_cast<std::size_t>(b)];
      });
      mid_[static_cast<std::size_t>(i)] = out;
      for (int k : own) {
        const int j = columns[static_cast<std::size_t>(k)];
        if (j < i) ++mid_[static_cast<std::size_t>(i)];
        column_[static_cast<std::size_t>(out)] = j;
        permutation_[static_cast<std::size_t>(out)] = k;
        ++out;
      }
      split_[static_cast<std::size_t>(i)] = out;
      for (int k = row_begin(i); k < row_end(i); ++k) {
        const int j = columns[static_cast<std::size_t>(k)];
        if (j >= lo && j < hi) continue;
        column_[static_cast<std::size_t>(out)] = j;
        permutation_[static_cast<std::size_t>(out)] = k;
        ++out;
      }
    }
  }
}

void BlockCsr::coefficients_changed() {
  parallel_for(
      n_,
      [&](int i) {
        const auto s = static_cast<std::size_t>(i);
        inv_diag_[s] = 1.0 / diag[s];
        if (single_) {
          diag_single_[s] = static_cast<float>(diag[s]);
          inv_diag_single_[s] = static_cast<float>(inv_diag_[s]);
          for (int k = row_begin(i); k < row_end(i); ++k)
            value_single_[static_cast<std::size_t>(k)] =
                static_cast<float>(value[static_cast<std::size_t>(k)]);
        }
      },
      kRowGrain);
}

void BlockCsr::keep_single() {
  if (single_) return;
  single_ = true;
  value_single_.resize(value.size());
  diag_single_.resize(diag.size());
  inv_diag_single_.resize(diag.size());
  coefficients_changed();
}

void BlockCsr::multiply(std::span<const double> x, std::span<double> y) const {
  parallel_ranges(
      n_,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) {
          const auto s = static_cast<std::size_t>(i);
          y[s] = diag[s] * x[s] + off_diagonal(i, x);
        }
      },
      kRowGrain);
}

template <bool Single>
double BlockCsr::multiply_dot(std::span<const double> x, std::span<double> y) const {
  return parallel_sum<1>(
      n_,
      [&](int b, int e, std::array<double, 1>& sum) {
        for (int i = b; i < e; ++i) {
          const auto s = static_cast<std::size_t>(i);
          const double d = Single ? static_cast<double>(diag_single_[s]) : diag[s];
          y[s] = d * x[s] + off_diagonal<Single>(i, x);
          sum[0] += x[s] * y[s];
        }
      },
      kRowGrain)[0];
}

BlockCsr::Residual BlockCsr::residual(std::span<const double> b, std::span<const double> x,
                                      std::span<double> r) const {
  const double mean = parallel_sum<1>(n_,
                                      [&](int lo, int hi, std::array<double, 1>& sum) {
                                        for (int i = lo; i < hi; ++i)
                                          sum[0] += x[static_cast<std::size_t>(i)];
                                      })[0] /
                      std::max(n_, 1);
  const auto s = parallel_sum<4>(
      n_,
      [&](int lo, int hi, std::array<double, 4>& sum) {
        for (int i = lo; i < hi; ++i) {
          const auto c = static_cast<std::size_t>(i);
          double off = 0, row_sum = diag[c];
          for (int k = row_begin(i); k < row_end(i); ++k) {
            const double a = value[static_cast<std::size_t>(k)];
            off += a * x[static_cast<std::size_t>(column(k))];
            row_sum += a;
          }
          const double ax = diag[c] * x[c] + off, axbar = row_sum * mean;
          r[c] = b[c] - ax;
          sum[0] += std::abs(r[c]);
          sum[1] += r[c] * r[c];
          sum[2] += b[c] * b[c];
          sum[3] += std::abs(ax - axbar) + std::abs(b[c] - axbar);
        }
      },
      kRowGrain);
  return {s[0], s[1], s[2], s[3]};
}

template <bool Single>
void BlockCsr::sweep(std::span<const double> b, std::span<double> x, bool backward, bool zero_x,
                     std::span<double> scratch) const {
  const bool coupled = blocks() > 1 && !zero_x;
  if (coupled) {  // 1. the terms to other blocks, from x before the sweep
    parallel_blocks(blocks(), [&](int blk) {
      for (int i = block_begin(blk); i < block_end(blk); ++i) {
        const auto s = static_cast<std::size_t>(i);
        if (split_[s] == row_end(i)) continue;
        double e = 0;
        for (int k = split_[s]; k < row_end(i); ++k)
          e += coefficient<Single>(k) * x[static_cast<std::size_t>(column(k))];
        scratch[s] = e;
      }
    });
  }
  // 2. Gauss-Seidel in each block. The entries the sweep has just updated (columns below the
  // row going forward, above it going backward) are summed apart from the others, nearest row
  // last, so that only one multiply-add waits for the previous row's result.
  parallel_blocks(blocks(), [&](int blk) {
    const auto relax = [&](int i) {
      const auto s = static_cast<std::size_t>(i);
      const int begin = row_begin(i), mid = mid_[s], split = split_[s];
      double older = 0, recent = 0;  // from x = 0 the older terms are all zero
      if (backward) {
        if (!zero_x)
          for (int k = begin; k < mid; ++k)
            older += coefficient<Single>(k) * x[static_cast<std::size_t>(column(k))];
        for (int k = split; k-- > mid;)
          recent += coefficient<Single>(k) * x[static_cast<std::size_t>(column(k))];
      } else {
        if (!zero_x)
          for (int k = mid; k < split; ++k)
            older += coefficient<Single>(k) * x[static_cast<std::size_t>(column(k))];
        for (int k = begin; k < mid; ++k)
          recent += coefficient<Single>(k) * x[static_cast<std::size_t>(column(k))];
      }
      double v = b[s] - older;
      if (coupled && split != row_end(i)) v -= scratch[s];
      x[s] = (v - recent) * (Single ? static_cast<double>(inv_diag_single_[s]) : inv_diag_[s]);
    };
    if (backward) {
      for (int i = block_end(blk); i-- > block_begin(blk);) relax(i);
    } else {
      for (int i = block_begin(blk); i < block_end(blk); ++i) relax(i);
    }
  });
}

template double BlockCsr::multiply_dot<false>(std::span<const double>, std::span<double>) const;
template double BlockCsr::multiply_dot<true>(std::span<const double>, std::span<double>) const;
template void BlockCsr::sweep<false>(std::span<const double>, std::span<double>, bool, bool,
                                     std::span<double>) const;
template void BlockCsr::sweep<true>(std::span<const double>, std::span<double>, bool, bool,
                                    std::span<double>) const;

double dot(std::span<const double> a, std::span<const double> b) {
  return parallel_sum<1>(static_cast<int>(a.size()), [&](int lo, int hi, std::array<double, 1>& s) {
    for (int i = lo; i < hi; ++i)
      s[0] += a[static_cast<std::size_t>(i)] * b[static_cast<std::size_t>(i)];
  })[0];
}

std::array<double, 2> dot2(std::span<const double> a, std::span<const double> b,
                           std::span<const double> c) {
  return parallel_sum<2>(static_cast<int>(a.size()), [&](int lo, int hi, std::array<double, 2>& s) {
    for (int i = lo; i < hi; ++i) {
      const auto k = static_cast<std::size_t>(i);
      s[0] += a[k] * b[k];
      s[1] += a[k] * c[k];
    }
  });
}

}  // namespace auvloop::engine::fv
