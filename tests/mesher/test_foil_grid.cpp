// SPDX-License-Identifier: GPL-3.0-or-later
// The 2D foil grids (foil_grid.hpp): all three valid with their documented patches; the wall
// points on the NACA section; the single grid the O-grid continued (the same cells near the
// foil); the O-grid over the background assembled without orphans at pitch angles up to 15
// degrees, the background's cells inside the section holes; bad settings named.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "auvloop/mesher/foil_grid.hpp"
#include "auvloop/mesher/mesh_report.hpp"
#include "auvloop/mesher/overset.hpp"

using namespace auvloop::mesher;

namespace {
int patch_size(const Grid& g, const std::string& name) {
  for (const auto& p : g.patches)
    if (p.name == name) return p.size;
  return -1;
}
FoilOversetSpec coarse() {
  FoilOversetSpec s;
  s.chordwise_cells = 24;
  s.trailing_edge_fan = 8;
  s.normal_cells = 16;
  s.first_cell = 4e-3;
  return s;
}
}  // namespace

TEST(FoilGrids, AreValidWithTheirPatchesAndTheWallOnTheSection) {
  const auto s = coarse();
  const auto g = foil_grids(s);
  for (const Grid* grid : {&g.foil, &g.background, &g.single}) {
    const auto geo = compute_geometry(*grid);
    EXPECT_NO_THROW(validate(*grid, geo)) << grid->name;
    double worst = 0;
    for (double a : cell_non_orthogonality(*grid, geo)) worst = std::max(worst, a);
    EXPECT_LT(worst, 65.0) << grid->name;  // degrees: beside the trailing-edge fan
  }
  const int lines = 2 * s.chordwise_cells + s.trailing_edge_fan;  // round the loop
  EXPECT_EQ(g.foil.cells, lines * s.normal_cells);
  EXPECT_GT(g.single.cells, g.foil.cells);
  // The wall: 2 m + 1 distinct points per level, so as many wall faces as segments between them.
  EXPECT_EQ(patch_size(g.foil, "foil"), 2 * s.chordwise_cells);
  EXPECT_EQ(patch_size(g.foil, "outer"), lines);
  EXPECT_EQ(patch_size(g.single, "far"), lines);
  EXPECT_EQ(patch_size(g.background, "west"), patch_size(g.background, "east"));
  // Every wall face's points lie on the section (pivot at the origin, unit chord).
  const auto& wall = g.foil.patches[0];
  for (int i = 0; i < wall.size; ++i)
    for (int k = 0; k < g.foil.face_size(wall.start + i); ++k) {
      const auto& x = g.foil.points[static_cast<std::size_t>(g.foil.face_point(wall.start + i, k))];
      const double xc = x.x() + s.pivot;
      ASSERT_GE(xc, -1e-12);
      ASSERT_LE(xc, 1 + 1e-12);
      EXPECT_NEAR(std::abs(x.y()), s.section.half_thickness(std::clamp(xc, 0.0, 1.0)), 1e-9);
    }
  // The single grid begins with the O-grid: the same cell centres in the same order.
  const auto a = compute_geometry(g.foil), b = compute_geometry(g.single);
  double shift = 0;
  for (std::size_t c = 0; c < static_cast<std::size_t>(g.foil.cells); ++c)
    shift = std::max(shift, (a.cell_centre[c] - b.cell_centre[c]).norm());
  EXPECT_LT(shift, 1e-12);
}

TEST(FoilGrids, TheOGridAssemblesOverTheBackgroundAtEveryPitchAngle) {
  auto g = foil_grids(coarse());
  OversetAssembler assembler({{&g.foil, 1, g.solid.get()}, {&g.background, 0, nullptr}});
  for (double deg : {0.0, 5.0, -10.0, 15.0}) {
    g.foil.placement = Eigen::Isometry3d(
        Eigen::AngleAxisd(deg * std::numbers::pi / 180, Eigen::Vector3d::UnitZ()));
    const auto a = assembler.assemble();
    EXPECT_EQ(a.grids[0].count(CellStatus::orphan) + a.grids[1].count(CellStatus::orphan), 0)
        << deg;
    EXPECT_EQ(a.grids[0].count(CellStatus::hole), 0) << deg;
    EXPECT_GT(a.grids[0].count(CellStatus::fringe), 0) << deg;
    EXPECT_GT(a.grids[1].count(CellStatus::hole), 0) << deg;
    // The background cell at the pivot (inside the section) is a hole.
    const int inside = assembler.locate(1, {0.1, 0.0, 0.05});
    ASSERT_GE(inside, 0);
    EXPECT_EQ(a.grids[1].status[static_cast<std::size_t>(inside)], CellStatus::hole) << deg;
    EXPECT_TRUE(a.warnings.empty()) << deg << ": " << a.warnings.front();
  }
}

// A background too coarse for the cover rule is legal but not an overset system: the O-grid
// covers none of its cells, only those inside the section are holes. The assembly says so.
TEST(FoilGrids, ABackgroundTheOGridCannotCoverIsNamed) {
  auto s = coarse();
  // 0.16 chords: six background centres fall inside the section, but the cover rule needs 3.5
  // of these sizes inside the O-grid's active region (less than one chord); at 0.14 the O-grid
  // covers background cells.
  s.spacing = 0.16;
  auto g = foil_grids(s);
  OversetAssembler assembler({{&g.foil, 1, g.solid.get()}, {&g.background, 0, nullptr}});
  const auto a = assembler.assemble();
  EXPECT_GT(a.grids[1].count(CellStatus::hole), 0);  // the cells inside the section
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("overset grid 1"), std::string::npos) << a.warnings[0];
  EXPECT_NE(a.warnings[0].find("but no other grid covers"), std::string::npos) << a.warnings[0];
  // At 0.2 chords no background centre falls inside the section at all: the body is invisible.
  s.spacing = 0.2;
  auto h = foil_grids(s);
  OversetAssembler blind({{&h.foil, 1, h.solid.get()}, {&h.background, 0, nullptr}});
  const auto b = blind.assemble();
  EXPECT_EQ(b.grids[1].count(CellStatus::hole), 0);
  ASSERT_EQ(b.warnings.size(), 1u);
  EXPECT_NE(b.warnings[0].find("overset grid 0"), std::string::npos) << b.warnings[0];
  EXPECT_NE(b.warnings[0].find("passes through the body"), std::string::npos) << b.warnings[0];
}

TEST(FoilGrids, BadSettingsAreNamed) {
  auto s = coarse();
  s.outer_radius = 0.5;  // the trailing edge lies 0.75 chords from the pivot
  try {
    (void)foil_grids(s);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("outer_radius"), std::string::npos) << e.what();
  }
  s = coarse();
  s.core_side = 0.8;
  EXPECT_THROW((void)foil_grids(s), std::invalid_argument);
}
