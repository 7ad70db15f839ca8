// SPDX-License-Identifier: GPL-3.0-or-later
// fv::VehicleOverset on the REMUS coarse system (issue 17): after the fins turn (the mesher's
// incremental update), a uniform body-frame velocity stored in every grid's own axes arrives
// in every fringe cell in that cell's axes (a missing turn of a fin's axes would be off by the
// deflection); fin k's axes are its post rotation by d_k - d0_k; the motions turn each fin
// about its post (zero grid velocity on the post, rate x arm off it); bad input is rejected and
// a rejected update keeps the coupling; every wall face belongs to an active cell, the hull's
// wall area is the Myring profile's (faceted), the fins' equal, at rest and turned; a run with the
// fins turning is bitwise the same on one and two threads; a stored assembly naming a donor off
// its grid is refused.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/engine/fv/vehicle_overset.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

using namespace auvloop;
using namespace auvloop::engine;

namespace {
constexpr double kDeg = std::numbers::pi / 180;

fv::VehicleOverset remus_coarse() {
  const auto vehicle = geometry::preset_vehicle("remus100");
  return fv::VehicleOverset(
      mesher::build_grid_system(vehicle, mesher::mesh_preset("coarse", vehicle)), vehicle);
}

// The largest |interpolated - expected| over every fringe cell of a body-frame u stored in each
// component's axes (u_k = Q_k^T u_body).
double turned_mismatch(const fv::VehicleOverset& sys, const Eigen::Vector3d& u_body) {
  const auto& ov = sys.overset();
  const int n = sys.mesh().cells();
  std::array<std::vector<double>, 3> u;
  for (auto& c : u) c.resize(static_cast<std::size_t>(n));
  const auto axes = [&](int component) -> Eigen::Matrix3d {
    const int k = component - 1;
    if (k < 0 || k >= sys.fins()) return Eigen::Matrix3d::Identity();
    return sys.fin_axes(k).linear();
  };
  for (int c = 0; c < n; ++c) {
    const Eigen::Vector3d v = axes(ov.component_of(c)).transpose() * u_body;
    for (std::size_t i = 0; i < 3; ++i)
      u[i][static_cast<std::size_t>(c)] = v[static_cast<Eigen::Index>(i)];
  }
  double worst = 0;
  for (int c : ov.fringe_cells()) {
    const Eigen::Vector3d got = ov.interpolate({u[0], u[1], u[2]}, c);
    const Eigen::Vector3d want = axes(ov.component_of(c)).transpose() * u_body;
    worst = std::max(worst, (got - want).norm());
  }
  return worst;
}
}  // namespace

TEST(VehicleOverset, TurnedFinsCarryVectorsIntoEveryFringeCellsAxes) {
  auto sys = remus_coarse();
  ASSERT_EQ(sys.fins(), 4);
  EXPECT_EQ(sys.background_component(), 5);
  const Eigen::Vector3d u_body(1.54, -0.2, 0.1);
  EXPECT_LT(turned_mismatch(sys, u_body), 1e-12);
  const std::vector<double> d{10 * kDeg, -20 * kDeg, 5 * kDeg, 30 * kDeg};
  const auto& a = sys.set_fins(d);
  // The coarse preset's assembly warns (the background is never covered by the hull grid, the
  // hull grid by the fin grids): reported, not a failure of the coupling (docs/overset-flow.md).
  for (const auto& w : a.warnings) std::printf("  %s\n", w.c_str());
  EXPECT_EQ(sys.deflections(), d);
  for (const auto& g : a.grids) EXPECT_EQ(g.count(mesher::CellStatus::orphan), 0);
  EXPECT_LT(turned_mismatch(sys, u_body), 1e-10);
  // Fin k's axes: its post rotation by d_k (merged at 0), the post point fixed.
  for (int k = 0; k < sys.fins(); ++k) {
    const auto& fin = sys.system().fin_geometry[static_cast<std::size_t>(k)];
    const Eigen::Isometry3d q = sys.fin_axes(k);
    EXPECT_LT((q.linear() - fin.rotation(d[static_cast<std::size_t>(k)])).norm(), 1e-14) << k;
    EXPECT_LT((q * fin.post_origin() - fin.post_origin()).norm(), 1e-14) << k;
  }
  // Without the fins' orientation the same field is off by the deflections.
  std::vector<Eigen::Matrix3d> none(6, Eigen::Matrix3d::Identity());
  sys.overset().set_orientation(none);
  EXPECT_GT(turned_mismatch(sys, u_body), 0.1);
}

