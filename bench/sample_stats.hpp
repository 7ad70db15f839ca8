// SPDX-License-Identifier: GPL-3.0-or-later
// The mean and the sample standard deviation the optimizer benchmarks print (0 for fewer than
// one and two values).
#pragma once

#include <cmath>
#include <numeric>
#include <vector>

struct MeanSd {
  double mean = 0, sd = 0;
};

inline MeanSd mean_sd(const std::vector<double>& v) {
  MeanSd r;
  if (v.empty()) return r;
  const auto n = static_cast<double>(v.size());
  r.mean = std::accumulate(v.begin(), v.end(), 0.0) / n;
  double ss = 0;
  for (double x : v) ss += (x - r.mean) * (x - r.mean);
  r.sd = v.size() > 1 ? std::sqrt(ss / (n - 1)) : 0;
  return r;
}
