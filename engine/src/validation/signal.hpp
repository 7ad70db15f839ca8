// SPDX-License-Identifier: GPL-3.0-or-later
// Sampled force histories of the shedding cases (Schaefer-Turek 2D-2, the unconfined cylinder):
// private to engine/src/validation.
#pragma once

#include <algorithm>
#include <vector>

namespace auvloop::engine::validation {

// Times at which x(t) - mean crosses zero upwards, interpolated linearly between samples.
inline std::vector<double> upward_crossings(const std::vector<double>& t,
                                            const std::vector<double>& x) {
  double mean = 0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  std::vector<double> out;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double a = x[i - 1] - mean, b = x[i] - mean;
    if (a < 0 && b >= 0) out.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-a) / (b - a));
  }
  return out;
}

// Maximum of sampled x, refined by the parabola through the largest sample and its neighbours
// (the sampling error of a peak is O(dt^2) otherwise).
inline double peak(const std::vector<double>& x) {
  const auto it = std::max_element(x.begin() + 1, x.end() - 1);
  const double a = *(it - 1), b = *it, c = *(it + 1);
  const double den = a - 2 * b + c;
  return den < 0 ? b - (c - a) * (c - a) / (8 * den) : b;
}

}  // namespace auvloop::engine::validation
