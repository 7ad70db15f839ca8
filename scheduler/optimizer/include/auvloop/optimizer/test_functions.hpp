// SPDX-License-Identifier: GPL-3.0-or-later
// Analytic test problems for the optimizer (shared/reference/optimizer-benchmarks.md; Dixon &
// Szego 1978), so that anyone can check the optimizer on problems with known minima.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace auvloop::optimizer {

struct TestFunction {
  std::string name;
  Eigen::VectorXd lower, upper;
  double minimum;  // global minimum value
  std::function<double(const Eigen::VectorXd&)> f;
};

// "branin", "goldstein-price", "hartmann3", "hartmann6"; throws std::invalid_argument otherwise.
TestFunction test_function(const std::string& name);
std::vector<std::string> test_function_names();

}  // namespace auvloop::optimizer
