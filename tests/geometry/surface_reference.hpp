// SPDX-License-Identifier: GPL-3.0-or-later
// Independent reference values for the triangulated surfaces, computed from the formulas alone.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "auvloop/geometry/fin.hpp"
#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/surface.hpp"
#include "fin_reference.hpp"

namespace auvloop::test {

// Hull and four fins deflected by +-deg (rudders) and +-deg/2 (stern planes) unite into one clean
// closed surface (five components: the fins stand a gap off the hull) whose volume exceeds the
// hull's by four fins.
inline void expect_clean_union(const geometry::Vehicle& v, int deg) {
  using namespace geometry;
  const double r = deg * std::numbers::pi / 180;
  const std::vector<double> d{-r, 0.5 * r, r, -0.5 * r};
  const auto merged = merge_parts(vehicle_parts(v, d, {0.01}));
  const auto defects = inspect(merged);
  EXPECT_TRUE(defects.ok()) << deg << " deg: " << defects.describe();
  const MyringProfile hull(v.hull);
  // Less the polyhedral hull of the same edge length (its own error, 1e-4 of its volume, is
  // of the order of the fins' volume), the fins' polyhedra: a few per cent inside the smooth
  // solids with 1 cm edges.
  const double fins =
      measure(merged).volume - measure(hull_surface(hull, v.mass.cb_station, {0.01})).volume;
  EXPECT_NEAR(fins / (4 * exact_fin(v.fin_set, hull).volume), 1.0, 0.03) << deg;
}

}  // namespace auvloop::test
