// SPDX-License-Identifier: GPL-3.0-or-later
// The revolved hull grid against the exact Myring body: closed positive cells, prisms on the
// axis, outward patches, end faces equal to the inscribed polygons, and wall area and enclosed
// volume within the bounds of an inscribed polyhedron.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/hull_grid.hpp"
#include "grid_checks.hpp"

using namespace auvloop;
using namespace auvloop::mesher;
using ::testing::HasSubstr;

namespace {
const geometry::Vehicle& remus() {
  static const geometry::Vehicle v = geometry::preset_vehicle("remus100");
  return v;
}

HullGridSpec small_spec() {
  HullGridSpec s;
  s.nose_face_cells = 4;
  s.body_cells = 40;
  s.tail_face_cells = 3;
  s.circumferential = 16;
  s.normal_cells = 10;
  s.first_cell = 1e-3;
  s.extent = 0.06;
  return s;
}

// Largest |r''| and curvature of the profile on [s0, s1], from slope differences at 21 points.
struct ProfileBounds {
  double max_r2 = 0, max_kappa = 0;
};
ProfileBounds profile_bounds(const geometry::MyringProfile& p, double s0, double s1) {
  ProfileBounds b;
  constexpr int n = 20;
  const double d = std::max((s1 - s0) / n, 1e-7);
  for (int k = 0; k <= n; ++k) {
    const double s = s0 + (s1 - s0) * k / n;
    const double a = std::max(0.0, s - 0.5 * d), c = std::min(p.length(), s + 0.5 * d);
    const double r2 = std::abs((p.slope(c) - p.slope(a)) / (c - a));
    b.max_r2 = std::max(b.max_r2, r2);
    b.max_kappa = std::max(b.max_kappa, r2 / std::pow(1 + std::pow(p.slope(s), 2), 1.5));
  }
  return b;
}

// The wall's meridian: (station, radius) of the wall points in the first sector's half-angle
// plane and on the axis, from the nose-face centre round to the tail-face centre.
std::vector<Eigen::Vector2d> wall_meridian(const Grid& g, const Patch& wall, double cb, int n) {
  std::vector<bool> seen(g.points.size(), false);
  std::vector<Eigen::Vector2d> m;
  for (int f = wall.start; f < wall.start + wall.size; ++f) {
    for (int k = 0; k < g.face_size(f); ++k) {
      const auto p = static_cast<std::size_t>(g.face_point(f, k));
      if (seen[p]) continue;
      seen[p] = true;
      const auto& x = g.points[p];
      const double r = std::hypot(x.y(), x.z());
      if (r == 0 || std::abs(std::atan2(x.z(), x.y()) - std::numbers::pi / n) < 1e-9)
        m.emplace_back(cb - x.x(), r);
    }
  }
  const double end =
      std::max_element(m.begin(), m.end(), [](auto& a, auto& b) { return a.x() < b.x(); })->x();
  std::sort(m.begin(), m.end(), [&](auto& a, auto& b) {
    const auto key = [&](const Eigen::Vector2d& q) {
      return std::pair(q.x(), q.x() == end ? -q.y() : q.y());
    };
    return key(a) < key(b);
  });
  return m;
}

// Closed-form measures of the wall polyhedron (planar trapezoids between rings, N-gon end
// faces), and the exact-body deficits of the revolved meridian polyline with their bounds.
struct Polyhedron {
  double area = 0, volume = 0;              // of the polyhedron
  double frustum_area = 0, lin_volume = 0;  // of the revolved polyline (circular rings)
  double area_bound = 0, volume_bound = 0;  // polyline deficits against the exact body
};
Polyhedron polyhedron(const geometry::MyringProfile& p, const std::vector<Eigen::Vector2d>& m,
                      int n) {
  Polyhedron q;
  const double dth = 2 * std::numbers::pi / n, pi = std::numbers::pi;
  for (std::size_t i = 0; i + 1 < m.size(); ++i) {
    const double ds = m[i + 1].x() - m[i].x(), ra = m[i].y(), rb = m[i + 1].y();
    const double chord = std::hypot(ds, rb - ra);
    const double slant = std::hypot(ds, std::cos(dth / 2) * (rb - ra));
    q.area += n * (ra + rb) * std::sin(dth / 2) * slant;
    q.volume += 0.5 * n * std::sin(dth) * ds * (ra * ra + ra * rb + rb * rb) / 3;
    q.frustum_area += pi * (ra + rb) * chord;
    q.lin_volume += pi * ds * (ra * ra + ra * rb + rb * rb) / 3;
    if (ds == 0) continue;  // flat end faces are exact
    const auto b = profile_bounds(p, m[i].x(), m[i + 1].x());
    const double rmax = std::max(ra, rb) + ds * ds * b.max_r2 / 8;
    const double sagitta = ds * ds * b.max_r2 / 8;  // |r - r_lin| on the segment
    const double arc_excess = chord * std::pow(b.max_kappa * chord, 2) / 24;
    q.volume_bound += pi * ds * 2 * rmax * sagitta;
    q.area_bound += 2 * pi * ((chord + arc_excess) * sagitta + rmax * arc_excess);
  }
  return q;
}
}  // namespace

