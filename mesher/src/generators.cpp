// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/generators.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace auvloop::mesher {

std::vector<double> graded_nodes(double a, double b, int n, double ratio, bool two_sided) {
  if (n < 1 || !(b > a) || !(ratio > 0))
    throw std::invalid_argument("graded_nodes: need n >= 1, b > a, ratio > 0");
  if (two_sided) {
    const int half = n / 2;
    const double mid = 0.5 * (a + b);
    auto left = graded_nodes(a, mid, std::max(1, half), ratio);
    auto right = graded_nodes(mid, b, std::max(1, n - half), 1 / ratio);
    left.insert(left.end(), right.begin() + 1, right.end());
    return left;
  }
  // Cell sizes h, h r, h r^2, ...: h = (b - a) (r - 1) / (r^n - 1).
  std::vector<double> x{a};
  const double h = ratio == 1.0 ? (b - a) / n : (b - a) * (ratio - 1) / (std::pow(ratio, n) - 1);
  double step = h;
  for (int i = 1; i < n; ++i) {
    x.push_back(x.back() + step);
    step *= ratio;
  }
  x.push_back(b);
  return x;
}

std::vector<double> grown_nodes(double a, double b, double first, double max_ratio) {
  const double length = b - a;
  if (!(length > 0) || !(first > 0) || !(max_ratio >= 1)) {
    throw std::invalid_argument("grown_nodes: need b > a, first > 0, max_ratio >= 1");
  }
  if (first >= length) return {a, b};
  // Fewest cells that reach `length` with growth max_ratio, then the ratio that fits exactly.
  const int n = max_ratio == 1.0
                    ? static_cast<int>(std::ceil(length / first))
                    : static_cast<int>(std::ceil(std::log(1 + length * (max_ratio - 1) / first) /
                                                 std::log(max_ratio)));
  auto first_cell = [&](double r) {
    return r == 1.0 ? length / n : length * (r - 1) / (std::pow(r, n) - 1);
  };
  double lo = 1.0, hi = std::max(max_ratio, 1.0 + 1e-12);
  for (int i = 0; i < 200; ++i) {  // first_cell decreases with r
    const double mid = 0.5 * (lo + hi);
    (first_cell(mid) > first ? lo : hi) = mid;
  }
  return graded_nodes(a, b, n, 0.5 * (lo + hi));
}

std::vector<double> banded_nodes(double length, double first, double growth, double band_size,
                                 double band_end) {
  if (!(length > 0) || !(first > 0) || !(growth >= 1) || !(band_size > 0)) {
    throw std::invalid_argument(
        "banded_nodes: need length > 0, first > 0, growth >= 1, band_size > 0");
  }
  std::vector<double> x{0.0};
  double h = std::min(first, band_size);
  while (x.back() + 0.5 * h < length) {
    x.push_back(x.back() + h);
    h = x.back() < band_end ? std::min(h * growth, band_size) : h * growth;
  }
  x.back() = length;
  return x;
}

std::vector<double> stretched_nodes(double a, double b, double first, int n) {
  const double length = b - a;
  if (n < 1 || !(length > 0) || !(first > 0) || !(first < length)) {
    throw std::invalid_argument("stretched_nodes: need n >= 1, b > a and 0 < first < b - a");
  }
  if (n == 1) return {a, b};
  // first_cell(r) = length (r - 1) / (r^n - 1) falls monotonically with r; bisect on log r.
  auto first_cell = [&](double log_r) {
    return std::abs(log_r) < 1e-14 ? length / n
                                   : length * std::expm1(log_r) / std::expm1(n * log_r);
  };
  double lo = -5.0, hi = 5.0;  // ratios from 0.007 to 148: far beyond any usable grading
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (first_cell(mid) > first ? lo : hi) = mid;
  }
  return graded_nodes(a, b, n, std::exp(0.5 * (lo + hi)));
}

