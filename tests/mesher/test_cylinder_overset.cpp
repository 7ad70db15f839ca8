// SPDX-License-Identifier: GPL-3.0-or-later
// The cylinder-in-a-channel overset pair (cylinder_overset) and its assembly by the general
// OversetAssembler: both grids valid; the background's cells inside the cylinder are holes and
// so are those the O-grid covers; every fringe cell has active donors whose weights reproduce a
// field linear in the plane at its centre (the planar system's stencils), none an orphan; the
// O-grid itself has no holes; a moved O-grid (placement) moves the hole; bad input rejected.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "auvloop/geometry/surface.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/overset.hpp"

using namespace auvloop::mesher;

namespace {
struct Assembled {
  CylinderOverset pair;
  Assembly a;
  explicit Assembled(const CylinderOversetSpec& spec) : pair(cylinder_overset(spec)) {
    OversetAssembler assembler(
        {{&pair.cylinder, 1, pair.solid.get()}, {&pair.background, 0, nullptr}});
    a = assembler.assemble();
  }
};

double radius_of(const Eigen::Vector3d& x, const CylinderOversetSpec& s) {
  return std::hypot(x.x() - s.cx, x.y() - s.cy);
}
}  // namespace

TEST(CylinderOverset, GridsAreValidAndPatchesAsDocumented) {
  const CylinderOversetSpec spec;
  const auto pair = cylinder_overset(spec);
  for (const Grid* g : {&pair.cylinder, &pair.background})
    EXPECT_NO_THROW(validate(*g, compute_geometry(*g))) << g->name;
  EXPECT_EQ(pair.cylinder.cells, spec.around * spec.radial_cells);
  std::vector<std::string> names;
  for (const auto& p : pair.cylinder.patches) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"cylinder", "outer", "front", "back"}));
  EXPECT_EQ(pair.cylinder.patches[0].size, spec.around);
  EXPECT_EQ(pair.cylinder.patches[1].type, PatchType::overset);
  names.clear();
  for (const auto& p : pair.background.patches) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"inlet", "outlet", "bottom", "top", "front", "back"}));
  const auto m = auvloop::geometry::measure(*pair.solid);
  EXPECT_NEAR(m.volume, std::numbers::pi * spec.radius * spec.radius * 3 * spec.thickness,
              1e-4 * m.volume);  // the inscribed prism's, within its chord's area
  EXPECT_TRUE(auvloop::geometry::inspect(*pair.solid).ok());
}

TEST(CylinderOverset, AssemblyCutsTheCylinderAndConnectsEveryFringe) {
  const CylinderOversetSpec spec;
  const Assembled s(spec);
  ASSERT_EQ(s.a.grids.size(), 2U);
  const auto& o = s.a.grids[0];
  const auto& bg = s.a.grids[1];
  EXPECT_EQ(o.count(CellStatus::hole), 0);
  EXPECT_EQ(o.count(CellStatus::orphan) + bg.count(CellStatus::orphan), 0);
  EXPECT_EQ(o.count(CellStatus::fringe), 2 * spec.around);  // two layers at the outer circle
  const auto og = compute_geometry(s.pair.cylinder), bgg = compute_geometry(s.pair.background);
  int inside = 0, covered = 0;
  double outermost_hole = 0;
  for (int c = 0; c < s.pair.background.cells; ++c) {
    const double r = radius_of(bgg.cell_centre[static_cast<std::size_t>(c)], spec);
    const auto st = bg.status[static_cast<std::size_t>(c)];
    if (r < spec.radius) {
      EXPECT_EQ(st, CellStatus::hole) << "background cell " << c << " inside the cylinder";
      ++inside;
    } else if (st == CellStatus::hole) {
      ++covered;
      outermost_hole = std::max(outermost_hole, r);
    }
    if (r > spec.outer_radius) {
      EXPECT_EQ(st, CellStatus::active) << "cell " << c;
    }
  }
  EXPECT_GT(inside, 0);
  EXPECT_GT(covered, 0) << "the O-grid covers part of the background beyond the wall";
  EXPECT_LT(outermost_hole, spec.outer_radius);
  // Stencils: donors active, in the other grid, reproducing a planar linear field.
  const auto f = [](const Eigen::Vector3d& x) { return 1.5 - 2.0 * x.x() + 0.7 * x.y(); };
  for (std::size_t g = 0; g < 2; ++g) {
    const auto& ga = s.a.grids[g];
    const auto& own = g == 0 ? og : bgg;
    for (std::size_t c = 0; c < ga.status.size(); ++c) {
      if (ga.status[c] != CellStatus::fringe) continue;
      double v = 0, wsum = 0;
      for (int k = ga.stencil_offsets[c]; k < ga.stencil_offsets[c + 1]; ++k) {
        const auto ku = static_cast<std::size_t>(k);
        const int dg = ga.stencil_grids[ku];
        ASSERT_NE(dg, static_cast<int>(g));
        const auto& dga = s.a.grids[static_cast<std::size_t>(dg)];
        const auto dc = static_cast<std::size_t>(ga.stencil_cells[ku]);
        ASSERT_EQ(dga.status[dc], CellStatus::active);
        v += ga.stencil_weights[ku] * f((dg == 0 ? og : bgg).cell_centre[dc]);
        wsum += ga.stencil_weights[ku];
      }
      ASSERT_GT(ga.stencil_offsets[c + 1], ga.stencil_offsets[c]) << "grid " << g << " cell " << c;
      EXPECT_NEAR(wsum, 1.0, 1e-12);
      EXPECT_NEAR(v, f(own.cell_centre[c]), 1e-10) << "grid " << g << " cell " << c;
    }
  }
}

