// SPDX-License-Identifier: GPL-3.0-or-later
// The fin grid against the analytic NACA 0012 fin: closed positive cells, outward patches, a flat
// tip wall, and wall area and enclosed volume converging at second order to closed-form values
// (Abbott & von Doenhoff's thickness polynomial, integrated here independently of geometry/).
#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "auvloop/geometry/fin.hpp"
#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/fin_grid.hpp"
#include "grid_checks.hpp"

using namespace auvloop;
using namespace auvloop::mesher;
using ::testing::HasSubstr;

namespace {
geometry::FinGeometry first_fin() {
  static const geometry::Vehicle v = geometry::preset_vehicle("remus100");
  return {v.fin_set, v.fin_set.fins.front(), v.mass.cb_station};
}

FinGridSpec small_spec(int chordwise) {
  FinGridSpec s;
  s.chordwise_cells = chordwise;
  s.normal_cells = 8;
  s.embedded_cells = 2;
  s.span_cells = 8;
  s.cap_cells = 4;
  s.first_cell = 5e-4;
  s.extent = 0.02;
  s.cap_height = 0.02;
  return s;
}

// NACA 00tt with the closed trailing edge in u = sqrt(x/c): x = u^2 and the thickness
// y = 5 t (0.2969 u - 0.1260 u^2 - 0.3516 u^4 + 0.2843 u^6 - 0.1036 u^8), a polynomial.
double y_of(double t, double u) {
  return 5 * t *
         (0.2969 * u - 0.1260 * u * u - 0.3516 * std::pow(u, 4) + 0.2843 * std::pow(u, 6) -
          0.1036 * std::pow(u, 8));
}
double dy_du(double t, double u) {
  return 5 * t *
         (0.2969 - 0.2520 * u - 1.4064 * std::pow(u, 3) + 1.7058 * std::pow(u, 5) -
          0.8288 * std::pow(u, 7));
}
// Section area per chord^2: int_0^1 2 y dx, term by term.
double section_area(double t) {
  return 10 * t * (0.2969 * 2 / 3 - 0.1260 / 2 - 0.3516 / 3 + 0.2843 / 4 - 0.1036 / 5);
}

// Area of both sides of a ruled piece between similar sections, per unit integral of chord over
// the span: |P_u x P_rho| / c = sqrt(x_u^2 + y_u^2 + (x_u c' y - y_u (le' + c' x))^2).
double side_factor(double t, double dc, double dle) {
  return 2 *
         geometry::integrate(
             [&](double u) {
               const double x = u * u, xu = 2 * u, y = y_of(t, u), yu = dy_du(t, u);
               return std::sqrt(xu * xu + yu * yu + std::pow(xu * dc * y - yu * (dle + dc * x), 2));
             },
             0.0, 1.0, 200);
}

struct Measures {
  double area = 0, volume = 0;
};

Measures exact_fin(const geometry::FinGeometry& fin) {
  const auto& s = fin.set();
  const double t = s.section.thickness_percent / 100.0, cr = s.root_chord, ct = s.tip_chord;
  const double dc = (ct - cr) / s.span, dle = std::tan(s.sweep);
  Measures m;
  m.area = side_factor(t, 0, 0) * cr * s.embed_depth +
           side_factor(t, dc, dle) * 0.5 * (cr + ct) * s.span + section_area(t) * ct * ct;
  m.volume =
      section_area(t) * (cr * cr * s.embed_depth + s.span * (cr * cr + cr * ct + ct * ct) / 3);
  return m;
}

// Wall area, and the volume enclosed by the wall closed with the flat polygon at the inner end
// (whose outward area vector is the wall's area-vector sum, the wall facing into the fin).
Measures grid_fin(const geometry::FinGeometry& fin, const Grid& g, const GridGeometry& geo) {
  const Patch& wall = test::patch_named(g, fin.name());
  const Eigen::Vector3d cap = test::patch_area_vector(geo, wall);
  const Eigen::Vector3d on_cap = fin.post_origin() + fin.inner_radius() * fin.span_axis();
  return {test::patch_area(geo, wall), test::enclosed_volume(geo, wall) + cap.dot(on_cap) / 3};
}
}  // namespace

