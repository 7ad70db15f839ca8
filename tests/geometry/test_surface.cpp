// SPDX-License-Identifier: GPL-3.0-or-later
// Triangulated hull and fins: watertight, outward, converging to the analytic solids; fins deflect
// about their posts; the union with deflected fins is a clean closed surface.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "auvloop/geometry/error.hpp"
#include "auvloop/geometry/surface.hpp"
#include "surface_reference.hpp"

using namespace auvloop::geometry;

namespace {
constexpr double kDeg = std::numbers::pi / 180;
const Vehicle& remus() {
  static const Vehicle v = preset_vehicle("remus100");
  return v;
}
FinGeometry fin(std::size_t i) {
  return FinGeometry(remus().fin_set, remus().fin_set.fins[i], MyringProfile(remus().hull),
                     remus().mass.cb_station);
}
}  // namespace

TEST(Surface, HullIsClosedOutwardAndClean) {
  const MyringProfile profile(remus().hull);
  const auto mesh = hull_surface(profile, remus().mass.cb_station, {0.01});
  const auto defects = inspect(mesh);
  EXPECT_TRUE(defects.ok()) << defects.describe();
  const auto m = measure(mesh);
  // Body frame: nose at x = cb_station, tail end at cb_station - l; axis on y = z = 0.
  EXPECT_NEAR(m.bbox_max.x(), 0.611, 1e-12);
  EXPECT_NEAR(m.bbox_min.x(), 0.611 - 1.3327, 1e-12);
  EXPECT_NEAR(m.centroid.y(), 0.0, 1e-9);
  EXPECT_NEAR(m.centroid.z(), 0.0, 1e-9);
  // The volume centroid of the hull lies 0.6058 m aft of the nose (remus100.md).
  EXPECT_NEAR(0.611 - m.centroid.x(), 0.6058, 0.0005);
}

TEST(Surface, HullVolumeConvergesAtSecondOrder) {
  const MyringProfile profile(remus().hull);
  const double exact = hull_properties(profile).volume;
  std::vector<double> error;
  for (double h : {0.02, 0.01, 0.005}) {
    error.push_back(std::abs(measure(hull_surface(profile, 0.611, {h})).volume - exact));
  }
  for (std::size_t i = 1; i < error.size(); ++i) {
    const double order = std::log2(error[i - 1] / error[i]);
    EXPECT_NEAR(order, 2.0, 0.15) << "refinement " << i << ": errors " << error[i - 1] << " -> "
                                  << error[i];
  }
}

TEST(Surface, FinIsClosedOutwardAndConverges) {
  const auto f = fin(0);
  const double exact = auvloop::test::exact_fin(f.set(), MyringProfile(remus().hull)).volume;
  double previous = 0;
  for (double h : {0.004, 0.002}) {
    const auto mesh = fin_surface(f, 0.0, {h});
    const auto defects = inspect(mesh);
    EXPECT_TRUE(defects.ok()) << defects.describe();
    const double error = std::abs(measure(mesh).volume / exact - 1);
    EXPECT_LT(error, 5e-3) << "h = " << h;
    if (previous > 0) {
      EXPECT_GT(previous / error, 3.0) << "second order: the error should quarter";
    }
    previous = error;
  }
}

TEST(Surface, BluntAndCamberedSectionsAreClosed) {
  FinSetParameters set = remus().fin_set;
  set.section = *NacaSection::parse("NACA 2412");
  set.section.sharp_trailing_edge = false;
  const FinGeometry f(set, set.fins[1], MyringProfile(remus().hull), 0.611);
  const auto defects = inspect(fin_surface(f, 10 * kDeg, {0.005}));
  EXPECT_TRUE(defects.ok()) << defects.describe();
}