TEST(CylinderOverset, MovingTheOGridMovesTheHole) {
  CylinderOversetSpec spec;
  auto pair = cylinder_overset(spec);
  pair.cylinder.placement = Eigen::Translation3d(0.02, -0.01, 0) * Eigen::Isometry3d::Identity();
  OversetAssembler assembler(
      {{&pair.cylinder, 1, pair.solid.get()}, {&pair.background, 0, nullptr}});
  const auto a = assembler.assemble();
  const auto bgg = compute_geometry(pair.background);
  spec.cx += 0.02;
  spec.cy -= 0.01;
  for (int c = 0; c < pair.background.cells; ++c)
    if (radius_of(bgg.cell_centre[static_cast<std::size_t>(c)], spec) < spec.radius) {
      EXPECT_EQ(a.grids[1].status[static_cast<std::size_t>(c)], CellStatus::hole) << c;
    }
  EXPECT_EQ(a.grids[0].count(CellStatus::orphan) + a.grids[1].count(CellStatus::orphan), 0);
}

TEST(CylinderOverset, RejectsBadInput) {
  CylinderOversetSpec spec;
  spec.outer_radius = 0.25;  // beyond the channel's walls
  EXPECT_THROW(cylinder_overset(spec), std::invalid_argument);
  spec = {};
  spec.outer_radius = spec.radius;
  EXPECT_THROW(cylinder_overset(spec), std::invalid_argument);
  const auto pair = cylinder_overset({});
  EXPECT_THROW(OversetAssembler({{&pair.cylinder, 1, pair.solid.get()}}), std::invalid_argument);
  OversetAssembler two({{&pair.cylinder, 1, pair.solid.get()}, {&pair.background, 0, nullptr}});
  EXPECT_THROW(two.assemble({0.1}), std::logic_error);
}

// The unconfined variant: a square box of the stated extent centred on the cylinder, uniform
// cells of the O-grid's outer size in the core growing by at most the stated ratio outside it,
// the four far-field sides named, and an assembly with the cylinder cut out and no orphans.
TEST(CylinderOverset, TheUnconfinedBoxIsCentredGradedAndAssembles) {
  UnconfinedCylinderSpec spec;
  spec.around = 32;
  spec.radial_cells = 16;
  const auto pair = unconfined_cylinder_overset(spec);
  for (const Grid* g : {&pair.cylinder, &pair.background})
    EXPECT_NO_THROW(validate(*g, compute_geometry(*g))) << g->name;
  std::vector<std::string> names;
  for (const auto& p : pair.background.patches) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"west", "east", "south", "north", "front", "back"}));
  double lo = 1e9, hi = -1e9, bottom = 1e9, top = -1e9, smallest = 1e9, largest = 0;
  for (const auto& x : pair.background.points) {
    lo = std::min(lo, x.x());
    hi = std::max(hi, x.x());
    bottom = std::min(bottom, x.y());
    top = std::max(top, x.y());
  }
  const auto g = compute_geometry(pair.background);
  for (int c = 0; c < pair.background.cells; ++c) {
    const double v = g.cell_volume[static_cast<std::size_t>(c)] / (spec.thickness * spec.diameter);
    smallest = std::min(smallest, v);
    largest = std::max(largest, v);
  }
  const double h = 2 * std::numbers::pi * spec.outer_radius / spec.around;
  EXPECT_NEAR(smallest, h * h, 0.05 * h * h);  // the core's cells
  EXPECT_GT(largest, 25 * h * h);              // grown towards the sides
  for (double side : {-lo, hi, -bottom, top}) EXPECT_NEAR(side, 0.5 * spec.extent, 1e-9);
  OversetAssembler assembler(
      {{&pair.cylinder, 1, pair.solid.get()}, {&pair.background, 0, nullptr}});
  const auto a = assembler.assemble();
  EXPECT_EQ(a.grids[0].count(CellStatus::orphan) + a.grids[1].count(CellStatus::orphan), 0);
  EXPECT_GT(a.grids[1].count(CellStatus::hole), 0);
  spec.core_side = 1.0;  // the O-grid (to 1.5 D) no longer fits in the core
  EXPECT_THROW(unconfined_cylinder_overset(spec), std::invalid_argument);
}