TEST(HullGrid, CellsAreClosedPositiveAndPrismsLineTheAxis) {
  const geometry::MyringProfile profile(remus().hull);
  const HullGridSpec s = small_spec();
  const Grid g = hull_grid(profile, remus().mass.cb_station, s);
  const GridGeometry geo = compute_geometry(g);
  ASSERT_NO_THROW(validate(g, geo));  // positive volumes, closure <= 1e-9 (round-off)
  const int ni = s.nose_face_cells + s.body_cells + s.tail_face_cells + 2 * s.rim_fan;
  EXPECT_EQ(g.cells, ni * s.normal_cells * s.circumferential);
  EXPECT_EQ(test::inward_boundary_faces(g, geo), 0);
  // Triangles only where the revolved wall-normal lines collapse on the axis: the j = const faces
  // of the axis prisms, (normal_cells + 1) per sector at each end. No face has zero area.
  int triangles = 0;
  double min_area = 1e300;
  for (int f = 0; f < g.faces(); ++f) {
    triangles += g.face_size(f) == 3;
    min_area = std::min(min_area, geo.face_area[static_cast<std::size_t>(f)].norm());
  }
  // The rim fans' first-layer cells add one triangle per fan line and sector on each rim.
  EXPECT_EQ(triangles, 2 * (s.normal_cells + 1 + s.rim_fan) * s.circumferential);
  EXPECT_GT(min_area, 0.0);
  // Both patches are closed surfaces (the wall encloses the body, the outer boundary the grid).
  for (const auto& p : g.patches) {
    EXPECT_LT(test::patch_area_vector(geo, p).norm(), 1e-12 * test::patch_area(geo, p)) << p.name;
  }
}

TEST(HullGrid, EndFacesAreTheInscribedPolygons) {
  const geometry::MyringProfile profile(remus().hull);
  const double cb = remus().mass.cb_station;
  const HullGridSpec s = small_spec();
  const Grid g = hull_grid(profile, cb, s);
  const GridGeometry geo = compute_geometry(g);
  const Patch& wall = test::patch_named(g, "hull");
  // Flat faces of an N-gon of circumradius r: (N / 2) r^2 sin(2 pi / N), to round-off.
  const auto face_area_at = [&](double x) {
    double a = 0;
    for (int f = wall.start; f < wall.start + wall.size; ++f)
      if (std::abs(geo.face_centre[static_cast<std::size_t>(f)].x() - x) < 1e-12)
        a += geo.face_area[static_cast<std::size_t>(f)].norm();
    return a;
  };
  const int n = s.circumferential;
  const double polygon = 0.5 * n * std::sin(2 * std::numbers::pi / n);
  const double r_nose = profile.radius(0), r_tail = profile.radius(profile.length());
  EXPECT_NEAR(face_area_at(cb), polygon * r_nose * r_nose, 1e-14);
  EXPECT_NEAR(face_area_at(cb - profile.length()), polygon * r_tail * r_tail, 1e-14);
}

