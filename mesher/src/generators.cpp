// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/generators.hpp"

#include <cmath>
#include <stdexcept>

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

}  // namespace auvloop::mesher
