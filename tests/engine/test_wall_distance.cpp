// SPDX-License-Identifier: GPL-3.0-or-later
// Wall distance against analytic distances: a channel between two plane walls (exact), a grid
// placed by a rotation and a translation over another grid's wall (the overset case: a component
// grid sees the walls of the others), and a cylinder in a channel, where the wall is a polygon of
// N chords inscribed in the circle of radius R, so the distance from a point at radius r lies
// between r - R and r - R cos(pi / N). The update as grids move: after a component grid with a
// wall turns, the distances are those measured afresh at the new placements (bit for bit) and
// against one tree of every wall in the body frame, only cells near the turned wall are
// re-measured, a whole-system motion re-measures nothing, and the result is the same on 1 and 3
// threads.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/engine/turbulence/wall_distance.hpp"
#include "auvloop/geometry/error.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"
#include "auvloop/mesher/wall_triangles.hpp"

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
  const engine::fv::Mesh* meshes[] = {&mesh};
  const turb::WallDistances walls(meshes);
  const auto d = walls.of(0);
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
  const engine::fv::Mesh mesh_a(a), mesh_b(b);
  const engine::fv::Mesh* meshes[] = {&mesh_a, &mesh_b};
  const turb::WallDistances walls(meshes);
  const auto d = walls.of(1);
  for (int c = 0; c < mesh_b.cells(); ++c) {
    const Eigen::Vector3d p = b.placement * mesh_b.centre(c);
    EXPECT_NEAR(d[static_cast<std::size_t>(c)], p.y(), 1e-14) << "cell " << c;
  }
  // The cube's own (overset) faces are no walls: without the slab there is nothing to measure.
  const engine::fv::Mesh* cube_only[] = {&mesh_b};
  EXPECT_THROW(turb::WallDistances{cube_only}, std::invalid_argument);
}

TEST(WallDistance, AtACylinderItLiesBetweenTheCircleAndItsInscribedPolygonsInnerCircle) {
  mesher::CylinderChannelSpec spec;
  spec.cells_per_side = 8;
  spec.radial_cells = 6;
  spec.downstream_cells = 12;
  const auto grid = mesher::cylinder_channel(spec);
  const engine::fv::Mesh mesh(grid);
  const engine::fv::Mesh* meshes[] = {&mesh};
  const turb::WallDistances walls(meshes);
  const auto d = walls.of(0);
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

namespace {
// A cylinder channel and a "fin": a small box whose y- side is a wall, placed in the channel
// downstream of the cylinder and turned about z by `angle` (rad).
struct TurningFin {
  mesher::Grid channel, fin;
  TurningFin() {
    mesher::CylinderChannelSpec spec;
    spec.cells_per_side = 8;
    spec.radial_cells = 6;
    spec.downstream_cells = 24;
    channel = mesher::cylinder_channel(spec);
    fin = mesher::cartesian_box(mesher::graded_nodes(-0.05, 0.05, 10),
                                mesher::graded_nodes(0, 0.03, 6), mesher::graded_nodes(0, 0.01, 1),
                                patches_with_walls({2}, mesher::PatchType::overset), "fin");
    turn(0);
  }
  void turn(double angle) {
    fin.placement =
        Eigen::Translation3d(0.6, 0.2, 0) * Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ());
  }
};

std::vector<double> as_vector(std::span<const double> d) {
  return {d.begin(), d.end()};
}
}  // namespace