TEST(FinGrid, CellsAreClosedPositiveAndTheTipIsAWall) {
  const auto fin = first_fin();
  const FinGridSpec s = small_spec(12);
  const Grid g = fin_grid(fin, s);
  const GridGeometry geo = compute_geometry(g);
  ASSERT_NO_THROW(validate(g, geo));
  EXPECT_EQ(test::inward_boundary_faces(g, geo), 0);
  // O-grid: 2 m points round the sharp section; column: m strips above the tip.
  const int span = s.embedded_cells + s.span_cells + s.cap_cells;
  EXPECT_EQ(g.cells,
            span * s.normal_cells * 2 * s.chordwise_cells + s.cap_cells * s.chordwise_cells);
  // The wall's open end is the flat inner section: its area vector points along -span only.
  const Eigen::Vector3d cap = test::patch_area_vector(geo, test::patch_named(g, fin.name()));
  EXPECT_LT((cap + cap.norm() * fin.span_axis()).norm(), 1e-12 * cap.norm());
  // The tip wall: wall faces in the tip plane, facing the fin (-span), area = tip polygon.
  double tip_area = 0;
  const Patch& wall = test::patch_named(g, fin.name());
  for (int f = wall.start; f < wall.start + wall.size; ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const double rho = (geo.face_centre[fs] - fin.post_origin()).dot(fin.span_axis());
    if (std::abs(rho - fin.set().tip_radius) < 1e-12) {
      EXPECT_LT((geo.face_area[fs].normalized() + fin.span_axis()).norm(), 1e-12);
      tip_area += geo.face_area[fs].norm();
    }
  }
  const double ct = fin.set().tip_chord;
  // Inscribed in the convex section, so smaller than it (its accuracy is covered by the
  // convergence test below); the lower limit only rules out a missing or partial tip.
  EXPECT_LT(tip_area, section_area(0.12) * ct * ct);
  EXPECT_GT(tip_area, 0.9 * section_area(0.12) * ct * ct);
}

// Chords of a convex section: the polygonal wall converges at second order. Doubling the
// chordwise count must cut the area and volume errors by about 4 (at least 3).
TEST(FinGrid, WallAreaAndVolumeConvergeAtSecondOrder) {
  const auto fin = first_fin();
  const Measures exact = exact_fin(fin);
  double prev_a = 0, prev_v = 0;
  for (int m : {8, 16, 32}) {
    const Grid g = fin_grid(fin, small_spec(m));
    const Measures got = grid_fin(fin, g, compute_geometry(g));
    const double ea = std::abs(got.area - exact.area) / exact.area;
    const double ev = std::abs(got.volume - exact.volume) / exact.volume;
    std::printf(
        "fin grid, %d chordwise cells: wall area %.6e m^2 (exact %.6e, rel. error %.2e), "
        "volume %.6e m^3 (exact %.6e, rel. error %.2e)\n",
        m, got.area, exact.area, ea, got.volume, exact.volume, ev);
    if (prev_a > 0) {
      EXPECT_GT(prev_a / ea, 3.0);
      EXPECT_GT(prev_v / ev, 3.0);
    }
    prev_a = ea;
    prev_v = ev;
  }
}

TEST(FinGrid, PlacementTurnsAboutThePost) {
  const auto fin = first_fin();
  const double d = 30 * std::numbers::pi / 180;
  const Eigen::Isometry3d t = fin_placement(fin, d);
  for (double x : {0.0, 0.3, 1.0}) {
    const Eigen::Vector3d p0 = fin.point(0.08, x, 1, 0.0), p1 = fin.point(0.08, x, 1, d);
    EXPECT_LT((t * p0 - p1).norm(), 1e-14);
  }
}

TEST(FinGrid, BadSettingsNameTheSetting) {
  const auto fin = first_fin();
  const auto error = [&](auto edit) {
    FinGridSpec s = small_spec(8);
    edit(s);
    try {
      (void)fin_grid(fin, s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error([](auto& s) { s.span_cells = -2; }), HasSubstr("span_cells"));
  EXPECT_THAT(error([](auto& s) { s.chordwise_cells = 1; }), HasSubstr("chordwise_cells"));
  EXPECT_THAT(error([](auto& s) { s.first_cell = 0.05; }), HasSubstr("first_cell (0.05 m)"));
}