// The wall is a polyhedron inscribed in the convex body. Its area and volume (from the grid's
// face geometry) equal the closed-form polyhedron of its meridian points to round-off; that
// polyhedron differs from the revolved meridian polyline by exactly the chord factors of the
// N-gon, and the polyline from the exact body by at most the chord sagitta h^2 |r''| / 8 and the
// arc excess h (kappa h)^2 / 24 of each segment.
void expect_inscribed(const HullGridSpec& s, double area_limit) {
  const geometry::MyringProfile profile(remus().hull);
  const double cb = remus().mass.cb_station;
  const auto exact = geometry::hull_properties(profile);
  const Grid g = hull_grid(profile, cb, s);
  const GridGeometry geo = compute_geometry(g);
  const Patch& wall = test::patch_named(g, "hull");
  const double area = test::patch_area(geo, wall), volume = test::enclosed_volume(geo, wall);
  const auto m = wall_meridian(g, wall, cb, s.circumferential);
  ASSERT_EQ(static_cast<int>(m.size()), s.nose_face_cells + s.body_cells + s.tail_face_cells + 1);
  const Polyhedron poly = polyhedron(profile, m, s.circumferential);
  EXPECT_NEAR(area, poly.area, 1e-12 * area);  // round-off of the face decomposition
  EXPECT_NEAR(volume, poly.volume, 1e-12 * volume);
  const double area_exact = exact.wetted_area_curved + exact.end_face_area;
  const double da = area_exact - poly.frustum_area, dv = exact.volume - poly.lin_volume;
  EXPECT_GE(da, 0.0);  // chords of a convex profile: inside and shorter
  EXPECT_LE(da, poly.area_bound);
  EXPECT_GE(dv, 0.0);
  EXPECT_LE(dv, poly.volume_bound);
  std::printf(
      "hull grid %d cells: wall area %.6f m^2 (exact %.6f, rel. error %.3e; polyline deficit "
      "%.3e <= bound %.3e), volume %.7f m^3 (exact %.7f, rel. error %.3e; polyline deficit %.3e "
      "<= bound %.3e)\n",
      g.cells, area, area_exact, (area_exact - area) / area_exact, da, poly.area_bound, volume,
      exact.volume, (exact.volume - volume) / exact.volume, dv, poly.volume_bound);
  EXPECT_LE((area_exact - area) / area_exact, area_limit);
}

// The small grid has only 16 sectors: the N-gon factor alone costs (dtheta)^2 / 24 = 0.64 % of
// the area, so the 0.5 % acceptance applies to the medium preset (validation test).
TEST(HullGrid, WallIsAnInscribedPolyhedron) {
  expect_inscribed(small_spec(), 0.01);
}

namespace {
HullGridSpec zone_spec() {
  HullGridSpec s = small_spec();
  s.circumferential = 32;
  s.fins = 4;
  s.fin_angle = -0.5 * std::numbers::pi;  // a fin up (-z)
  s.fin_clustering = 0.5;
  s.fin_zone_begin = 1.19;  // the REMUS fins' planform
  s.fin_zone_end = 1.30;
  s.fin_zone_share = 0.3;
  s.fin_zone_ramp = 0.1;
  return s;
}

// Stations of the wall rings on the curved hull (the points off the axis and off the end faces).
std::vector<double> wall_ring_stations(const Grid& g, double cb, double length) {
  std::vector<double> st;
  const Patch& wall = test::patch_named(g, "hull");
  for (int f = wall.start; f < wall.start + wall.size; ++f)
    for (int k = 0; k < g.face_size(f); ++k) {
      const double s = cb - g.points[static_cast<std::size_t>(g.face_point(f, k))].x();
      if (s > 1e-9 && s < length - 1e-9) st.push_back(s);
    }
  std::sort(st.begin(), st.end());
  st.erase(std::unique(st.begin(), st.end(), [](double a, double b) { return b - a < 1e-12; }),
           st.end());
  return st;
}

// Largest spacing of the rings whose midpoints lie in [a, b].
double largest_spacing(const std::vector<double>& st, double a, double b) {
  double h = 0;
  for (std::size_t i = 0; i + 1 < st.size(); ++i)
    if (0.5 * (st[i] + st[i + 1]) >= a && 0.5 * (st[i] + st[i + 1]) <= b)
      h = std::max(h, st[i + 1] - st[i]);
  return h;
}

// Polar angles (from +y towards +z) of the wall points of the ring nearest a station.
std::vector<double> ring_angles(const Grid& g, double cb, double station) {
  double best = 1e300;
  for (const auto& x : g.points)
    if (std::hypot(x.y(), x.z()) > 0) best = std::min(best, std::abs(cb - x.x() - station));
  std::vector<std::pair<double, double>> ring;  // (radius, angle)
  for (const auto& x : g.points)
    if (std::abs(std::abs(cb - x.x() - station) - best) < 1e-12 && std::hypot(x.y(), x.z()) > 0)
      ring.emplace_back(std::hypot(x.y(), x.z()), std::atan2(x.z(), x.y()));
  const double r0 = std::min_element(ring.begin(), ring.end())->first;  // the wall ring
  std::vector<double> angles;
  for (const auto& [r, a] : ring)
    if (r < r0 * (1 + 1e-12)) angles.push_back(a);
  std::sort(angles.begin(), angles.end());
  return angles;
}
}  // namespace

