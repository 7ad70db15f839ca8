// SPDX-License-Identifier: GPL-3.0-or-later
// A stretched box whose interior points are moved by a smooth shear: non-orthogonal and skewed
// everywhere, for tests of the finite-volume operators and solvers on distorted cells.
#pragma once

#include <cmath>
#include <numbers>

#include "auvloop/mesher/generators.hpp"

namespace auvloop::test {

// n^3 cells on the unit cube, graded by 1.3 per cell along x and 0.8 along z.
inline mesher::Grid sheared_box(int n) {
  auto g = mesher::cartesian_box(mesher::graded_nodes(0, 1, n, 1.3), mesher::graded_nodes(0, 1, n),
                                 mesher::graded_nodes(0, 1, n, 0.8), {}, "sheared");
  for (auto& p : g.points) {
    p.x() += 0.1 * std::sin(std::numbers::pi * p.x()) * p.y();
    p.y() += 0.08 * std::sin(std::numbers::pi * p.y()) * p.z();
  }
  return g;
}

}  // namespace auvloop::test
