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

namespace auvloop::test {

// Volume of the whole fin solid (embedded part included): integral over the span of
// chord(rho)^2 times the area of the unit-chord section, 2 * integral of y_t.
inline double fin_solid_volume(const geometry::FinGeometry& fin) {
  const auto& set = fin.set();
  const double unit_area =
      2 *
      geometry::integrate([&](double x) { return set.section.half_thickness(x); }, 0.0, 1.0, 4096);
  const double embedded = set.root_chord * set.root_chord * unit_area * set.embed_depth;
  const double exposed =
      geometry::integrate([&](double rho) { return std::pow(fin.chord_at(rho), 2) * unit_area; },
                          set.root_radius(), set.tip_radius, 16);
  return embedded + exposed;
}

// Hull and four fins deflected by +-deg (rudders) and +-deg/2 (stern planes) unite into one clean
// closed surface whose volume exceeds the hull's by four exposed fins.
inline void expect_clean_union(const geometry::Vehicle& v, int deg) {
  using namespace geometry;
  const double r = deg * std::numbers::pi / 180;
  const std::vector<double> d{-r, 0.5 * r, r, -0.5 * r};
  const auto merged = merge_parts(vehicle_parts(v, d, {0.01}));
  const auto defects = inspect(merged);
  EXPECT_TRUE(defects.ok()) << deg << " deg: " << defects.describe();
  const double fins = measure(merged).volume - hull_properties(MyringProfile(v.hull)).volume;
  // Each exposed fin holds well under the 5.5e-5 m^3 of a whole fin solid.
  EXPECT_GT(fins, 4 * 2e-5) << deg;
  EXPECT_LT(fins, 4 * 5.5e-5) << deg;
}

}  // namespace auvloop::test
