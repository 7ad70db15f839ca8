// SPDX-License-Identifier: GPL-3.0-or-later
// AABB-tree queries against the analytic shapes: inside/outside and signed distance of the hull
// against the Myring profile, and of a fin against the NACA thickness formula.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "auvloop/geometry/error.hpp"
#include "auvloop/geometry/surface_query.hpp"

using namespace auvloop::geometry;

namespace {
constexpr double kDeg = std::numbers::pi / 180;
constexpr double kCb = 0.611;

const Vehicle& remus() {
  static const Vehicle v = preset_vehicle("remus100");
  return v;
}

// Signed distance from (station, rho) to the closed meridian curve of the hull (nose face,
// profile, tail face), by brute force over a dense polyline: independent of the triangulation.
class MeridianDistance {
 public:
  explicit MeridianDistance(const MyringProfile& p) : profile_(p) {
    curve_.emplace_back(0.0, 0.0);
    constexpr int n = 40000;
    for (int i = 0; i <= n; ++i) {
      const double x = p.length() * i / n;
      curve_.emplace_back(x, p.radius(x));
    }
    curve_.emplace_back(p.length(), 0.0);
  }
  double operator()(double station, double rho) const {
    const Eigen::Vector2d q(station, rho);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < curve_.size(); ++i) {
      const Eigen::Vector2d a = curve_[i], ab = curve_[i + 1] - a;
      const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (a + t * ab - q).norm());
    }
    const bool inside =
        station >= 0 && station <= profile_.length() && rho <= profile_.radius(station);
    return inside ? -best : best;
  }

 private:
  const MyringProfile& profile_;
  std::vector<Eigen::Vector2d> curve_;
};
}  // namespace

TEST(SurfaceQuery, HullAgreesWithTheAnalyticProfile) {
  const MyringProfile profile(remus().hull);
  const double h = 0.005;
  const SurfaceQuery query(hull_surface(profile, kCb, {h}));
  const MeridianDistance reference(profile);
  // Chords of the profile deviate from it by at most h^2 / (8 R_min), R_min = (d/2)^2 / a = 0.048 m
  // (radius of curvature at the nose shoulder): 6.6e-5 m at h = 5 mm. Allow 1.5 times that.
  const double tol = 1.5 * h * h / (8 * 0.0955 * 0.0955 / 0.191);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> station(-0.05, 1.3827), rho(0.0, 0.12),
      angle(0, 2 * std::numbers::pi);
  int checked_inside = 0;
  for (int i = 0; i < 400; ++i) {
    const double s = station(rng), r = rho(rng), th = angle(rng);
    const Eigen::Vector3d p(kCb - s, r * std::sin(th), -r * std::cos(th));
    const double expected = reference(s, r);
    EXPECT_NEAR(query.signed_distance(p), expected, tol) << "station " << s << " rho " << r;
    if (std::abs(expected) > tol) {
      EXPECT_EQ(query.inside(p), expected < 0) << "station " << s << " rho " << r;
      checked_inside += expected < 0 ? 1 : 0;
    }
  }
  EXPECT_GT(checked_inside, 50);  // the sample really probes the interior
}

TEST(SurfaceQuery, ClosestPointLiesOnTheSurface) {
  const MyringProfile profile(remus().hull);
  const SurfaceQuery query(hull_surface(profile, kCb, {0.01}));
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.0, 0.3, 0.1), Eigen::Vector3d(-0.6, 0.01, 0.0),
                                   Eigen::Vector3d(1.0, 0.0, 0.0)}) {
    const Eigen::Vector3d c = query.closest_point(p);
    EXPECT_NEAR(std::abs(query.signed_distance(c)), 0.0, 1e-12);
    EXPECT_NEAR((c - p).norm(), std::abs(query.signed_distance(p)), 1e-12);
  }
}

TEST(SurfaceQuery, RaysHitTheNoseFaceAndTheBody) {
  const MyringProfile profile(remus().hull);
  const SurfaceQuery query(hull_surface(profile, kCb, {0.01}));
  // From 1 m ahead along the axis: the flat nose face at x = cb_station, normal +x.
  const auto nose = query.first_hit({kCb + 1.0, 0.001, 0.002}, {-1, 0, 0});
  ASSERT_TRUE(nose);
  EXPECT_NEAR(nose->distance, 1.0, 1e-12);
  EXPECT_NEAR(nose->normal.x(), 1.0, 1e-12);
  // From the side at mid-body: the faceted cylinder lies between the inscribed polygon and d/2.
  const auto side = query.first_hit({0.0, 1.0, 0.0}, {0, -1, 0});
  ASSERT_TRUE(side);
  EXPECT_LE(1.0 - side->distance, 0.0955 + 1e-12);
  EXPECT_GT(1.0 - side->distance, 0.0955 * std::cos(std::numbers::pi / 60) - 1e-12);
  EXPECT_FALSE(query.first_hit({0.0, 1.0, 0.0}, {0, 1, 0}));
}

TEST(SurfaceQuery, FinAgreesWithTheNacaThickness) {
  const auto& set = remus().fin_set;
  for (double delta : {0.0, 20 * kDeg}) {
    const FinGeometry fin(set, set.fins[1], MyringProfile(remus().hull), kCb);
    const SurfaceQuery query(fin_surface(fin, delta, {0.002}));
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> along(0.0, 1.0), x(0.02, 0.98);
    for (int i = 0; i < 200; ++i) {
      const double xc = x(rng), lo = fin.root_rho(xc) + 0.002, hi = set.tip_radius - 0.002;
      const double r = lo + along(rng) * (hi - lo);
      const int side = i % 2 == 0 ? 1 : -1;
      // A point of the analytic surface lies on the triangulation to within the chord sagitta.
      const Eigen::Vector3d on = fin.point(r, xc, side, delta);
      EXPECT_LT(std::abs(query.signed_distance(on)), 2e-5) << "rho " << r << " x/c " << xc;
      // Half the local thickness inward is inside; as far outward is outside.
      const Eigen::Vector3d mid = fin.point(r, xc, 0, delta);
      const Eigen::Vector3d half_in = 0.5 * (on + mid), out = on + 0.5 * (on - mid);
      EXPECT_TRUE(query.inside(half_in));
      EXPECT_FALSE(query.inside(out));
      EXPECT_EQ(fin.contains(half_in, delta), true);
      EXPECT_EQ(fin.contains(out, delta), false);
    }
  }
}

TEST(SurfaceQuery, RejectsAnOpenSurface) {
  const MyringProfile profile(remus().hull);
  auto mesh = hull_surface(profile, kCb, {0.02});
  CGAL::Euler::remove_face(mesh.halfedge(*mesh.faces().begin()), mesh);
  EXPECT_THROW(SurfaceQuery{mesh}, GeometryError);
}
