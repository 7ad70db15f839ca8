// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/optimizer/infill.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <nlopt.hpp>

#include "auvloop/optimizer/design.hpp"
#include "random.hpp"

namespace auvloop::optimizer {

double expected_improvement(double mean, double variance, double f_min) {
  const double s = std::sqrt(std::max(variance, 0.0));
  const double gain = f_min - mean;
  if (s <= 1e-300) return std::max(gain, 0.0);
  const double z = gain / s;
  const double Phi = 0.5 * std::erfc(-z / std::numbers::sqrt2);
  const double phi = std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi);
  return gain * Phi + s * phi;
}

Eigen::VectorXd pso_minimize(const UnitObjective& f, int d, std::uint64_t seed, const PsoOptions& o,
                             const std::vector<Eigen::VectorXd>& seeds) {
  detail::Random rng(seed);
  const int n = std::max(o.particles, static_cast<int>(seeds.size()));
  std::vector<Eigen::VectorXd> x(static_cast<std::size_t>(n)), v(static_cast<std::size_t>(n)),
      best_x;
  std::vector<double> best_f;
  Eigen::VectorXd global;
  double global_f = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    auto& xi = x[static_cast<std::size_t>(i)];
    xi = Eigen::VectorXd(d);
    for (int k = 0; k < d; ++k) xi[k] = rng.uniform();
    if (static_cast<std::size_t>(i) < seeds.size()) xi = seeds[static_cast<std::size_t>(i)];
    v[static_cast<std::size_t>(i)] = Eigen::VectorXd::Zero(d);
    best_x.push_back(xi);
    best_f.push_back(f(xi));
    if (best_f.back() < global_f) {
      global_f = best_f.back();
      global = xi;
    }
  }
  for (int it = 0; it < o.iterations; ++it) {
    for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
      for (int k = 0; k < d; ++k) {
        const double r1 = rng.uniform(), r2 = rng.uniform();
        double vk = o.inertia * v[i][k] + o.cognitive * r1 * (best_x[i][k] - x[i][k]) +
                    o.social * r2 * (global[k] - x[i][k]);
        v[i][k] = std::clamp(vk, -o.max_velocity, o.max_velocity);
        x[i][k] = std::clamp(x[i][k] + v[i][k], 0.0, 1.0);
      }
      const double fi = f(x[i]);
      if (fi < best_f[i]) {
        best_f[i] = fi;
        best_x[i] = x[i];
        if (fi < global_f) {
          global_f = fi;
          global = x[i];
        }
      }
    }
  }
  return global;
}

Eigen::VectorXd nlopt_minimize(const UnitObjective& f, int d, std::uint64_t seed, int starts,
                               const std::vector<Eigen::VectorXd>& seeds) {
  std::vector<Eigen::VectorXd> x0 = seeds;
  const Eigen::MatrixXd design = latin_hypercube(starts, d, seed, 1, 0);
  for (int i = 0; i < starts; ++i) x0.push_back(design.row(i).transpose());
  auto objective = [](const std::vector<double>& t, std::vector<double>&, void* raw) {
    const auto& fn = *static_cast<const UnitObjective*>(raw);
    return fn(Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size())));
  };
  Eigen::VectorXd best = x0.front();
  double best_f = std::numeric_limits<double>::infinity();
  for (const auto& start : x0) {
    nlopt::opt opt(d >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA, static_cast<unsigned>(d));
    opt.set_lower_bounds(std::vector<double>(static_cast<std::size_t>(d), 0.0));
    opt.set_upper_bounds(std::vector<double>(static_cast<std::size_t>(d), 1.0));
    opt.set_min_objective(objective, const_cast<UnitObjective*>(&f));
    opt.set_maxeval(300);
    opt.set_xtol_rel(1e-6);
    std::vector<double> t(start.data(), start.data() + d);
    double value = std::numeric_limits<double>::infinity();
    try {
      opt.optimize(t, value);
    } catch (const std::exception&) {
      value = f(Eigen::Map<const Eigen::VectorXd>(t.data(), d));
    }
    if (value < best_f) {
      best_f = value;
      best = Eigen::Map<const Eigen::VectorXd>(t.data(), d);
    }
  }
  return best;
}

}  // namespace auvloop::optimizer
