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
#include "fin_reference.hpp"
#include "grid_checks.hpp"

using namespace auvloop;
using namespace auvloop::mesher;
using ::testing::HasSubstr;

namespace {
geometry::FinGeometry first_fin() {
  static const geometry::Vehicle v = geometry::preset_vehicle("remus100");
  return {v.fin_set, v.fin_set.fins.front(), geometry::MyringProfile(v.hull), v.mass.cb_station};
}

FinGridSpec small_spec(int chordwise) {
  FinGridSpec s;
  s.chordwise_cells = chordwise;
  s.normal_cells = 8;
  s.span_cells = 8;
  s.cap_cells = 4;
  s.first_cell = 5e-4;
  s.extent = 0.02;
  s.cap_height = 0.02;
  return s;
}

// Wall area, and the volume the (closed) wall encloses.
test::Measures grid_fin(const geometry::FinGeometry& fin, const Grid& g, const GridGeometry& geo) {
  const Patch& wall = test::patch_named(g, fin.name());
  return {test::patch_area(geo, wall), test::enclosed_volume(geo, wall)};
}

test::Measures exact(const geometry::FinGeometry& fin) {
  return test::exact_fin(fin.set(),
                         geometry::MyringProfile(geometry::preset_vehicle("remus100").hull));
}
}  // namespace

TEST(FinGrid, CellsAreClosedPositiveAndTheTipIsAWall) {
  const auto fin = first_fin();
  const FinGridSpec s = small_spec(12);
  const Grid g = fin_grid(fin, s);
  const GridGeometry geo = compute_geometry(g);
  ASSERT_NO_THROW(validate(g, geo));
  EXPECT_EQ(test::inward_boundary_faces(g, geo), 0);
  // O-grid: 2 m lines round the sharp section plus the trailing-edge fan, in every layer and
  // level; columns: m strips in each level below the root face and above the tip. There are at
  // least gap_cells levels below the root face and span_cells up to the tip (more where the wall
  // cells grow to their size).
  const int lines = 2 * s.chordwise_cells + s.trailing_edge_fan;
  EXPECT_GE(g.cells, s.normal_cells * lines * (s.gap_cells + s.span_cells + s.cap_cells) +
                         s.chordwise_cells * (s.gap_cells + s.cap_cells));
  // The wall is closed (sides, root face, tip): its area vectors sum to zero.
  const Eigen::Vector3d sum = test::patch_area_vector(geo, test::patch_named(g, fin.name()));
  EXPECT_LT(sum.norm(), 1e-12 * test::patch_area(geo, test::patch_named(g, fin.name())));
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
  EXPECT_LT(tip_area, test::section_area(0.12) * ct * ct);
  EXPECT_GT(tip_area, 0.9 * test::section_area(0.12) * ct * ct);
}

// Chords of a convex section: the polygonal wall converges at second order. Doubling the
// chordwise count must cut the area and volume errors by about 4 (at least 3).
TEST(FinGrid, WallAreaAndVolumeConvergeAtSecondOrder) {
  const auto fin = first_fin();
  const test::Measures want = exact(fin);
  double prev_a = 0, prev_v = 0;
  for (int m : {8, 16, 32}) {
    const Grid g = fin_grid(fin, small_spec(m));
    const test::Measures got = grid_fin(fin, g, compute_geometry(g));
    const double ea = std::abs(got.area - want.area) / want.area;
    const double ev = std::abs(got.volume - want.volume) / want.volume;
    std::printf(
        "fin grid, %d chordwise cells: wall area %.6e m^2 (exact %.6e, rel. error %.2e), "
        "volume %.6e m^3 (exact %.6e, rel. error %.2e)\n",
        m, got.area, want.area, ea, got.volume, want.volume, ev);
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
