// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <array>

namespace auvloop::geometry {

template <class F>
double integrate(F&& f, double a, double b, int panels) {
  // 8-point Gauss-Legendre nodes and weights on [-1, 1].
  static constexpr std::array<double, 4> x{0.1834346424956498, 0.5255324099163290,
                                           0.7966664774136267, 0.9602898564975363};
  static constexpr std::array<double, 4> w{0.3626837833783620, 0.3137066458778873,
                                           0.2223810344533745, 0.1012285362903763};
  const double h = (b - a) / panels;
  double sum = 0;
  for (int i = 0; i < panels; ++i) {
    const double mid = a + (i + 0.5) * h;
    for (std::size_t k = 0; k < x.size(); ++k) {
      sum += w[k] * (f(mid - 0.5 * h * x[k]) + f(mid + 0.5 * h * x[k]));
    }
  }
  return 0.5 * h * sum;
}

}  // namespace auvloop::geometry
