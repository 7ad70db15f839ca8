// SPDX-License-Identifier: GPL-3.0-or-later
// Overset grids that turn against each other (fv::MovingOverset, Overset::set_orientation,
// Pimple's re-assembly stage overset_transition.cpp): a vector interpolated across turned axes
// arrives in the receiver's axes; a uniform stream seen from a box turning in its background
// converges to the exact turning vector at second order in time; a cylinder's O-grid swinging
// about an off-centre pivot (its hole moving through the background, cells coming out of it)
// keeps every fringe cell at its donors' interpolation and runs bitwise alike on one and two
// threads.
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/engine/fv/moving_overset.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {

Eigen::Isometry3d turn_about(const Eigen::Vector3d& pivot, double angle) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity();
  a.translate(pivot).rotate(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())).translate(-pivot);
  return a;
}

// The coarse Schaefer-Turek pair as a moving system: the O-grid (component 0) over the channel.
std::unique_ptr<fv::MovingOverset> cylinder_pair() {
  mesher::CylinderOversetSpec spec;
  spec.around = 32;
  spec.radial_cells = 8;
  spec.downstream_cells = 16;
  auto pair = mesher::cylinder_overset(spec);
  std::vector<fv::MovingOverset::Component> c;
  c.push_back({std::move(pair.cylinder), 1, std::move(pair.solid)});
  c.push_back({std::move(pair.background), 0, nullptr});
  return std::make_unique<fv::MovingOverset>(std::move(c));
}

mesher::Grid square(double half, int n, const std::string& name, mesher::PatchType sides) {
  mesher::BoxPatches patches;
  patches.names = {"west", "east", "south", "north", "front", "back"};
  patches.types = {sides, sides, sides, sides, mesher::PatchType::empty, mesher::PatchType::empty};
  return mesher::cartesian_box(mesher::graded_nodes(-half, half, n),
                               mesher::graded_nodes(-half, half, n),
                               mesher::graded_nodes(0, 0.1, 1), patches, name);
}

}  // namespace

TEST(OversetMotion, AVectorFromTurnedAxesArrivesInTheReceiversAxes) {
  auto sys = cylinder_pair();
  const Eigen::Vector3d centre(0.2, 0.2, 0);
  const double angle = 0.5;
  sys->place(0, turn_about(centre, angle));
  sys->reassemble();
  const auto& ov = sys->overset();
  const auto& mesh = sys->mesh();
  ASSERT_TRUE(ov.turned());
  const Eigen::Vector3d v(1.0, -0.4, 0.0);  // one vector, resolved in each grid's axes
  const Eigen::Matrix3d R = sys->axes(0).linear();
  std::array<std::vector<double>, 3> u;
  for (auto& ui : u) ui.assign(static_cast<std::size_t>(mesh.cells()), 0.0);
  for (int c = 0; c < mesh.cells(); ++c) {
    const Eigen::Vector3d own = ov.component_of(c) == 0 ? Eigen::Vector3d(R.transpose() * v) : v;
    for (std::size_t i = 0; i < 3; ++i)
      u[i][static_cast<std::size_t>(c)] = own[static_cast<Eigen::Index>(i)];
  }
  auto expected = u;
  for (int c : ov.fringe_cells())  // spoil the fringe values: apply must restore them
    for (auto& ui : u) ui[static_cast<std::size_t>(c)] = 7.0;
  ov.apply(std::array<std::span<double>, 3>{u[0], u[1], u[2]});
  double worst = 0;
  int across = 0;
  for (int c : ov.fringe_cells())
    for (std::size_t i = 0; i < 3; ++i)
      worst = std::max(worst, std::abs(u[i][static_cast<std::size_t>(c)] -
                                       expected[i][static_cast<std::size_t>(c)]));
  for (int c : ov.fringe_cells()) across += ov.component_of(c) == 0 ? 1 : 0;
  EXPECT_GT(across, 0);
  EXPECT_LT(worst, 1e-12);
  // Without the orientation the O-grid's fringe would take the background's components as they
  // are: the test sees it.
  sys->overset().set_orientation(std::vector<Eigen::Matrix3d>(2, Eigen::Matrix3d::Identity()));
  ov.apply(std::array<std::span<double>, 3>{u[0], u[1], u[2]});
  double wrong = 0;
  for (int c : ov.fringe_cells())
    wrong = std::max(wrong, std::abs(u[0][static_cast<std::size_t>(c)] -
                                     expected[0][static_cast<std::size_t>(c)]));
  EXPECT_GT(wrong, 0.1);
}