TEST(VehicleOverset, MotionsTurnEachFinAboutItsPost) {
  const auto sys = remus_coarse();
  fv::FrameMotion body;  // at rest in a stream
  body.stream = {-1.54, 0, 0};
  const std::vector<double> rates{0.5, -0.5, 0.25, 0};
  const auto m = sys.motions(body, rates);
  ASSERT_EQ(m.size(), 6u);
  EXPECT_TRUE(m[0].at_rest());
  EXPECT_TRUE(m[5].at_rest());
  for (int k = 0; k < sys.fins(); ++k) {
    const auto& fin = sys.system().fin_geometry[static_cast<std::size_t>(k)];
    const auto& mk = m[static_cast<std::size_t>(fv::VehicleOverset::fin_component(k))];
    const double rate = rates[static_cast<std::size_t>(k)];
    const Eigen::Vector3d on_post = fin.post_origin() + 0.08 * fin.span_axis();
    EXPECT_LT(mk.at(on_post).norm(), 1e-14) << k;
    const Eigen::Vector3d arm = 0.02 * fin.chord_axis();
    EXPECT_NEAR(mk.at(on_post + arm).norm(), std::abs(rate) * 0.02, 1e-14) << k;
    EXPECT_LT((mk.at(on_post + arm) - rate * fin.span_axis().cross(arm)).norm(), 1e-14) << k;
    EXPECT_LT((mk.stream - body.stream).norm(), 1e-14) << k;  // merged at 0: axes = body's
  }
  EXPECT_THROW((void)sys.motions(body, {0.1}), std::invalid_argument);
}

// Output: the grid ParaView shows has each fin grid turned to its deflection (its points by
// fin_axes, the others where they were), and locate() finds the grid a point is in the flow of.
TEST(VehicleOverset, PlacedGridTurnsTheFinsAndLocateFindsTheCellInTheFlow) {
  auto sys = remus_coarse();
  const std::vector<double> d{20 * kDeg, -10 * kDeg, 5 * kDeg, 0.0};
  sys.set_fins(d);
  const auto placed = sys.placed_grid();
  const auto& merged = sys.composite().grid;
  ASSERT_EQ(placed.points.size(), merged.points.size());
  std::size_t first = sys.system().hull.points.size();
  for (std::size_t i = 0; i < first; ++i) ASSERT_EQ(placed.points[i], merged.points[i]);
  for (int k = 0; k < sys.fins(); ++k) {
    const auto n = sys.system().fins[static_cast<std::size_t>(k)].points.size();
    double worst = 0;
    for (std::size_t i = first; i < first + n; ++i)
      worst = std::max(worst, (placed.points[i] - sys.fin_axes(k) * merged.points[i]).norm());
    EXPECT_LT(worst, 1e-15) << k;
    first += n;
  }
  // The upper rudder turned by 20 deg: its trailing edge moved sideways by about chord x sin 20.
  double moved = 0;
  for (std::size_t i = sys.system().hull.points.size(); i < first; ++i)
    moved = std::max(moved, (placed.points[i] - merged.points[i]).norm());
  EXPECT_GT(moved, 0.01);
  for (std::size_t i = first; i < placed.points.size(); ++i)
    ASSERT_EQ(placed.points[i], merged.points[i]);  // the background
  // Inside the hull no grid has a cell in the flow; far off the body only the background
  // does; next to the hull's wall the hull grid's active cell.
  EXPECT_EQ(sys.locate({0.0, 0.0, 0.0}), -1);
  const int far = sys.locate({0.0, 0.0, 0.5});
  ASSERT_GE(far, 0);
  EXPECT_EQ(sys.overset().component_of(far), sys.background_component());
  const int near = sys.locate({0.0, 0.0, 0.191 / 2 + 0.003});  // 3 mm off the mid-body
  ASSERT_GE(near, 0);
  EXPECT_EQ(sys.overset().component_of(near), 0);
  EXPECT_TRUE(sys.overset().active(near));
}

TEST(VehicleOverset, BadDeflectionsAreRejectedKeepingTheCoupling) {
  auto sys = remus_coarse();
  const auto before = sys.assembly().grids[0].status;
  EXPECT_THROW((void)sys.set_fins({0.1, 0.2}), std::invalid_argument);
  EXPECT_EQ(sys.assembly().grids[0].status, before);
  EXPECT_EQ(sys.deflections(), std::vector<double>(4, 0.0));
}

