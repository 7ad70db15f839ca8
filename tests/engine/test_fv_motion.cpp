// SPDX-License-Identifier: GPL-3.0-or-later
// Rigid grid motion in Pimple (motion.hpp): geometric conservation per cell on a grid with warped
// faces; fluid at rest stays at rest, and a uniform current stays uniform, on a grid that moves
// through it; and Galilean invariance on the overset cylinder pair: the cylinder towed through
// fluid at rest against the fixed cylinder in the stream, field by field, and the towed run bitwise
// the same on one and two threads.
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {

// A 6 x 5 x 4 box of graded cells whose inner points are moved at random by up to a fifth of a
// cell (unless !warp), so that its faces are not planar; every side is called "far".
mesher::Grid warped_box(bool warp = true) {
  mesher::BoxPatches patches;
  patches.names = {"far0", "far1", "far2", "far3", "far4", "far5"};
  auto grid = mesher::cartesian_box(mesher::graded_nodes(0, 1.2, 6, 1.3),
                                    mesher::graded_nodes(-0.5, 0.5, 5),
                                    mesher::graded_nodes(0, 0.8, 4), patches, "box");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-0.04, 0.04);
  for (auto& x : grid.points) {
    const bool inner = x.x() > 1e-9 && x.x() < 1.2 - 1e-9 && std::abs(x.y()) < 0.5 - 1e-9 &&
                       x.z() > 1e-9 && x.z() < 0.8 - 1e-9;
    if (inner && warp) x += Eigen::Vector3d(d(rng), d(rng), d(rng));
  }
  return grid;
}

fv::FrameMotion tumbling() {
  fv::FrameMotion m;
  m.velocity = {0.3, -0.1, 0.2};
  m.rate = {0.5, -0.2, 1.0};
  return m;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}
}  // namespace

TEST(FvMotion, GridFluxConservesEveryCellsVolumeOnWarpedFaces) {
  const auto grid = warped_box();
  const fv::Mesh mesh(grid);
  fv::Pimple flow(mesh, {});
  const auto m = tumbling();
  flow.set_motion({m});
  flow.initialise();
  const auto& phi_g = flow.grid_flux();
  ASSERT_EQ(phi_g.size(), static_cast<std::size_t>(mesh.faces()));
  const auto net = fv::div(mesh, phi_g);
  // The face-centre rule (V + Omega x x_f) . S_f, exact on planar faces only: these faces are
  // warped enough for it to leave a volume error, so the test can tell the two apart.
  std::vector<double> naive(phi_g.size());
  for (int f = 0; f < mesh.faces(); ++f)
    naive[static_cast<std::size_t>(f)] = m.at(mesh.face_centre(f)).dot(mesh.area(f));
  const auto naive_net = fv::div(mesh, naive);
  const double scale = 1.5 / 0.2;  // |w| (m/s) over a cell size (m): div's natural size (1/s)
  EXPECT_LT(max_abs(net) / scale, 1e-14);
  EXPECT_GT(max_abs(naive_net) / scale, 1e-6);
}

TEST(FvMotion, FluidAtRestStaysAtRestAndACurrentStaysUniform) {
  const auto grid = warped_box();
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = 1e-2;
  s.dt = 0.05;
  s.outer_iterations = 2;
  s.tolerance = 1e-12;
  auto run = [&](const fv::FrameMotion& m) {
    fv::Pimple flow(mesh, s);
    for (const auto& patch : grid.patches) flow.far_field(patch.name);
    for (std::size_t i = 0; i < 3; ++i)
      std::fill(flow.U.c[i].cells.begin(), flow.U.c[i].cells.end(),
                m.stream[static_cast<Eigen::Index>(i)]);
    flow.set_motion({m});
    flow.initialise();
    for (int k = 0; k < 5; ++k) {
      flow.set_motion({m});
      flow.step();
    }
    double du = 0;
    for (int c = 0; c < mesh.cells(); ++c) du = std::max(du, (flow.U.cell(c) - m.stream).norm());
    return std::pair{du, max_abs(flow.p.cells)};
  };
  // At rest in the Earth frame, the grid translating and turning about all three axes.
  const auto [u_rest, p_rest] = run(tumbling());
  EXPECT_LT(u_rest, 1e-12);
  EXPECT_LT(p_rest, 1e-12);
  // A uniform current through a translating grid (a turning one would see the current's
  // direction change in its axes).
  fv::FrameMotion moving;
  moving.velocity = {-0.4, 0.1, 0.05};
  moving.stream = {0.25, -0.1, 0.3};
  const auto [u_current, p_current] = run(moving);
  EXPECT_LT(u_current, 1e-12);
  EXPECT_LT(p_current, 1e-12);
}