// The stern zone takes 30 % of the body cells and clusters the sectors at the fins there only:
// valid cells, rings about twice as close over the fins as without the zone, the sectors at a fin
// narrowed by the closed form in the zone and uniform well ahead of it.
TEST(HullGrid, SternZoneRefinesOnlyNearTheFins) {
  const geometry::MyringProfile profile(remus().hull);
  const double cb = remus().mass.cb_station, L = profile.length();
  const HullGridSpec s = zone_spec();
  const Grid g = hull_grid(profile, cb, s);
  const GridGeometry geo = compute_geometry(g);
  ASSERT_NO_THROW(validate(g, geo));
  EXPECT_EQ(test::inward_boundary_faces(g, geo), 0);

  HullGridSpec plain = s;
  plain.fin_zone_end = plain.fin_zone_begin;  // no zone: clustering everywhere, no band
  const auto with = wall_ring_stations(g, cb, L);
  const auto without = wall_ring_stations(hull_grid(profile, cb, plain), cb, L);
  ASSERT_EQ(with.size(), without.size());
  // 30 % of 40 cells spread over the 0.11 m zone and its ramps (0.21 m of weight) add about 57
  // rings per metre to the 40 per metre of the rim-clustered grid here: 12 mm instead of 25 mm.
  const double ratio = largest_spacing(with, 1.19, 1.30) / largest_spacing(without, 1.19, 1.30);
  EXPECT_GT(ratio, 0.35);
  EXPECT_LT(ratio, 0.6);
  // Mid-body rings are 1 / (1 - 0.3) = 1.43 times farther apart.
  EXPECT_NEAR(largest_spacing(with, 0.5, 0.7) / largest_spacing(without, 0.5, 0.7), 1.43, 0.1);

  const int n = s.circumferential, fins = s.fins;
  const double step = 2 * std::numbers::pi / n;
  const auto width_at_fin = [&](double station) {  // the sector straddling the upper fin plane
    const auto a = ring_angles(g, cb, station);
    EXPECT_EQ(static_cast<int>(a.size()), n);
    const auto above = std::lower_bound(a.begin(), a.end(), s.fin_angle);
    return *above - *(above - 1);
  };
  const double clustered = step - 2 * s.fin_clustering * std::sin(fins * step / 2) / fins;
  EXPECT_NEAR(width_at_fin(1.25), clustered, 1e-3 * step);  // ring stations are not exactly 1.25
  EXPECT_NEAR(width_at_fin(0.6), step, 1e-12);
}