TEST(Surface, DeflectedFinRotatesAboutItsPost) {
  const auto f = fin(0);
  const double delta = 25 * kDeg;
  const auto straight = fin_surface(f, 0.0, {0.008});
  const auto turned = fin_surface(f, delta, {0.008});
  ASSERT_EQ(straight.number_of_vertices(), turned.number_of_vertices());
  // Independent of FinGeometry::rotation: Rodrigues' formula about the post axis (0, 0, -1)
  // through (cb - post_station, 0, 0) for the upper fin.
  const Eigen::Vector3d k(0, 0, -1), o(0.611 - 1.249, 0, 0);
  double worst = 0;
  for (auto v : straight.vertices()) {
    const auto& p = straight.point(v);
    const auto& q = turned.point(v);
    const Eigen::Vector3d r = Eigen::Vector3d(p.x(), p.y(), p.z()) - o;
    const Eigen::Vector3d expected = o + r * std::cos(delta) + k.cross(r) * std::sin(delta) +
                                     k * k.dot(r) * (1 - std::cos(delta));
    worst = std::max(worst, (expected - Eigen::Vector3d(q.x(), q.y(), q.z())).norm());
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(Surface, PositiveRudderMovesTrailingEdgesToPort) {
  // Prestero: delta_r > 0 puts the rudder trailing edges to port (-y).
  for (std::size_t i : {0U, 2U}) {
    const auto f = fin(i);
    const double delta = fin_deflection(remus().fin_set.fins[i], 10 * kDeg, 0.0);
    const double rho = f.set().root_radius() + 0.5 * f.set().span;
    EXPECT_LT(f.point(rho, 1.0, 1, delta).y(), -1e-3) << f.name();
    EXPECT_GT(f.point(rho, 0.0, 1, delta).y(), 1e-3) << f.name() << " leading edge to starboard";
  }
  // delta_s > 0 puts the stern-plane trailing edges down (+z).
  for (std::size_t i : {1U, 3U}) {
    const auto f = fin(i);
    const double delta = fin_deflection(remus().fin_set.fins[i], 0.0, 10 * kDeg);
    const double rho = f.set().root_radius() + 0.5 * f.set().span;
    EXPECT_GT(f.point(rho, 1.0, 1, delta).z(), 1e-3) << f.name();
  }
}

TEST(Surface, UnionIsCleanForDeflectedFins) {
  // The full sweep (-35 to 35 deg in 5 deg steps) is the validation test UnionSweep.
  for (int deg : {-35, 0, 20, 35}) auvloop::test::expect_clean_union(remus(), deg);
}

TEST(Surface, DeflectionBeyondTheLimitIsRejected) {
  const std::vector<double> d{36 * kDeg, 0, 0, 0};
  EXPECT_THROW(vehicle_parts(remus(), d, {0.01}), GeometryError);
  const std::vector<double> wrong_count{0, 0};
  EXPECT_THROW(vehicle_parts(remus(), wrong_count, {0.01}), GeometryError);
}

TEST(Surface, PointedEndsAreClosedWithAnApex) {
  MyringParameters p = remus().hull;
  p.a_offset = 0;
  p.c_offset = 0;
  const MyringProfile profile(p);
  const auto mesh = hull_surface(profile, 0.6, {0.01});
  EXPECT_TRUE(inspect(mesh).ok()) << inspect(mesh).describe();
  EXPECT_NEAR(measure(mesh).volume / hull_properties(profile).volume, 1.0, 5e-3);
}

TEST(FinGeometry, RootFaceStandsTheGapOffTheHull) {
  const auto f = fin(0);
  const MyringProfile hull(remus().hull);
  const double gap = remus().fin_set.root_gap;
  for (double x : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    // The chord line's root point (the mid-point of the root face's line across the section).
    const Eigen::Vector3d p =
        0.5 * (f.point(f.root_rho(x), x, 1, 0.0) + f.point(f.root_rho(x), x, -1, 0.0));
    const double station = remus().mass.cb_station - p.x();
    EXPECT_NEAR(std::hypot(p.y(), p.z()) - hull.radius(station), gap, 1e-12) << x;
  }
  // Turned, the root face's trailing part moves forward over a thicker hull and the gap narrows
  // (2.45 mm at 35 deg): hull_clearance against a dense sampling of the whole face.
  for (double deg : {0.0, 10.0, 20.0, 35.0}) {
    const double d = deg * kDeg;
    double dense = 1.0;
    for (int i = 0; i <= 1000; ++i) {
      const double x = i / 1000.0, rho = f.root_rho(x);
      for (int k = 0; k <= 10; ++k) {
        const Eigen::Vector3d p =
            f.point(rho, x, 1, d) + (k / 10.0) * (f.point(rho, x, -1, d) - f.point(rho, x, 1, d));
        dense = std::min(dense,
                         std::hypot(p.y(), p.z()) - hull.radius(remus().mass.cb_station - p.x()));
      }
    }
    std::printf("root gap at %g deg: %.4f mm (dense sampling %.4f mm)\n", deg,
                1e3 * f.hull_clearance(d), 1e3 * dense);
    EXPECT_NEAR(f.hull_clearance(d), dense, 2e-5) << deg;
    EXPECT_GT(f.hull_clearance(d), 0.5 * gap) << deg;  // what the vehicle check demands
  }
}