// A checkpoint's assembly is checked before it is used: a record whose stencil names a donor cell
// that does not exist is refused naming the grid and the entry, and the coupling is kept; the
// record as written loads.
TEST(VehicleOverset, AStoredAssemblyWithADonorOffTheGridIsRefused) {
  auto sys = remus_coarse();
  (void)sys.set_fins({0.05, 0, 0, 0});
  const auto write = [&](int bad_cell) {
    StateWriter out;
    out.tag("overset assembly");
    out.put(sys.deflections());
    out.put(static_cast<std::int64_t>(sys.assembly().grids.size()));
    for (auto g : sys.assembly().grids) {
      if (bad_cell >= 0 && !g.stencil_cells.empty()) {
        g.stencil_cells.front() = bad_cell;
        bad_cell = -1;
      }
      out.put(g.status);  // the record's order (vehicle_overset.cpp)
      out.put(g.donor_grid);
      out.put(g.donor_cell);
      out.put(g.fallback);
      out.put(g.chained);
      out.put(g.stencil_offsets);
      out.put(g.stencil_grids);
      out.put(g.stencil_cells);
      out.put(g.stencil_weights);
    }
    return out.bytes();
  };
  auto fresh = remus_coarse();
  const auto before = fresh.assembly().grids[0].status;
  StateReader bad(write(1 << 30), "bad");
  try {
    fresh.load(bad);
    ADD_FAILURE() << "a donor off the grid was loaded";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_EQ(fresh.assembly().grids[0].status, before);
  StateReader good(write(-1), "good");
  fresh.load(good);
  EXPECT_EQ(fresh.deflections(), sys.deflections());
  EXPECT_EQ(fresh.assembly().grids[1].stencil_cells, sys.assembly().grids[1].stencil_cells);
}

// Forces per grid (issue 17, item 4): the hull's and each fin's wall patches are disjoint by
// construction (a fin stands a gap off the hull, its root face a wall of its own grid), so the
// force on each patch counts every wall face once, provided no wall face belongs to a hole or
// fringe cell (whose values are not the flow's there). Checked at rest and at turned fins; the
// hull's wall area against the Myring profile's (side integral plus nose and tail faces: the
// faceted wall lies inside the exact one, 40 facets round: (pi/40)^2/6 = 0.1 % below, plus the
// chords along the profile); the four identical fins' areas equal and unchanged by turning.
TEST(VehicleOverset, EveryWallFaceIsAnActiveCellsSoEachPatchCountsItsWallOnce) {
  auto sys = remus_coarse();
  const auto vehicle = geometry::preset_vehicle("remus100");
  const geometry::MyringProfile hull(vehicle.hull);
  const int n = 100000;
  const double length = hull.length(), dx = length / n;
  double exact =
      std::numbers::pi * (std::pow(hull.radius(0), 2) + std::pow(hull.radius(length), 2));
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * dx, r = hull.radius(x), s = hull.slope(x);
    exact += 2 * std::numbers::pi * r * std::sqrt(1 + s * s) * dx;
  }
  const auto wall_area = [&](const std::string& name) {
    const auto& m = sys.mesh();
    for (const auto& p : m.grid().patches) {
      if (p.name != name) continue;
      double area = 0;
      for (int i = 0; i < p.size; ++i) {
        const int f = p.start + i;
        EXPECT_TRUE(sys.overset().active(m.owner(f))) << name << " face " << f;
        area += m.area(f).norm();
      }
      return area;
    }
    ADD_FAILURE() << "no patch " << name;
    return 0.0;
  };
  double fin0 = 0;
  for (const auto& d : {std::vector<double>(4, 0.0),
                        std::vector<double>{30 * kDeg, -30 * kDeg, 20 * kDeg, -20 * kDeg}}) {
    sys.set_fins(d);
    const double a = wall_area(fv::VehicleOverset::hull_wall());
    EXPECT_LT(a, exact);
    EXPECT_GT(a, 0.995 * exact) << a << " against " << exact;
    for (int k = 0; k < sys.fins(); ++k) {
      const double f = wall_area(sys.fin_wall(k));
      if (fin0 == 0) fin0 = f;
      EXPECT_NEAR(f, fin0, 1e-12 * fin0) << k;
    }
  }
  EXPECT_GT(fin0, 0);
}

// The REMUS system with every fin turning (the mesher's update each step, cells coming out of
// holes, the fins' axes turning, the bordered mass balance), laminar and with SST as
// remus-overset-sst runs it (k and omega on the coupling, the wall distances followed, U by
// limited linear upwind, the ambient sources, k and omega by Gauss-Seidel BiCGSTAB): the fields
// after 2 straight and 3 turning steps are bitwise the same on one and on two threads.
class FinsTurning : public testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(VehicleOverset, FinsTurning, testing::Values(false, true),
                         [](const auto& p) { return p.param ? "Sst" : "Laminar"; });
TEST_P(FinsTurning, RunIsBitwiseTheSameOnOneAndTwoThreads) {
  const auto run = [this](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(threads));
    validation::RemusOversetRun r;
    r.straight = 2 * r.dt;
    r.turning = 3 * r.dt;
    r.outer_iterations = 2;
    r.keep_fields = true;
    r.sst = GetParam();
    if (r.sst) {
      r.convection = fv::Convection::linear_upwind_limited;
      r.ambient_sources = true;
      r.turbulence_solver = fv::AsymmetricMethod::bicgstab_gs;
    }
    return validation::remus_overset(r);
  };
  const auto a = run(1), b = run(2);
  ASSERT_TRUE(a.failure.empty()) << a.failure;
  ASSERT_EQ(a.steps, 5);
  std::printf("%d status changes over the turning steps, %d cells out of a hole\n",
              a.status_changes, a.uncovered_cells);
  EXPECT_GT(a.status_changes, 0);
  EXPECT_TRUE(a.U == b.U && a.p == b.p && a.phi == b.phi);
  EXPECT_EQ(a.drag, b.drag);
}