namespace {
// Largest ratio of the volumes of two cells that share a face, both touching the wall (a corner
// on the patch "hull": the first layer, and the rim fans' wedges, whose wall edge collapses).
// Away from the wall the cells round a convex corner widen with the distance while those over the
// flat end face do not: a ratio of the corner, not of the wall cells.
double largest_wall_neighbour_volume_ratio(const Grid& g, const GridGeometry& geo) {
  const Patch& wall = test::patch_named(g, "hull");
  std::vector<bool> on_wall(g.points.size(), false), touches(static_cast<std::size_t>(g.cells));
  for (int f = wall.start; f < wall.start + wall.size; ++f)
    for (int k = 0; k < g.face_size(f); ++k)
      on_wall[static_cast<std::size_t>(g.face_point(f, k))] = true;
  for (int f = 0; f < g.faces(); ++f)
    for (int k = 0; k < g.face_size(f); ++k)
      if (on_wall[static_cast<std::size_t>(g.face_point(f, k))]) {
        touches[static_cast<std::size_t>(g.owner[static_cast<std::size_t>(f)])] = true;
        if (f < g.internal_faces())
          touches[static_cast<std::size_t>(g.neighbour[static_cast<std::size_t>(f)])] = true;
      }
  double worst = 1;
  for (int f = 0; f < g.internal_faces(); ++f) {
    const auto o = static_cast<std::size_t>(g.owner[static_cast<std::size_t>(f)]);
    const auto n = static_cast<std::size_t>(g.neighbour[static_cast<std::size_t>(f)]);
    if (!touches[o] || !touches[n]) continue;
    const double a = geo.cell_volume[o], b = geo.cell_volume[n];
    worst = std::max(worst, std::max(a / b, b / a));
  }
  return worst;
}

HullGridSpec filleted_spec() {
  HullGridSpec s = small_spec();
  s.nose_face_cells = 12;
  s.tail_face_cells = 8;
  s.rim_fan = 4;
  s.first_cell = 1e-4;
  s.growth = 1.25;
  s.normal_cells = 0;
  s.rim_radius = 0.005;
  return s;
}
}  // namespace

// Rims rounded by a 5 mm fillet: valid cells with triangles only on the axis (no fan, no wedge),
// every wall point on the rounded body (the end faces, the arcs at 5 mm from their centres,
// tangent to face and hull, or the exact profile), the wall cells next to each arc within 25 % of
// the arc's own (the grading down to it), and neighbouring cells at the wall within a factor of 4
// in volume where the sharp rims' wedges are hundreds of times smaller than the cells beside them.
TEST(HullGrid, FilletedRimsHaveNoWedgeCells) {
  const geometry::MyringProfile profile(remus().hull);
  const double cb = remus().mass.cb_station, L = profile.length();
  const HullGridSpec s = filleted_spec();
  const Grid g = hull_grid(profile, cb, s);
  const GridGeometry geo = compute_geometry(g);
  ASSERT_NO_THROW(validate(g, geo));
  EXPECT_EQ(test::inward_boundary_faces(g, geo), 0);
  int triangles = 0;
  for (int f = 0; f < g.faces(); ++f) triangles += g.face_size(f) == 3;
  const int nj = static_cast<int>(
      g.cells /
      (s.circumferential * (s.nose_face_cells + s.body_cells + s.tail_face_cells + 2 * s.rim_fan)));
  EXPECT_EQ(triangles, 2 * (nj + 1) * s.circumferential);

  auto m = wall_meridian(g, test::patch_named(g, "hull"), cb, s.circumferential);
  ASSERT_EQ(static_cast<int>(m.size()),
            s.nose_face_cells + s.body_cells + s.tail_face_cells + 2 * s.rim_fan + 1);
  // Classify each point: end face, profile, or arc (then its centre is the point minus R times
  // the unit normal, found from the points either side; a single centre per arc).
  int on_face = 0, on_profile = 0, on_arc = 0;
  for (const auto& q : m) {
    if (q.x() == 0 || q.x() == L) {
      ++on_face;
    } else if (std::abs(q.y() - profile.radius(q.x())) < 1e-12) {
      ++on_profile;
    } else {
      ++on_arc;
      EXPECT_TRUE(q.x() < s.rim_radius || q.x() > L - s.rim_radius) << q.x();
      EXPECT_LT(q.y(), profile.radius(q.x()));  // inside the sharp body
    }
  }
  // The arcs' tangent points lie on the face and on the profile; their rim_fan - 1 inner points
  // on neither.
  EXPECT_EQ(on_arc, 2 * (s.rim_fan - 1));
  EXPECT_EQ(on_face, s.nose_face_cells + s.tail_face_cells + 2);
  EXPECT_EQ(on_profile, s.body_cells + 1);
  // Arc points are R from a common centre (the nose arc's first s.rim_fan + 1 points after the
  // face's; centre at x = R, tangent to the face).
  // `slope`: the profile's dr/dx in the meridian's frame (mirrored at the tail).
  const auto arc_check = [&](std::size_t first, double cx, const auto& slope) {
    const double cy = m[first].y();  // the face tangent point has the centre's radius
    for (int k = 0; k <= s.rim_fan; ++k) {
      const auto& q = m[first + static_cast<std::size_t>(k)];
      EXPECT_NEAR(std::hypot(q.x() - cx, q.y() - cy), s.rim_radius, 1e-9) << k;
    }
    // Tangent to the hull: at the arc's last point its radius is normal to the profile, and the
    // wall turns smoothly there (the chords either side within 5 deg of each other: the arc's own
    // cells turn by 10 deg or more, so a kink of the size of the corner would show).
    const auto& t = m[first + static_cast<std::size_t>(s.rim_fan)];
    const Eigen::Vector2d along(1, slope(t.x()));
    EXPECT_NEAR((t - Eigen::Vector2d(cx, cy)).dot(along.normalized()), 0, 1e-9 * s.rim_radius);
    const auto dir = [&](std::size_t i) { return (m[i + 1] - m[i]).normalized().eval(); };
    const std::size_t last = first + static_cast<std::size_t>(s.rim_fan);
    const double turn = std::acos(std::clamp(dir(last - 1).dot(dir(last)), -1.0, 1.0));
    const double arc_turn = std::acos(std::clamp(dir(first).dot(dir(first + 1)), -1.0, 1.0));
    EXPECT_LT(turn, 0.75 * arc_turn) << "a kink where the arc meets the hull";
    // Segment lengths either side of the arc's ends within 25 % of the arc's chords.
    const auto seg = [&](std::size_t i) { return (m[i + 1] - m[i]).norm(); };
    const double arc_cell = seg(first);
    EXPECT_NEAR(seg(first - 1) / arc_cell, 1, 0.25);
    EXPECT_NEAR(seg(first + static_cast<std::size_t>(s.rim_fan)) / arc_cell, 1, 0.25);
  };
  arc_check(static_cast<std::size_t>(s.nose_face_cells), s.rim_radius,
            [&](double x) { return profile.slope(x); });
  // The tail: mirrored (the meridian runs down the tail face at its end).
  std::vector<Eigen::Vector2d> mirrored(m.rbegin(), m.rend());
  for (auto& q : mirrored) q.x() = L - q.x();
  std::swap(m, mirrored);
  arc_check(static_cast<std::size_t>(s.tail_face_cells), s.rim_radius,
            [&](double x) { return -profile.slope(L - x); });

  const double filleted = largest_wall_neighbour_volume_ratio(g, geo);
  HullGridSpec sharp = s;
  sharp.rim_radius = 0;
  const Grid gs = hull_grid(profile, cb, sharp);
  const double wedged = largest_wall_neighbour_volume_ratio(gs, compute_geometry(gs));
  std::printf("largest volume ratio of wall neighbours: filleted %.2f, sharp %.1f\n", filleted,
              wedged);
  EXPECT_LT(filleted, 4.0);
  EXPECT_GT(wedged, 100.0);
}