TEST(WallDistances, AfterAFinTurnsTheyAreTheFreshOnesAndOnlyCellsNearTheFinAreReMeasured) {
  TurningFin sys;
  const engine::fv::Mesh channel(sys.channel), fin(sys.fin);
  const engine::fv::Mesh* meshes[] = {&channel, &fin};
  const int cells = channel.cells() + fin.cells();
  turb::WallDistances walls(meshes);
  const auto& first = walls.initial_work();
  EXPECT_EQ(first.pairs, 4);
  EXPECT_EQ(first.bounds, 2L * cells);
  EXPECT_GE(first.queries, cells);  // at least the nearest group of every cell
  for (const double deg : {5.0, 20.0, -30.0}) {
    sys.turn(deg * std::numbers::pi / 180);
    const auto work = walls.update();
    EXPECT_EQ(work.pairs, 2) << "the fin against the channel's walls and back";
    EXPECT_EQ(work.bounds, cells);  // one changed group per cell
    EXPECT_LT(work.queries, cells / 4) << "at " << deg << " deg";
    const turb::WallDistances fresh(meshes);
    // Against one tree of every wall, in the body frame.
    auto triangles = mesher::wall_triangles(sys.channel, sys.channel.placement);
    const auto t = mesher::wall_triangles(sys.fin, sys.fin.placement);
    triangles.insert(triangles.end(), t.begin(), t.end());
    const geometry::TriangleDistance all(triangles);
    for (int g = 0; g < 2; ++g) {
      EXPECT_EQ(as_vector(walls.of(g)), as_vector(fresh.of(g))) << "grid " << g << ", " << deg;
      const auto& mesh = *meshes[g];
      for (int c = 0; c < mesh.cells(); ++c) {
        const Eigen::Vector3d x = mesh.source_grid().placement * mesh.centre(c);
        ASSERT_NEAR(walls.of(g)[static_cast<std::size_t>(c)], all.distance(x), 1e-13)
            << "grid " << g << ", cell " << c << ", " << deg << " deg";
      }
    }
  }
  // The whole system moved rigidly: no relative placement changed, nothing is re-measured.
  const auto before = as_vector(walls.of(1));
  const Eigen::Isometry3d body(Eigen::Translation3d(1, -2, 0.5) *
                               Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  sys.channel.placement = body * sys.channel.placement;
  sys.fin.placement = body * sys.fin.placement;
  const auto work = walls.update();
  EXPECT_EQ(work.pairs, 0);
  EXPECT_EQ(work.queries, 0);
  EXPECT_EQ(as_vector(walls.of(1)), before);
}

TEST(WallDistances, WithACellMaskOnlyNeededCellsAreMeasuredAndTheRestLater) {
  TurningFin sys;
  const engine::fv::Mesh channel(sys.channel), fin(sys.fin);
  const engine::fv::Mesh* meshes[] = {&channel, &fin};
  turb::WallDistances walls(meshes);
  sys.turn(0.4);
  // Every other cell needed.
  std::vector<std::vector<char>> needed(2);
  for (int g = 0; g < 2; ++g)
    for (int c = 0; c < meshes[g]->cells(); ++c)
      needed[static_cast<std::size_t>(g)].push_back(c % 2 == 0 ? 1 : 0);
  const auto masked = walls.update(needed);
  const turb::WallDistances fresh(meshes);
  for (int g = 0; g < 2; ++g)
    for (int c = 0; c < meshes[g]->cells(); c += 2)
      ASSERT_EQ(walls.of(g)[static_cast<std::size_t>(c)], fresh.of(g)[static_cast<std::size_t>(c)])
          << "grid " << g << ", cell " << c;
  // Without a mask (every cell needed, nothing moved since): the others are measured now.
  const auto rest = walls.update();
  EXPECT_EQ(rest.pairs, 0);
  EXPECT_GT(rest.queries, 0);
  EXPECT_EQ(as_vector(walls.of(0)), as_vector(fresh.of(0)));
  EXPECT_EQ(as_vector(walls.of(1)), as_vector(fresh.of(1)));
  needed[1].pop_back();
  EXPECT_THROW((void)walls.update(needed), std::invalid_argument);
  EXPECT_GT(masked.queries, 0);
}

TEST(WallDistances, AreTheSameOnOneAndThreeThreads) {
  TurningFin sys;
  sys.turn(0.3);
  const engine::fv::Mesh channel(sys.channel), fin(sys.fin);
  const engine::fv::Mesh* meshes[] = {&channel, &fin};
  const auto distances = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    const turb::WallDistances walls(meshes);
    return std::pair{as_vector(walls.of(0)), as_vector(walls.of(1))};
  };
  EXPECT_EQ(distances(1), distances(3));
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

// The same system merged into one composite mesh (as the flow solver runs it): each component's
// cells see every component's walls through its axes relative to where it was merged, and the
// distances are those of the grids taken apart, before and after the fin turns.
TEST(WallDistances, OnACompositeMeshTheyAreThoseOfItsGridsTakenApart) {
  TurningFin sys;
  const mesher::Grid* grids[] = {&sys.channel, &sys.fin};
  const auto composite = mesher::composite_grid(grids);
  const engine::fv::Mesh merged(composite.grid);
  turb::WallDistances walls(merged, composite.cell_offset);
  const Eigen::Isometry3d fin0 = sys.fin.placement;
  for (const double deg : {0.0, 20.0, -30.0}) {
    sys.turn(deg * std::numbers::pi / 180);
    const std::vector<Eigen::Isometry3d> axes{Eigen::Isometry3d::Identity(),
                                              sys.fin.placement * fin0.inverse()};
    if (deg != 0.0) (void)walls.update(axes);
    const engine::fv::Mesh channel(sys.channel), fin(sys.fin);
    const engine::fv::Mesh* meshes[] = {&channel, &fin};
    const turb::WallDistances apart(meshes);
    const auto all = walls.composite();
    ASSERT_EQ(all.size(), static_cast<std::size_t>(merged.cells()));
    for (int g = 0; g < 2; ++g)
      for (int c = 0; c < meshes[g]->cells(); ++c) {
        const auto at =
            static_cast<std::size_t>(composite.cell_offset[static_cast<std::size_t>(g)] + c);
        ASSERT_NEAR(all[at], apart.of(g)[static_cast<std::size_t>(c)], 1e-13)
            << "grid " << g << ", cell " << c << ", " << deg << " deg";
      }
  }
  EXPECT_THROW((void)walls.update(), std::invalid_argument);  // a composite needs its axes
  const std::vector<Eigen::Isometry3d> one{Eigen::Isometry3d::Identity()};
  EXPECT_THROW((void)walls.update(one), std::invalid_argument);
}
