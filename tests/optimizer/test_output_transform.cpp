// SPDX-License-Identifier: GPL-3.0-or-later
// The surrogate's output transform (output_transform.hpp): the log transform's shift and its
// inverse, leave-one-out errors carried back to y's units, "auto" choosing the better fit, and
// the optimizer on the log scale resuming bit for bit (the transform is part of the state).
#include <cmath>

#include <gtest/gtest.h>

#include "auvloop/optimizer/optimizer.hpp"
#include "auvloop/optimizer/output_transform.hpp"
#include "auvloop/optimizer/test_functions.hpp"

using namespace auvloop::optimizer;

TEST(OutputTransform, LogOfPositiveDataIsPlainAndElseShiftedByATenthOfTheRange) {
  const OutputTransform pos = log_transform(Eigen::Vector3d(750, 3000, 30000));
  EXPECT_TRUE(pos.log);
  EXPECT_EQ(pos.shift, 0.0);
  EXPECT_DOUBLE_EQ(pos(750.0), std::log(750.0));
  const OutputTransform mixed = log_transform(Eigen::Vector3d(-3.86, -1.0, 0.0));
  EXPECT_TRUE(mixed.log);
  EXPECT_DOUBLE_EQ(mixed.shift, -3.86 - 0.386);
  EXPECT_NEAR(mixed(-3.86), std::log(0.386), 1e-12);  // the smallest: a tenth of the range up
  for (double y : {-3.86, -2.0, 0.0, 5.0})
    EXPECT_NEAR(mixed.inverse(mixed(y)), y, 1e-12 * (1 + std::abs(y)));
  EXPECT_FALSE(log_transform(Eigen::Vector2d(2.0, 2.0)).log);  // nothing to scale
}

TEST(OutputTransform, LeaveOneOutErrorsAreCarriedBackToTheValuesUnits) {
  Eigen::MatrixXd X(6, 1);
  X << 0.0, 0.2, 0.4, 0.6, 0.8, 1.0;
  const Eigen::VectorXd y = (8.0 * X.col(0).array()).exp().matrix();
  // On the plain scale the RMSE is the model's own LOO errors' RMS.
  const Kriging plain(X, y);
  EXPECT_NEAR(loo_rmse_in_y(plain, y, {}), std::sqrt(plain.loo_errors().squaredNorm() / 6.0),
              1e-9 * y.maxCoeff());
  // On the log scale, by hand: each left-out prediction exp(ln y_i - e_i).
  const OutputTransform t = log_transform(y);
  const Kriging logged(X, t(y));
  const Eigen::VectorXd e = logged.loo_errors();
  double sum = 0;
  for (int i = 0; i < 6; ++i) sum += std::pow(y[i] - std::exp(std::log(y[i]) - e[i]), 2);
  EXPECT_NEAR(loo_rmse_in_y(logged, y, t), std::sqrt(sum / 6.0), 1e-9 * y.maxCoeff());
}

TEST(OutputTransform, AutoKeepsTheFitWithTheSmallerLeaveOneOutError) {
  Eigen::MatrixXd X(8, 1);
  for (int i = 0; i < 8; ++i) X(i, 0) = i / 7.0;
  // Exponential data spanning four decades: the log fits far better.
  const Eigen::VectorXd expo = (9.0 * X.col(0).array()).exp().matrix();
  const auto a = fit_transformed(X, expo, "auto", {});
  const auto n = fit_transformed(X, expo, "none", {});
  const auto l = fit_transformed(X, expo, "log", {});
  EXPECT_TRUE(a.transform.log);
  EXPECT_LT(l.model.loo_rmse_normalised(), n.model.loo_rmse_normalised());
  EXPECT_LT(l.loo_rmse, n.loo_rmse);  // in the values' own units too
  EXPECT_EQ(a.loo_rmse, l.loo_rmse);
  // A straight line: its log is curved, the plain fit is the better one.
  const Eigen::VectorXd line = (1.0 + 10.0 * X.col(0).array()).matrix();
  const auto b = fit_transformed(X, line, "auto", {});
  EXPECT_FALSE(b.transform.log);
  EXPECT_LE(b.model.loo_rmse_normalised(),
            fit_transformed(X, line, "log", {}).model.loo_rmse_normalised());
  EXPECT_THROW((void)fit_transformed(X, line, "sqrt", {}), std::invalid_argument);
}

TEST(OutputTransform, TheOptimizerOnTheLogScaleResumesBitForBit) {
  const TestFunction gp = test_function("goldstein-price");
  OptimizerConfig c;
  c.names = {"x1", "x2"};
  c.lower = gp.lower;
  c.upper = gp.upper;
  c.initial_points = 10;
  c.max_iterations = 4;
  c.epsilon = 0;
  c.output_transform = "log";
  SurrogateOptimizer full(c);
  SurrogateOptimizer half(c);
  int batches = 0;
  while (auto b = full.ask()) {
    std::vector<std::optional<double>> v;
    for (const auto& x : b->points) v.push_back(gp.f(x));
    full.tell(*b, v);
    if (++batches <= 3) half.tell(*half.ask(), v);
  }
  EXPECT_EQ(full.last_transform(), "log");
  SurrogateOptimizer resumed =
      SurrogateOptimizer::from_json(nlohmann::json::parse(half.to_json().dump()));
  EXPECT_EQ(resumed.config().output_transform, "log");
  while (auto b = resumed.ask()) {
    std::vector<std::optional<double>> v;
    for (const auto& x : b->points) v.push_back(gp.f(x));
    resumed.tell(*b, v);
  }
  ASSERT_EQ(resumed.evaluations().size(), full.evaluations().size());
  for (std::size_t i = 0; i < full.evaluations().size(); ++i)
    EXPECT_EQ(resumed.evaluations()[i].x, full.evaluations()[i].x) << i;
  c.output_transform = "exp";
  EXPECT_THROW(SurrogateOptimizer{c}, std::invalid_argument);
}