std::vector<double> two_sided_nodes(double a, double b, int n, double first, double last) {
  const double length = b - a;
  const double uniform = length / n;
  if (n < 3 || !(length > 0) || !(first > 0) || !(last > 0) || !(first < uniform) ||
      !(last < uniform)) {
    throw std::invalid_argument(
        "two_sided_nodes: need n >= 3, b > a and both end cells in (0, (b - a) / n)");
  }
  // Index xi = k / n in [0, 1] maps to s in [0, 1]: u = (1 + tanh(d (xi - 1/2)) / tanh(d / 2)) / 2,
  // s = u / (A + (1 - A) u). The slopes at the ends are ds/dxi = d / (A sinh d) and A d / sinh d;
  // setting them to S0 and S1 gives A = sqrt(S1 / S0) and sinh(d) / d = 1 / sqrt(S0 S1) > 1,
  // solved for d by bisection (sinh(d) / d rises with d). The end cells differ from the slopes
  // over n by O(1 / n) (tens of per cent at n = 12 for strong clustering), so S0 and S1, started
  // at the targets over the uniform size, are corrected by the ratio of target to cell until both
  // cells match to 1e-10: a fixed point that converges in a handful of passes when both ends are
  // finer than uniform and n >= 3 (a random sweep of 4,000 such cases converged); it is checked.
  const auto nodes = [&](double s0, double s1) {
    const double big_a = std::sqrt(s1 / s0), target = 1 / std::sqrt(s0 * s1);
    double lo = 0, hi = 1;
    while (std::sinh(hi) / hi < target) hi *= 2;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (mid > 0 && std::sinh(mid) / mid < target ? lo : hi) = mid;
    }
    const double d = 0.5 * (lo + hi);
    std::vector<double> x;
    for (int k = 0; k <= n; ++k) {
      const double xi = static_cast<double>(k) / n;
      const double u = 0.5 * (1 + std::tanh(d * (xi - 0.5)) / std::tanh(0.5 * d));
      x.push_back(a + length * u / (big_a + (1 - big_a) * u));
    }
    x.front() = a;
    x.back() = b;
    return x;
  };
  double s0 = first / uniform, s1 = last / uniform;
  auto x = nodes(s0, s1);
  for (int pass = 0; pass < 200; ++pass) {
    const double c0 = x[1] - x[0], c1 = x[x.size() - 1] - x[x.size() - 2];
    if (std::abs(c0 - first) < 1e-10 * first && std::abs(c1 - last) < 1e-10 * last) return x;
    const double t0 = s0 * first / c0, t1 = s1 * last / c1;
    if (!(t0 * t1 < 1)) break;  // no longer clustered
    s0 = t0;
    s1 = t1;
    x = nodes(s0, s1);
  }
  throw std::invalid_argument(
      fmt::format("two_sided_nodes: no map of {} cells on [{}, {}] has end cells {} and {}", n, a,
                  b, first, last));
}

namespace {
// Coarse - fine - coarse: growth away from [lo, hi] on both sides.
std::vector<double> clustered(double a, double lo, double hi, double b, double h, double growth) {
  auto left = grown_nodes(-lo, -a, h, growth);  // mirrored so the fine cell sits at lo
  std::vector<double> x;
  for (auto it = left.rbegin(); it != left.rend(); ++it) x.push_back(-*it);
  const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / h)));
  for (int i = 1; i <= n; ++i) x.push_back(lo + (hi - lo) * i / n);
  const auto right = grown_nodes(hi, b, h, growth);
  x.insert(x.end(), right.begin() + 1, right.end());
  return x;
}
}  // namespace

Grid background_box(const BackgroundSpec& s) {
  if (!(s.length > 0) || !(s.radius > 0) || !(s.spacing > 0)) {
    throw std::invalid_argument("background_box: length, radius and spacing must be positive");
  }
  const double L = s.length, stern = s.nose_x - L;
  const double r = s.radius + s.margin;
  const auto x = clustered(stern - s.behind * L, stern - s.wake * L, s.nose_x + s.margin,
                           s.nose_x + s.ahead * L, s.spacing, s.growth);
  const auto y = clustered(-s.side * L, -r, r, s.side * L, s.spacing, s.growth);
  BoxPatches p;
  // Body frame: the vehicle moves forward (+x), so the flow enters at x+ and leaves at x-.
  p.names = {"outlet", "inlet", "side_port", "side_starboard", "top", "bottom"};
  p.types = {PatchType::outlet,   PatchType::inlet,    PatchType::symmetry,
             PatchType::symmetry, PatchType::symmetry, PatchType::symmetry};
  return cartesian_box(x, y, y, p, "background");
}

