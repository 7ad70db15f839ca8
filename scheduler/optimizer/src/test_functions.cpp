// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/optimizer/test_functions.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace auvloop::optimizer {
namespace {

double hartmann(const Eigen::VectorXd& x, const Eigen::MatrixXd& A, const Eigen::MatrixXd& P) {
  const double alpha[] = {1.0, 1.2, 3.0, 3.2};
  double f = 0;
  for (int i = 0; i < 4; ++i) {
    f -= alpha[i] *
         std::exp(
             -(A.row(i).transpose().array() * (x - P.row(i).transpose()).array().square()).sum());
  }
  return f;
}

}  // namespace

std::vector<std::string> test_function_names() {
  return {"branin", "goldstein-price", "hartmann3", "hartmann6"};
}

TestFunction test_function(const std::string& name) {
  constexpr double pi = std::numbers::pi;
  if (name == "branin") {
    return {name, Eigen::Vector2d(-5, 0), Eigen::Vector2d(10, 15), 0.397887357729739,
            [](const Eigen::VectorXd& x) {
              const double b = 5.1 / (4 * pi * pi), c = 5 / pi, t = 1 / (8 * pi);
              return std::pow(x[1] - b * x[0] * x[0] + c * x[0] - 6, 2) +
                     10 * (1 - t) * std::cos(x[0]) + 10;
            }};
  }
  if (name == "goldstein-price") {
    return {
        name, Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2), 3.0, [](const Eigen::VectorXd& v) {
          const double x = v[0], y = v[1];
          const double a = 1 + std::pow(x + y + 1, 2) *
                                   (19 - 14 * x + 3 * x * x - 14 * y + 6 * x * y + 3 * y * y);
          const double b = 30 + std::pow(2 * x - 3 * y, 2) *
                                    (18 - 32 * x + 12 * x * x + 48 * y - 36 * x * y + 27 * y * y);
          return a * b;
        }};
  }
  if (name == "hartmann3") {
    Eigen::MatrixXd A(4, 3), P(4, 3);
    A << 3, 10, 30, 0.1, 10, 35, 3, 10, 30, 0.1, 10, 35;
    P << 3689, 1170, 2673, 4699, 4387, 7470, 1091, 8732, 5547, 381, 5743, 8828;
    P *= 1e-4;
    return {name, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Ones(3), -3.86278214782076,
            [A, P](const Eigen::VectorXd& x) { return hartmann(x, A, P); }};
  }
  if (name == "hartmann6") {
    Eigen::MatrixXd A(4, 6), P(4, 6);
    A << 10, 3, 17, 3.5, 1.7, 8, 0.05, 10, 17, 0.1, 8, 14, 3, 3.5, 1.7, 10, 17, 8, 17, 8, 0.05, 10,
        0.1, 14;
    P << 1312, 1696, 5569, 124, 8283, 5886, 2329, 4135, 8307, 3736, 1004, 9991, 2348, 1451, 3522,
        2883, 3047, 6650, 4047, 8828, 8732, 5743, 1091, 381;
    P *= 1e-4;
    return {name, Eigen::VectorXd::Zero(6), Eigen::VectorXd::Ones(6), -3.32236801141551,
            [A, P](const Eigen::VectorXd& x) { return hartmann(x, A, P); }};
  }
  throw std::invalid_argument("unknown test function \"" + name +
                              "\" (branin, goldstein-price, hartmann3, hartmann6)");
}

}  // namespace auvloop::optimizer