// A box turning at a constant rate about the background's centre, with no solid (so it covers
// nothing: the background is the stream's, the box takes its fringe from it), in a uniform
// stream U: in the box's axes the exact velocity is R(t)^T U, which obeys du/dt = -Omega x u (the
// rotation source) while the fringe gets R(t)^T U from the interpolation. BDF2 must converge to
// it at second order; a vector not turned into the box's axes, or a wrong grid motion, leaves
// an O(1) error.
TEST(OversetMotion, AStreamSeenFromATurningBoxTurnsAtSecondOrder) {
  const Eigen::Vector3d stream(1.0, 0.3, 0.0);
  const double rate = 1.0, end = 0.6;
  auto error = [&](int steps) {
    std::vector<fv::MovingOverset::Component> c;
    c.push_back({square(0.6, 16, "box", mesher::PatchType::overset), 1, nullptr});
    c.push_back({square(2.0, 32, "background", mesher::PatchType::inlet), 0, nullptr});
    fv::MovingOverset sys(std::move(c));
    fv::PimpleSettings s;
    s.nu = 1e-2;
    s.dt = end / steps;
    s.outer_iterations = 6;
    s.tolerance = 1e-12;
    fv::Pimple flow(sys.mesh(), s);
    flow.set_overset(&sys.overset());
    for (const char* side : {"west", "east", "south", "north"})
      flow.far_field(std::string("background/") + side);
    for (std::size_t i = 0; i < 3; ++i)
      std::fill(flow.U.c[i].cells.begin(), flow.U.c[i].cells.end(),
                stream[static_cast<Eigen::Index>(i)]);
    fv::FrameMotion body;
    body.stream = stream;
    const Eigen::Vector3d spin(0, 0, rate), centre = Eigen::Vector3d::Zero();
    flow.set_motion({fv::placed_motion(body, sys.axes(0), spin, centre), body});
    flow.initialise();
    for (int k = 1; k <= steps; ++k) {
      sys.place(0, turn_about(centre, rate * k * s.dt));
      sys.reassemble();
      flow.set_motion({fv::placed_motion(body, sys.axes(0), spin, centre), body});
      flow.step();
    }
    const Eigen::Vector3d exact = sys.axes(0).linear().transpose() * stream;
    double e = 0;
    for (int cell : sys.overset().active_cells())
      e = std::max(
          e, (flow.U.cell(cell) - (sys.overset().component_of(cell) == 0 ? exact : stream)).norm());
    return e;
  };
  const double coarse = error(12), fine = error(24);
  EXPECT_LT(coarse, 2e-2);  // of |U| = 1.04 m/s, turned by 0.6 rad
  EXPECT_GT(std::log2(coarse / fine), 1.8) << coarse << " " << fine;
}

namespace {
struct Swing {
  std::vector<double> u, v, p;
  int came_out = 0;            // cells that left a hole over the run
  int reported_out = 0;        // the same, as the steps report it
  double fringe_mismatch = 0;  // |U - interpolation| over the fringe after the last step
  double continuity = 0;       // the largest continuity error of a step
};

// The O-grid swinging about a pivot 0.05 m upstream of the cylinder's centre (the cylinder's
// hole sweeps through the background) in the Schaefer-Turek channel at Re ~ 20.
Swing swing(int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  auto sys = cylinder_pair();
  fv::PimpleSettings s;
  s.nu = 1e-3;
  s.dt = 0.02;
  s.outer_iterations = 2;
  fv::Pimple flow(sys->mesh(), s);
  flow.set_overset(&sys->overset());
  flow.wall("cylinder/cylinder");
  flow.wall("background/bottom");
  flow.wall("background/top");
  flow.far_field("background/inlet");
  flow.far_field("background/outlet");
  fv::FrameMotion body;
  body.stream = {0.2, 0, 0};
  std::fill(flow.U.c[0].cells.begin(), flow.U.c[0].cells.end(), 0.2);
  const Eigen::Vector3d pivot(0.15, 0.2, 0), spin(0, 0, 2.0);
  flow.set_motion({fv::placed_motion(body, sys->axes(0), spin, pivot), body});
  flow.initialise();
  Swing r;
  for (int k = 1; k <= 10; ++k) {
    std::vector<mesher::CellStatus> before(static_cast<std::size_t>(sys->mesh().cells()));
    for (int c = 0; c < sys->mesh().cells(); ++c)
      before[static_cast<std::size_t>(c)] = sys->overset().status(c);
    sys->place(0, turn_about(pivot, spin.z() * k * s.dt));
    sys->reassemble();
    for (int c = 0; c < sys->mesh().cells(); ++c)
      r.came_out += before[static_cast<std::size_t>(c)] == mesher::CellStatus::hole &&
                    !(sys->overset().status(c) == mesher::CellStatus::hole);
    flow.set_motion({fv::placed_motion(body, sys->axes(0), spin, pivot), body});
    const auto rep = flow.step();
    r.continuity = std::max(r.continuity, rep.continuity_error);
    r.reported_out += rep.uncovered_cells;
  }
  const auto& ov = sys->overset();
  for (int c : ov.fringe_cells()) {
    const Eigen::Vector3d want =
        ov.interpolate({flow.U.c[0].cells, flow.U.c[1].cells, flow.U.c[2].cells}, c);
    r.fringe_mismatch = std::max(r.fringe_mismatch, (flow.U.cell(c) - want).norm());
  }
  r.u = flow.U.c[0].cells;
  r.v = flow.U.c[1].cells;
  r.p = flow.p.cells;
  return r;
}
}  // namespace

TEST(OversetMotion, ASwingingOGridCarriesItsFringeAndIsBitwiseOnOneAndTwoThreads) {
  const auto a = swing(1), b = swing(2);
  EXPECT_GT(a.came_out, 0);  // the hole moved: cells came out of it
  EXPECT_EQ(a.reported_out, a.came_out);
  EXPECT_LT(a.fringe_mismatch, 1e-12);
  EXPECT_LT(a.continuity, 1e-6);
  for (double x : a.u) ASSERT_TRUE(std::isfinite(x));
  EXPECT_TRUE(a.u == b.u && a.v == b.v && a.p == b.p);
}
