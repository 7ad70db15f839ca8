// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/optimizer/design.hpp"

#include <limits>
#include <numeric>
#include <vector>

#include "random.hpp"

namespace auvloop::optimizer {

double minimum_distance(const Eigen::MatrixXd& p) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    for (Eigen::Index j = i + 1; j < p.rows(); ++j)
      best = std::min(best, (p.row(i) - p.row(j)).norm());
  }
  return best;
}

Eigen::MatrixXd latin_hypercube(int n, int d, std::uint64_t seed, int candidates,
                                int swap_iterations) {
  detail::Random rng(seed);
  Eigen::MatrixXd best;
  double best_score = -1;
  for (int c = 0; c < candidates; ++c) {
    Eigen::MatrixXd p(n, d);
    for (int k = 0; k < d; ++k) {
      std::vector<int> perm(static_cast<std::size_t>(n));
      std::iota(perm.begin(), perm.end(), 0);
      for (std::size_t i = perm.size(); i > 1; --i)
        std::swap(perm[i - 1], perm[rng.below(i)]);  // Fisher-Yates
      for (int i = 0; i < n; ++i) p(i, k) = (perm[static_cast<std::size_t>(i)] + 0.5) / n;
    }
    double score = minimum_distance(p);
    // Swapping two entries of a column keeps the Latin property; keep swaps that help.
    for (int it = 0; it < swap_iterations && n > 1; ++it) {
      const auto k = static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(d)));
      const auto a = static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(n)));
      const auto b = static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(n)));
      if (a == b) continue;
      std::swap(p(a, k), p(b, k));
      const double s = minimum_distance(p);
      if (s >= score) {
        score = s;
      } else {
        std::swap(p(a, k), p(b, k));
      }
    }
    if (score > best_score) {
      best_score = score;
      best = p;
    }
  }
  return best;
}

}  // namespace auvloop::optimizer
