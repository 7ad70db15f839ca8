// SPDX-License-Identifier: GPL-3.0-or-later
// The cylinder-in-a-channel O-grid: the grid invariants hold, the volume is the channel minus the
// inscribed polygon of the cylinder (exactly, since the cylinder wall is made of chords), and the
// patches have the expected sizes.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "auvloop/mesher/cylinder_grid.hpp"

using namespace auvloop::mesher;

TEST(CylinderGrid, ValidWithTheVolumeOfTheChannelMinusThePolygon) {
  CylinderChannelSpec s;
  s.cells_per_side = 8;
  s.radial_cells = 6;
  s.downstream_cells = 10;
  const Grid g = cylinder_channel(s);
  const auto geo = compute_geometry(g);
  EXPECT_NO_THROW(validate(g, geo));
  // Box [0.1, 0.3]^2 with 8 cells per side (spacing 0.025 m): 4 cells to the inlet, 4 below the
  // box, 4 above it (0.11 m); O-grid 4 x 8 x 6, Cartesian blocks 4 x (4 + 8 + 4) + 8 x (4 + 4),
  // downstream 10 x 16.
  EXPECT_EQ(g.cells, 4 * 8 * 6 + 4 * 16 + 8 * 8 + 10 * 16);
  const int n = 4 * s.cells_per_side;  // chords on the cylinder (uniform in angle per quadrant)
  double polygon = 0;
  // Per-quadrant angular spacing differs, so sum the triangles of the actual cylinder faces.
  const auto& cyl = g.patches[3];
  ASSERT_EQ(cyl.name, "cylinder");
  EXPECT_EQ(cyl.size, n);
  for (int i = 0; i < cyl.size; ++i) {
    const int f = cyl.start + i;
    const Eigen::Vector3d a = g.points[static_cast<std::size_t>(g.face_point(f, 0))];
    const Eigen::Vector3d b = g.points[static_cast<std::size_t>(g.face_point(f, 2))];
    const Eigen::Vector2d da(a.x() - s.cx, a.y() - s.cy), db(b.x() - s.cx, b.y() - s.cy);
    polygon += 0.5 * std::abs(da.x() * db.y() - da.y() * db.x());
  }
  EXPECT_NEAR(polygon, std::numbers::pi * s.radius * s.radius, 0.03 * s.radius * s.radius);
  double volume = 0;
  for (double v : geo.cell_volume) volume += v;
  EXPECT_NEAR(volume, (s.length * s.height - polygon) * s.thickness, 1e-12);
  EXPECT_EQ(g.patches[0].size, 16);  // inlet: 4 + 8 + 4
  EXPECT_EQ(g.patches[1].size, 16);  // outlet
  EXPECT_EQ(g.patches[2].size, 2 * (4 + 8 + 10));
  EXPECT_EQ(g.patches[4].size, g.cells);
}
