// SPDX-License-Identifier: GPL-3.0-or-later
// Infill criteria and the solvers of their sub-problems on the unit cube.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace auvloop::optimizer {

// Expected improvement of Jones, Schonlau & Welch (1998):
//   EI = (f_min - m) Phi(z) + s phi(z),  z = (f_min - m) / s,  and EI = max(f_min - m, 0) at s = 0.
double expected_improvement(double mean, double variance, double f_min);

// Global-best particle swarm (Kennedy & Eberhart 1995) with Clerc's constriction coefficients:
// inertia 0.7298, cognitive and social weights 1.49618; velocities limited to max_velocity per
// iteration (unit-cube units); positions clamped to [0, 1]. Deterministic for a given seed.
struct PsoOptions {
  int particles = 40;
  int iterations = 150;
  double inertia = 0.7298;
  double cognitive = 1.49618;
  double social = 1.49618;
  double max_velocity = 0.2;
};

using UnitObjective = std::function<double(const Eigen::VectorXd&)>;

// Minimises f over [0, 1]^d; `seeds` start as particles (e.g. the best sample so far).
Eigen::VectorXd pso_minimize(const UnitObjective& f, int d, std::uint64_t seed,
                             const PsoOptions& options,
                             const std::vector<Eigen::VectorXd>& seeds = {});

// The NLopt alternative: BOBYQA from `starts` points of a Latin hypercube plus the seeds.
Eigen::VectorXd nlopt_minimize(const UnitObjective& f, int d, std::uint64_t seed, int starts,
                               const std::vector<Eigen::VectorXd>& seeds = {});

}  // namespace auvloop::optimizer