TEST(HullGrid, BadSettingsNameTheSetting) {
  const geometry::MyringProfile profile(remus().hull);
  const auto error = [&](auto edit) {
    HullGridSpec s = small_spec();
    edit(s);
    try {
      (void)hull_grid(profile, 0.6, s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error([](auto& s) { s.body_cells = -3; }), HasSubstr("body_cells"));
  EXPECT_THAT(error([](auto& s) { s.normal_cells = -1; }), HasSubstr("normal_cells"));
  EXPECT_THAT(error([](auto& s) { s.circumferential = 18; }), HasSubstr("multiple of 4"));
  EXPECT_THAT(error([](auto& s) { s.first_cell = 0.2; }),
              HasSubstr("first_cell (0.2 m) must be smaller than the hull radius"));
  EXPECT_THAT(error([](auto& s) { s.growth = 0.9; }), HasSubstr("growth"));
  EXPECT_THAT(error([](auto& s) { s.fin_zone_share = 1; }), HasSubstr("fin_zone_share"));
  EXPECT_THAT(error([](auto& s) { s.fin_zone_ramp = 0; }), HasSubstr("fin_zone_ramp"));
  EXPECT_THAT(error([](auto& s) { s.rim_radius = -1e-3; }), HasSubstr("rim_radius"));
  EXPECT_THAT(error([](auto& s) { s.rim_radius = 0.05; }),
              HasSubstr("rim_radius (0.05 m) rounds away the whole tail face"));
}