Grid cartesian_box(const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<double>& z, const BoxPatches& patches,
                   const std::string& name) {
  const int nx = static_cast<int>(x.size()) - 1, ny = static_cast<int>(y.size()) - 1,
            nz = static_cast<int>(z.size()) - 1;
  if (nx < 1 || ny < 1 || nz < 1)
    throw std::invalid_argument("cartesian_box: at least two nodes per direction");
  Grid g;
  g.name = name;
  g.cells = nx * ny * nz;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        g.points.emplace_back(x[static_cast<std::size_t>(i)], y[static_cast<std::size_t>(j)],
                              z[static_cast<std::size_t>(k)]);
  const auto p = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  const auto c = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  // Faces with normals along +x, +y, +z through the node (i, j, k).
  const auto xface = [&](int i, int j, int k) {
    return std::vector<int>{p(i, j, k), p(i, j + 1, k), p(i, j + 1, k + 1), p(i, j, k + 1)};
  };
  const auto yface = [&](int i, int j, int k) {
    return std::vector<int>{p(i, j, k), p(i, j, k + 1), p(i + 1, j, k + 1), p(i + 1, j, k)};
  };
  const auto zface = [&](int i, int j, int k) {
    return std::vector<int>{p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k)};
  };
  // Internal faces in upper-triangular order: by owner, then by neighbour (+x < +y < +z).
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (i + 1 < nx) {
          g.add_face(xface(i + 1, j, k), c(i, j, k));
          g.neighbour.push_back(c(i + 1, j, k));
        }
        if (j + 1 < ny) {
          g.add_face(yface(i, j + 1, k), c(i, j, k));
          g.neighbour.push_back(c(i, j + 1, k));
        }
        if (k + 1 < nz) {
          g.add_face(zface(i, j, k + 1), c(i, j, k));
          g.neighbour.push_back(c(i, j, k + 1));
        }
      }
  auto reversed = [](std::vector<int> v) {
    std::reverse(v.begin(), v.end());
    return v;
  };
  auto add_patch = [&](int side, auto&& faces) {
    Patch patch{patches.names[static_cast<std::size_t>(side)],
                patches.types[static_cast<std::size_t>(side)], g.faces(), 0, -1};
    faces();
    patch.size = g.faces() - patch.start;
    if (patch.type == PatchType::periodic) patch.neighbour_patch = side ^ 1;
    g.patches.push_back(patch);
  };
  add_patch(0, [&] {
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j) g.add_face(reversed(xface(0, j, k)), c(0, j, k));
  });
  add_patch(1, [&] {
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j) g.add_face(xface(nx, j, k), c(nx - 1, j, k));
  });
  add_patch(2, [&] {
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i) g.add_face(reversed(yface(i, 0, k)), c(i, 0, k));
  });
  add_patch(3, [&] {
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i) g.add_face(yface(i, ny, k), c(i, ny - 1, k));
  });
  add_patch(4, [&] {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) g.add_face(reversed(zface(i, j, 0)), c(i, j, 0));
  });
  add_patch(5, [&] {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) g.add_face(zface(i, j, nz), c(i, j, nz - 1));
  });
  return g;
}

std::vector<double> cored_nodes(double half, double lo, double hi, double h, double growth) {
  const int n = std::max(1, static_cast<int>(std::lround((hi - lo) / h)));
  const auto core = graded_nodes(lo, hi, n);
  const double first = (hi - lo) / n;
  const auto below = grown_nodes(0, lo + half, first, growth);  // distances below the core
  std::vector<double> x;
  for (auto it = below.rbegin(); it != below.rend(); ++it) x.push_back(lo - *it);
  x.insert(x.end(), core.begin() + 1, core.end());
  const auto above = grown_nodes(hi, half, first, growth);
  x.insert(x.end(), above.begin() + 1, above.end());
  return x;
}

}  // namespace auvloop::mesher
