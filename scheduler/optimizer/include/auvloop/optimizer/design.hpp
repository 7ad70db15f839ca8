// SPDX-License-Identifier: GPL-3.0-or-later
// Latin hypercube designs on the unit cube with the maximin criterion (Morris & Mitchell 1995):
// among `candidates` random Latin hypercubes, refined by pairwise swaps within a column, keep the
// one whose smallest pairwise distance is largest. Fully determined by the seed.
#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace auvloop::optimizer {

// n points in [0, 1]^d, one per row; every column is a permutation of the n strata, each point at
// the centre of its stratum.
Eigen::MatrixXd latin_hypercube(int n, int d, std::uint64_t seed, int candidates = 20,
                                int swap_iterations = 200);

// Smallest Euclidean distance between two rows.
double minimum_distance(const Eigen::MatrixXd& points);

}  // namespace auvloop::optimizer
