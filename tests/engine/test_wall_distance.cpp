// SPDX-License-Identifier: GPL-3.0-or-later
// Wall distance against analytic distances: a channel between two plane walls (exact), a grid
// placed by a rotation and a translation over another grid's wall (the overset case: a component
// grid sees the walls of the others), and a cylinder in a channel, where the wall is a polygon of
// N chords inscribed in the circle of radius R, so the distance from a point at radius r lies
// between r - R and r - R cos(pi / N).
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "auvloop/engine/turbulence/wall_distance.hpp"
#include "auvloop/geometry/error.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
namespace turb = engine::turbulence;

namespace {
mesher::BoxPatches patches_with_walls(std::initializer_list<int> wall_sides,
                                      mesher::PatchType others) {
  mesher::BoxPatches p;
  p.types.fill(others);
  for (int s : wall_sides) p.types[static_cast<std::size_t>(s)] = mesher::PatchType::wall;
  return p;
}
}  // namespace

TEST(WallDistance, BetweenTwoPlaneWallsItIsTheDistanceToTheNearerOne) {
  const double h = 0.2;
  const auto grid =
      mesher::cartesian_box(mesher::graded_nodes(0, 1, 12, 1.3),
                            mesher::graded_nodes(0, h, 16, 4.0), mesher::graded_nodes(0, 0.1, 3),
                            patches_with_walls({2, 3}, mesher::PatchType::inlet), "channel");
  const engine::fv::Mesh mesh(grid);
  const mesher::Grid* grids[] = {&grid};
  const auto walls = turb::wall_surface(grids);
  const auto d = turb::wall_distance(mesh, walls);
  ASSERT_EQ(d.size(), static_cast<std::size_t>(mesh.cells()));
  for (int c = 0; c < mesh.cells(); ++c) {
    const double y = mesh.centre(c).y();
    EXPECT_NEAR(d[static_cast<std::size_t>(c)], std::min(y, h - y), 1e-14) << "cell " << c;
  }
}

TEST(WallDistance, AComponentGridSeesTheWallsOfTheOthersThroughItsPlacement) {
  // Grid a: a slab with its wall at y = 0 (wide in x and z); grid b: a cube without walls, turned
  // by 30 deg about z and moved to (0.5, 0.4, 0) in the body frame.
  const auto a =
      mesher::cartesian_box(mesher::graded_nodes(0, 1, 8), mesher::graded_nodes(0, 1, 8),
                            mesher::graded_nodes(-0.5, 0.5, 4),
                            patches_with_walls({2}, mesher::PatchType::symmetry), "slab");
  auto b =
      mesher::cartesian_box(mesher::graded_nodes(-0.1, 0.1, 5), mesher::graded_nodes(-0.1, 0.1, 5),
                            mesher::graded_nodes(-0.1, 0.1, 5),
                            patches_with_walls({}, mesher::PatchType::overset), "cube");
  b.placement = Eigen::Translation3d(0.5, 0.4, 0) *
                Eigen::AngleAxisd(std::numbers::pi / 6, Eigen::Vector3d::UnitZ());
  const mesher::Grid* grids[] = {&a, &b};
  const auto walls = turb::wall_surface(grids);
  const engine::fv::Mesh mesh_b(b);
  const auto d = turb::wall_distance(mesh_b, walls);
  for (int c = 0; c < mesh_b.cells(); ++c) {
    const Eigen::Vector3d p = b.placement * mesh_b.centre(c);
    EXPECT_NEAR(d[static_cast<std::size_t>(c)], p.y(), 1e-14) << "cell " << c;
  }
  // The cube's own (overset) faces are no walls: without the slab there is nothing to measure.
  const mesher::Grid* cube_only[] = {&b};
  EXPECT_THROW((void)turb::wall_surface(cube_only), std::invalid_argument);
}

TEST(WallDistance, AtACylinderItLiesBetweenTheCircleAndItsInscribedPolygonsInnerCircle) {
  mesher::CylinderChannelSpec spec;
  spec.cells_per_side = 8;
  spec.radial_cells = 6;
  spec.downstream_cells = 12;
  const auto grid = mesher::cylinder_channel(spec);
  const engine::fv::Mesh mesh(grid);
  const mesher::Grid* grids[] = {&grid};
  const auto d = turb::wall_distance(mesh, turb::wall_surface(grids));
  const int chords = 4 * spec.cells_per_side;
  const double inner = spec.radius * std::cos(std::numbers::pi / chords);
  for (int c = 0; c < mesh.cells(); ++c) {
    const Eigen::Vector3d& x = mesh.centre(c);
    const double r = std::hypot(x.x() - spec.cx, x.y() - spec.cy);
    const double channel = std::min(x.y(), spec.height - x.y());
    const double lo = std::min(channel, r - spec.radius), hi = std::min(channel, r - inner);
    EXPECT_GE(d[static_cast<std::size_t>(c)], lo - 1e-12) << "cell " << c;
    EXPECT_LE(d[static_cast<std::size_t>(c)], hi + 1e-12) << "cell " << c;
  }
}

TEST(TriangleDistance, RejectsAnEmptySetAndSkipsDegenerateTriangles) {
  EXPECT_THROW(geometry::TriangleDistance(std::span<const geometry::Triangle>{}),
               geometry::GeometryError);
  const Eigen::Vector3d o(0, 0, 0), ex(1, 0, 0), ey(0, 1, 0);
  const geometry::Triangle flat{o, ex, ex};  // zero area
  EXPECT_THROW(geometry::TriangleDistance(std::span<const geometry::Triangle>(&flat, 1)),
               geometry::GeometryError);
  const geometry::Triangle set[] = {flat, {o, ex, ey}};
  const geometry::TriangleDistance t(set);
  EXPECT_EQ(t.triangles(), 1);
  EXPECT_DOUBLE_EQ(t.distance({0.25, 0.25, 2.0}), 2.0);
  EXPECT_NEAR(t.distance({-3, 0, 4}), 5.0, 1e-15);  // nearest: the vertex at the origin
  EXPECT_TRUE(t.closest_point({0.2, 0.1, -1}).isApprox(Eigen::Vector3d(0.2, 0.1, 0)));
}
