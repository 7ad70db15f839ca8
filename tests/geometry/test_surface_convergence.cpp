// SPDX-License-Identifier: GPL-3.0-or-later
// Validation (slower): second-order convergence of the triangulated hull volume and wetted area
// to the analytic Myring values over four levels of refinement.
#include <cmath>

#include <gtest/gtest.h>

#include "auvloop/geometry/surface.hpp"
#include "surface_reference.hpp"

using namespace auvloop::geometry;

TEST(SurfaceConvergence, HullVolumeAndAreaAreSecondOrder) {
  const MyringProfile profile(preset_vehicle("remus100").hull);
  const auto exact = hull_properties(profile);
  const double exact_area = exact.wetted_area_curved + exact.end_face_area;
  std::vector<double> ev, ea;
  for (double h : {0.01, 0.005, 0.0025, 0.00125}) {
    const auto m = measure(hull_surface(profile, 0.611, {h}));
    ev.push_back(std::abs(m.volume / exact.volume - 1));
    ea.push_back(std::abs(m.area / exact_area - 1));
    std::printf("h = %.5f m: volume error %.3e, area error %.3e\n", h, ev.back(), ea.back());
  }
  for (std::size_t i = 1; i < ev.size(); ++i) {
    EXPECT_NEAR(std::log2(ev[i - 1] / ev[i]), 2.0, 0.1);
    EXPECT_NEAR(std::log2(ea[i - 1] / ea[i]), 2.0, 0.1);
  }
}

TEST(SurfaceConvergence, UnionSweep) {
  const auto v = preset_vehicle("remus100");
  for (int deg = -35; deg <= 35; deg += 5) auvloop::test::expect_clean_union(v, deg);
}
