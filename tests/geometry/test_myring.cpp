// SPDX-License-Identifier: GPL-3.0-or-later
// The Myring hull of the remus100 preset against the reference values in
// shared/reference/remus100.md (computed there from the profile) and Prestero's thesis table.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "auvloop/geometry/myring.hpp"

using namespace auvloop::geometry;

namespace {
const MyringProfile& remus() {
  static const MyringProfile p(preset_vehicle("remus100").hull);
  return p;
}
void expect_rel(double value, double reference, double tol) {
  EXPECT_NEAR(value / reference - 1, 0.0, tol) << "value " << value << " reference " << reference;
}
}  // namespace

TEST(Myring, ReferencePropertiesWithinHalfPercent) {
  const HullProperties h = hull_properties(remus());
  expect_rel(h.length, 1.3327, 5e-3);
  expect_rel(h.volume, 0.03166, 5e-3);
  expect_rel(h.frontal_area, 0.02865, 5e-3);
  expect_rel(h.projected_area, 0.2265, 5e-3);
  expect_rel(h.wetted_area_curved, 0.7195, 5e-3);
  expect_rel(h.wetted_area_curved + h.end_face_area, 0.7250, 5e-3);
  expect_rel(h.centroid_station, 0.6058, 5e-3);
  EXPECT_NEAR(h.nose_radius, 0.0388, 0.00005);
  EXPECT_NEAR(h.tail_radius, 0.0162, 0.00005);
}

TEST(Myring, ProfileIsContinuousWithTheCorrectedTailFormula) {
  const auto& p = remus();
  const double r = p.max_radius();
  EXPECT_NEAR(p.radius(p.nose_end() - 1e-12), r, 1e-6);
  EXPECT_NEAR(p.radius(p.tail_start() + 1e-12), r, 1e-9);  // (x - l_f), not (x - l)
  EXPECT_NEAR(p.slope(p.tail_start() + 1e-12), 0.0, 1e-9);
  // Hull radius at the fin post, 1.249 m aft of the nose: 46.0 mm.
  EXPECT_NEAR(p.radius(1.249), 0.0460, 0.00005);
  // The tail leaves the body with the Myring semi-angle at its full (untruncated) length:
  // slope at station l_f + c equals -tan(theta) by construction of the cubic.
  const auto& q = p.parameters();
  const double t = q.c;
  const double c2 = 3 * q.d / (2 * q.c * q.c) - std::tan(q.theta) / q.c;
  const double c3 = q.d / (q.c * q.c * q.c) - std::tan(q.theta) / (q.c * q.c);
  EXPECT_NEAR(-2 * c2 * t + 3 * c3 * t * t, -std::tan(q.theta), 1e-12);
}

TEST(Myring, SlopeMatchesFiniteDifferences) {
  const auto& p = remus();
  for (double x : {1e-5, 0.05, 0.12, 0.17, 0.5, 0.9, 1.1, 1.3}) {
    const double h = 1e-6;
    const double fd = (p.radius(x + h) - p.radius(x - h)) / (2 * h);
    EXPECT_NEAR(p.slope(x), fd, 1e-5) << "station " << x;
  }
}

TEST(Myring, GaussLegendreQuadratureMatchesClosedForms) {
  // 8-point Gauss-Legendre is exact for polynomials up to degree 15 on one panel.
  EXPECT_NEAR(integrate([](double x) { return std::sin(x); }, 0.0, std::numbers::pi, 8), 2.0,
              1e-14);
  EXPECT_NEAR(integrate([](double x) { return x * x * x * x * x * x * x; }, 0.0, 1.0, 1), 0.125,
              1e-15);
}