namespace {
// The coarse overset cylinder pair of test_fv_overset, plug inflow U_in; `towed`: the grids
// move at -U_in through fluid at rest, else the cylinder is fixed in the stream (and the channel
// walls slide at U_in, so that both are the same flow seen from two frames).
struct Towing {
  std::vector<Eigen::Vector3d> u;
  std::vector<double> p;
  Eigen::Vector3d force;
};

Towing towing(bool towed, int threads = 2) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  constexpr double U_in = 0.2;
  mesher::CylinderOversetSpec spec;
  spec.around = 32;
  spec.radial_cells = 8;
  spec.downstream_cells = 16;
  const auto pair = mesher::cylinder_overset(spec);
  const auto system = mesher::composite_system(
      {{&pair.cylinder, 1, pair.solid.get()}, {&pair.background, 0, nullptr}});
  const fv::Mesh mesh(system.composite.grid);
  const fv::Overset overset(mesh, system.stencils, system.composite.cell_offset);
  fv::PimpleSettings s;
  s.nu = 1e-3;
  s.dt = 0.02;
  // Outer iterations to convergence: the start is impulsive (the wall's velocity differs from
  // the fluid's), so the first flux is not divergence-free, and the first iteration's convection
  // of U by it, div(phi - phi_g) U, differs between the frames by U_in div(phi - phi_g). The
  // converged iteration does not see it (measured on the single-grid channel after one step: the
  // largest difference 5.8e-4, 2.4e-5 and 1.1e-8 m/s after 3, 10 and 40 outer iterations).
  s.outer_iterations = 40;
  s.relax_u = 0.7;
  s.relax_p = 0.3;
  s.tolerance = 1e-13;
  s.pressure_solver = fv::SymmetricMethod::cg_amg;
  fv::Pimple flow(mesh, s);
  flow.set_overset(&overset);
  const Eigen::Vector3d stream(U_in, 0, 0);
  std::vector<fv::FrameMotion> motion(2);
  for (auto& m : motion) m.velocity = towed ? Eigen::Vector3d(-stream) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d far = towed ? Eigen::Vector3d::Zero() : stream;
  for (const char* side : {"background/bottom", "background/top"}) flow.U.fix(mesh, side, far);
  flow.U.fix(mesh, "background/inlet", far);
  flow.p.fix(mesh, "background/outlet", 0.0);
  flow.wall("cylinder/cylinder");
  // The same start seen from both frames: the fluid at rest (towed) is the stream (fixed).
  for (std::size_t i = 0; i < 3; ++i)
    std::fill(flow.U.c[i].cells.begin(), flow.U.c[i].cells.end(),
              far[static_cast<Eigen::Index>(i)]);
  flow.set_motion(motion);
  flow.initialise();
  for (int k = 0; k < 2; ++k) {
    flow.set_motion(motion);
    flow.step();
  }
  Towing t;
  for (int c : overset.active_cells()) {
    t.u.push_back(flow.U.cell(c) - (towed ? motion[0].velocity : Eigen::Vector3d::Zero()));
    t.p.push_back(flow.p.cells[static_cast<std::size_t>(c)]);
  }
  t.force = fv::patch_force(flow, "cylinder/cylinder").total();
  return t;
}
}  // namespace

