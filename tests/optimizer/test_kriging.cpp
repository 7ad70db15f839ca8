// SPDX-License-Identifier: GPL-3.0-or-later
// Kriging against hand calculation, interpolation, the likelihood gradient against finite
// differences, EI against numerical integration, and the Latin hypercube's properties.
#include <cmath>
#include <numbers>
#include <set>

#include <gtest/gtest.h>

#include "auvloop/optimizer/design.hpp"
#include "auvloop/optimizer/infill.hpp"
#include "auvloop/optimizer/kriging.hpp"

using namespace auvloop::optimizer;

TEST(Kriging, OneDimensionalCaseMatchesHandCalculation) {
  // Samples (0, 0) and (1, 1), theta = 1. Standardised y = (-1, 1), rho = e^-1, mu = 0 by symmetry,
  // R^-1 y = (-1, 1) / (1 - rho), sigma^2 = 1 / (1 - rho) (standardised units, scale 0.5).
  Eigen::MatrixXd X(2, 1);
  X << 0, 1;
  const Kriging k(X, Eigen::Vector2d(0, 1), Eigen::VectorXd::Constant(1, 1.0));
  const double rho = std::exp(-1.0);
  for (double x : {0.25, 0.5, 0.8}) {
    const double r1 = std::exp(-x * x), r2 = std::exp(-(x - 1) * (x - 1));
    const double mean = 0.5 + 0.5 * (r2 - r1) / (1 - rho);
    // MSE = sigma^2 [1 - r^T R^-1 r + (1 - 1^T R^-1 r)^2 / 1^T R^-1 1]
    const double det = 1 - rho * rho;
    const double rRr = (r1 * r1 + r2 * r2 - 2 * rho * r1 * r2) / det;
    const double oneRr = (r1 + r2) / (1 + rho);
    const double oneRone = 2 / (1 + rho);
    const double mse = 0.25 / (1 - rho) * (1 - rRr + (1 - oneRr) * (1 - oneRr) / oneRone);
    const Prediction p = k.predict(Eigen::VectorXd::Constant(1, x));
    EXPECT_NEAR(p.mean, mean, 1e-12) << x;
    EXPECT_NEAR(p.variance, mse, 1e-12) << x;
  }
}

TEST(Kriging, InterpolatesItsSamples) {
  const Eigen::MatrixXd X = latin_hypercube(12, 2, 3);
  Eigen::VectorXd y(12);
  for (int i = 0; i < 12; ++i) y[i] = std::sin(6 * X(i, 0)) + X(i, 1) * X(i, 1);
  const Kriging k(X, y);
  for (int i = 0; i < 12; ++i) {
    const Prediction p = k.predict(X.row(i).transpose());
    EXPECT_NEAR(p.mean, y[i], 1e-6);
    EXPECT_LT(p.variance, 1e-8);
  }
  EXPECT_GT(k.predict(Eigen::Vector2d(0.5, 0.5)).variance, 1e-8);  // uncertain between samples
  EXPECT_LT(k.loo_rmse_normalised(), 1.0);                         // predicts better than the mean
}

TEST(Kriging, LikelihoodGradientMatchesFiniteDifferences) {
  const Eigen::MatrixXd X = latin_hypercube(10, 3, 5);
  Eigen::VectorXd y(10);
  for (int i = 0; i < 10; ++i) y[i] = std::cos(3 * X(i, 0)) + X(i, 1) - 2 * X(i, 2) * X(i, 0);
  y = (y.array() - y.mean()) / std::sqrt((y.array() - y.mean()).square().mean());
  const Eigen::Vector3d t(-0.7, 0.2, 0.6);
  Eigen::VectorXd g;
  Kriging::concentrated_likelihood(X, y, t, 1e-10, &g);
  for (int k = 0; k < 3; ++k) {
    const double h = 1e-6;
    Eigen::Vector3d tp = t, tm = t;
    tp[k] += h;
    tm[k] -= h;
    const double fd = (Kriging::concentrated_likelihood(X, y, tp, 1e-10, nullptr) -
                       Kriging::concentrated_likelihood(X, y, tm, 1e-10, nullptr)) /
                      (2 * h);
    EXPECT_NEAR(g[k], fd, 1e-6 * std::max(1.0, std::abs(fd))) << k;
  }
}

TEST(Infill, ExpectedImprovementMatchesNumericalIntegration) {
  // E[max(f_min - Y, 0)], Y ~ N(m, s^2), by composite Simpson over +-10 s.
  for (const auto& [m, s, fmin] : {std::tuple{1.0, 0.5, 0.8}, {0.0, 2.0, 1.0}, {3.0, 0.1, 2.0}}) {
    const int n = 20000;
    const double a = m - 10 * s, b = m + 10 * s, h = (b - a) / n;
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
      const double y = a + i * h;
      const double f = std::max(fmin - y, 0.0) * std::exp(-0.5 * std::pow((y - m) / s, 2)) /
                       (s * std::sqrt(2 * std::numbers::pi));
      sum += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * f;
    }
    EXPECT_NEAR(expected_improvement(m, s * s, fmin), sum * h / 3, 1e-7) << m << " " << s;
  }
  EXPECT_EQ(expected_improvement(1.0, 0.0, 2.0), 1.0);  // no uncertainty: the plain improvement
  EXPECT_EQ(expected_improvement(3.0, 0.0, 2.0), 0.0);
}

TEST(Design, LatinMaximinAndReproducible) {
  const Eigen::MatrixXd p = latin_hypercube(20, 3, 42);
  for (int k = 0; k < 3; ++k) {
    std::set<long> strata;
    for (int i = 0; i < 20; ++i) strata.insert(std::lround(p(i, k) * 20 - 0.5));
    EXPECT_EQ(strata.size(), 20U);  // one point per stratum in every column
  }
  EXPECT_EQ(p, latin_hypercube(20, 3, 42));
  EXPECT_NE(p, latin_hypercube(20, 3, 43));
  // The maximin search beats a single random Latin hypercube.
  EXPECT_GT(minimum_distance(p), minimum_distance(latin_hypercube(20, 3, 42, 1, 0)));
}

TEST(Infill, ParticleSwarmFindsAQuadraticMinimum) {
  const auto f = [](const Eigen::VectorXd& x) {
    return (x - Eigen::Vector3d(0.3, 0.7, 0.5)).squaredNorm();
  };
  const Eigen::VectorXd x = pso_minimize(f, 3, 9, {});
  EXPECT_LT((x - Eigen::Vector3d(0.3, 0.7, 0.5)).norm(), 1e-4);
  EXPECT_EQ(x, pso_minimize(f, 3, 9, {}));  // deterministic for a seed
  EXPECT_LT((nlopt_minimize(f, 3, 9, 4) - Eigen::Vector3d(0.3, 0.7, 0.5)).norm(), 1e-4);
}