TEST(FvMotion, ATowedCylinderIsTheFixedCylinderInAStream) {
  const auto fixed = towing(false), towed = towing(true);
  ASSERT_EQ(fixed.u.size(), towed.u.size());
  double du = 0, dp = 0, p_scale = 0;
  for (std::size_t i = 0; i < fixed.u.size(); ++i) {
    du = std::max(du, (fixed.u[i] - towed.u[i]).norm());
    dp = std::max(dp, std::abs(fixed.p[i] - towed.p[i]));
    p_scale = std::max(p_scale, std::abs(fixed.p[i]));
  }
  // Measured 9.9e-8, 1.3e-7 and 9.9e-8 (the outer loop's convergence after 40 iterations); with
  // 3 outer iterations they are 1e-3.
  EXPECT_LT(du / 0.2, 1e-6);
  EXPECT_LT(dp / p_scale, 1e-6);
  EXPECT_GT(fixed.force.norm(), 0.0);
  EXPECT_LT((fixed.force - towed.force).norm() / fixed.force.norm(), 1e-6);
}

// A uniform current seen from turning axes: u(t) = R(t)^T U_c, which in those axes obeys
// du/dt = -Omega x u, the term motion.hpp adds; the far field is given the exact value every step.
// BDF2 must converge to it at second order (a wrong sign or a missing term leaves an O(1) error).
// On the box with planar faces: with the warped faces the error stops at 2.9e-3 m/s below 12
// steps (2.90e-3, 2.87e-3 at 12, 24 steps; a pressure of 1e-3 m^2/s^2 remains), which is not
// understood yet (docs/cfd.md, "Moving grids").
TEST(FvMotion, ACurrentSeenFromTurningAxesTurnsAtSecondOrder) {
  const auto grid = warped_box(false);
  const fv::Mesh mesh(grid);
  const Eigen::Vector3d rate(0.3, -0.4, 1.2), current(1.0, 0.2, -0.1);
  const double end = 0.6;
  auto exact = [&](double t) -> Eigen::Vector3d {
    return Eigen::AngleAxisd(-rate.norm() * t, rate.normalized()) * current;
  };
  auto error = [&](int steps) {
    fv::PimpleSettings s;
    s.nu = 1e-2;
    s.dt = end / steps;
    s.outer_iterations = 6;  // the explicit -Omega x u converged within each step
    s.tolerance = 1e-12;
    fv::Pimple flow(mesh, s);
    for (const auto& patch : grid.patches) flow.far_field(patch.name);
    for (std::size_t i = 0; i < 3; ++i)
      std::fill(flow.U.c[i].cells.begin(), flow.U.c[i].cells.end(),
                current[static_cast<Eigen::Index>(i)]);
    fv::FrameMotion m;
    m.rate = rate;
    m.stream = exact(0);
    flow.set_motion({m});
    flow.initialise();
    for (int k = 1; k <= steps; ++k) {
      m.stream = exact(k * s.dt);
      flow.set_motion({m});
      flow.step();
    }
    double e = 0;
    for (int c = 0; c < mesh.cells(); ++c) e = std::max(e, (flow.U.cell(c) - exact(end)).norm());
    return e;
  };
  const double coarse = error(12), fine = error(24);
  EXPECT_LT(coarse, 2e-2);  // of |U_c| = 1.02 m/s, turned by 0.78 rad
  EXPECT_GT(std::log2(coarse / fine), 1.8) << coarse << " " << fine;
}

TEST(FvMotion, BitwiseIdenticalForOneAndTwoThreads) {
  const auto a = towing(true, 1), b = towing(true, 2);
  ASSERT_EQ(a.u.size(), b.u.size());
  bool same = a.p == b.p && a.force == b.force;
  for (std::size_t i = 0; i < a.u.size(); ++i) same = same && a.u[i] == b.u[i];
  EXPECT_TRUE(same);
}
