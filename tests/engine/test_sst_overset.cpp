// SPDX-License-Identifier: GPL-3.0-or-later
// SST k-omega on overset grids (turbulence_model.hpp hooks 8 and 9): k and omega ride on the
// coupling as U does.
// - Free-stream decay through an overset box: in a uniform stream U far from walls (F1 = 0, no
//   strain) the model reduces to U d omega/dx = -beta2 omega^2 and U dk/dx = -beta* k omega,
//   whose solution from the inlet values is analytic (the TMR's free-stream decay,
//   validation/flat_plate.cpp step 4); a box turned by 30 deg over the background, taking its
//   fringe from it, must converge to it like the background alone does. A box whose fringe did
//   not take the background's values would keep an error of order one.
// - The same through a box turning at a constant rate (the grid flux in the scalars'
//   convection, the fringe re-interpolated every step).
// - A cylinder's O-grid swinging through its background with SST: cells that come out of the
//   cylinder's hole take k and omega (and their old levels) from their neighbours, the fringe
//   keeps its donors' values, and the run is bitwise the same on one, two and three threads.
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include <Eigen/Geometry>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/engine/fv/moving_overset.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/turbulence/sst_model.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
namespace fv = engine::fv;
namespace turb = engine::turbulence;

namespace {

Eigen::Isometry3d turn_about(const Eigen::Vector3d& pivot, double angle) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity();
  a.translate(pivot).rotate(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())).translate(-pivot);
  return a;
}

mesher::Grid square(double half, int n, const std::string& name, mesher::PatchType sides) {
  mesher::BoxPatches patches;
  patches.names = {"west", "east", "south", "north", "front", "back"};
  patches.types = {sides, sides, sides, sides, mesher::PatchType::empty, mesher::PatchType::empty};
  return mesher::cartesian_box(mesher::graded_nodes(-half, half, n),
                               mesher::graded_nodes(-half, half, n),
                               mesher::graded_nodes(0, 0.1, 1), patches, name);
}

// The free stream of the decay cases: U along x from the background's west side at x = -2 m.
constexpr double kU = 1.0, kNu = 1e-5, kHalf = 2.0;
constexpr turb::FreeStream kInlet{1e-4, 10.0};  // k (m^2/s^2), omega (1/s): nu_t / nu = 1

// The analytic decay at distance X downstream of the inlet (F1 = 0: beta = beta2).
turb::FreeStream decay(double X) {
  const turb::SstConstants c;
  const double s = 1 + c.beta2 * kInlet.omega * X / kU;
  return {kInlet.k * std::pow(s, -c.beta_star / c.beta2), kInlet.omega / s};
}

turb::SstSettings decay_settings() {
  turb::SstSettings t;
  t.nu = kNu;
  t.freestream = kInlet;
  t.tolerance = 1e-12;
  return t;
}

// The largest relative error of k and of omega over the active cells (x in the background's
// frame: every grid here is placed in it), for the box's and the background's cells apart,
// upstream of the background's last cells (whose zero-gradient outlet makes their error first
// order, the single grid's matter: 6.5e-3 at n = 64, twice that at 32, against 9e-4 elsewhere).
struct DecayError {
  double box = 0, background = 0;
};
DecayError decay_error(const fv::Mesh& mesh, const fv::Overset* ov, const turb::SstModel& sst,
                       const std::function<Eigen::Vector3d(int)>& at) {
  DecayError e;
  for (int c = 0; c < mesh.cells(); ++c) {
    if (ov != nullptr && !ov->active(c)) continue;
    if (at(c).x() > kHalf - 0.25) continue;  // the outlet cells: first order (flat_plate.cpp 4.)
    const auto exact = decay(at(c).x() + kHalf);
    const auto s = static_cast<std::size_t>(c);
    const double err = std::max(std::abs(sst.k.cells[s] / exact.k - 1),
                                std::abs(sst.omega.cells[s] / exact.omega - 1));
    double& into = ov != nullptr && ov->component_of(c) == 0 ? e.box : e.background;
    into = std::max(into, err);
  }
  return e;
}

// Steady SIMPLE on the turned box (or on the background alone), n cells a side of the
// background, n / 2 of the box.
DecayError steady_decay(int n, bool with_box) {
  std::unique_ptr<fv::MovingOverset> sys;
  std::unique_ptr<fv::Mesh> alone;
  auto background = square(kHalf, n, "background", mesher::PatchType::inlet);
  if (with_box) {
    std::vector<fv::MovingOverset::Component> c;
    c.push_back({square(0.6, n / 2, "box", mesher::PatchType::overset), 1, {}});
    c.push_back({std::move(background), 0, nullptr});
    sys = std::make_unique<fv::MovingOverset>(std::move(c));
    sys->place(0, turn_about(Eigen::Vector3d(0.3, 0.1, 0), std::numbers::pi / 6));
    sys->reassemble();
  } else {
    alone = std::make_unique<fv::Mesh>(background);
  }
  const fv::Mesh& mesh = with_box ? sys->mesh() : *alone;
  const fv::Overset* ov = with_box ? &sys->overset() : nullptr;
  fv::PimpleSettings s;
  s.nu = kNu;
  s.steady = true;
  s.relax_u = 0.7;
  s.relax_p = 0.3;
  s.tolerance = 1e-12;
  s.max_courant = 1e30;
  fv::Pimple flow(mesh, s);
  flow.set_overset(ov);
  // Far from any wall: F1 = 0 and F2 = 0 everywhere.
  turb::SstModel sst(mesh, std::vector<double>(static_cast<std::size_t>(mesh.cells()), 1e3),
                     decay_settings());
  flow.set_turbulence(&sst);
  const std::string bg = with_box ? "background/" : "";
  flow.U.fix(mesh, bg + "west", {kU, 0, 0});
  flow.slip(bg + "south");
  flow.slip(bg + "north");
  flow.p.fix(mesh, bg + "east", 0.0);
  sst.inlet(bg + "west");
  std::fill(flow.U.c[0].cells.begin(), flow.U.c[0].cells.end(), kU);
  flow.initialise();
  for (int k = 0; k < 150; ++k) flow.step();
  // The grids' cells are where the composite put them unless the box was turned afterwards.
  const auto at = [&](int cell) -> Eigen::Vector3d {
    const Eigen::Vector3d x = mesh.centre(cell);
    return ov != nullptr && ov->component_of(cell) == 0 ? Eigen::Vector3d(sys->axes(0) * x) : x;
  };
  return decay_error(mesh, ov, sst, at);
}

}  // namespace

TEST(SstOverset, FreeStreamDecayThroughATurnedBoxConvergesToTheAnalyticOne) {
  const auto single = steady_decay(32, false);
  const auto coarse = steady_decay(32, true), fine = steady_decay(64, true);
  std::printf("single %.3e; overset box %.3e background %.3e; fine box %.3e background %.3e\n",
              single.background, coarse.box, coarse.background, fine.box, fine.background);
  EXPECT_LT(coarse.box, single.background);
  EXPECT_LT(coarse.background, 1.5 * single.background);
  EXPECT_GT(std::log2(coarse.box / fine.box), 1.5);
  EXPECT_GT(std::log2(coarse.background / fine.background), 1.5);
}

namespace {
// The box turning at `rate` (rad/s) about (0.3, 0.1) for 0.6 s from the analytic field, n = 32.
DecayError turning_decay(double rate) {
  constexpr int n = 32, steps = 60;
  std::vector<fv::MovingOverset::Component> c;
  c.push_back({square(0.6, n / 2, "box", mesher::PatchType::overset), 1, {}});
  c.push_back({square(kHalf, n, "background", mesher::PatchType::inlet), 0, nullptr});
  fv::MovingOverset sys(std::move(c));
  const fv::Mesh& mesh = sys.mesh();
  const auto& ov = sys.overset();
  fv::PimpleSettings s;
  s.nu = kNu;
  s.dt = 0.01;
  s.outer_iterations = 3;
  s.tolerance = 1e-12;
  fv::Pimple flow(mesh, s);
  flow.set_overset(&ov);
  turb::SstModel sst(mesh, std::vector<double>(static_cast<std::size_t>(mesh.cells()), 1e3),
                     decay_settings());
  flow.set_turbulence(&sst);
  flow.U.fix(mesh, "background/west", {kU, 0, 0});
  flow.slip("background/south");
  flow.slip("background/north");
  flow.p.fix(mesh, "background/east", 0.0);
  sst.inlet("background/west");
  const auto at = [&](int cell) -> Eigen::Vector3d {
    const Eigen::Vector3d x = mesh.centre(cell);
    return ov.component_of(cell) == 0 ? Eigen::Vector3d(sys.axes(0) * x) : x;
  };
  // The exact field to start from (in the box's axes, U turned into them: at rest, identity).
  std::vector<double> k0, w0;
  for (int cell = 0; cell < mesh.cells(); ++cell) {
    const auto e = decay(at(cell).x() + kHalf);
    k0.push_back(e.k);
    w0.push_back(e.omega);
  }
  sst.start_from(k0, w0);
  std::fill(flow.U.c[0].cells.begin(), flow.U.c[0].cells.end(), kU);
  const Eigen::Vector3d pivot(0.3, 0.1, 0), spin(0, 0, rate);
  const fv::FrameMotion still;
  flow.set_motion({fv::placed_motion(still, sys.axes(0), spin, pivot), still});
  flow.initialise();
  for (int k = 1; k <= steps; ++k) {
    sys.place(0, turn_about(pivot, rate * k * s.dt));
    sys.reassemble();
    flow.set_motion({fv::placed_motion(still, sys.axes(0), spin, pivot), still});
    flow.step();
  }
  return decay_error(mesh, &ov, sst, at);
}
}  // namespace

// The box turns by 0.6 rad (34 deg) through the steady field; its cells must carry the field as
// the background does, through the grid flux in the scalars' convection. Without it (the
// absolute flux) the box's field would move with the box: an error of order |w| T |grad omega|
// / omega (measured 9.1e-2 with the absolute flux, against 4.8e-4).
TEST(SstOverset, FreeStreamDecayThroughATurningBoxStaysTheAnalyticOne) {
  const auto still = turning_decay(0.0), turning = turning_decay(1.0);
  std::printf("box at rest %.3e (background %.3e); turning %.3e (background %.3e)\n", still.box,
              still.background, turning.box, turning.background);
  EXPECT_LT(turning.box, 2 * still.box);
  EXPECT_LT(turning.background, 2 * still.background);
}

namespace {
struct SwingSst {
  std::vector<double> u, p, k, omega, nu_t;
  int came_out = 0, came_out_fringe = 0;
  double fringe_mismatch = 0;  // |k - interpolation| / k and the same of omega, over the fringe
  bool positive = true;        // k and omega of every cell in the flow above zero, finite
  // Each cell out of a hole took its donors' k and omega (fringe) or values between its
  // neighbours' (active), in its current and its old level.
  bool filled_right = true;
};

// The coarse Schaefer-Turek pair at Re = 100 on the cylinder's diameter, its O-grid swinging about
// a pivot 0.05 m upstream of the cylinder's centre (test_fv_overset_motion's swing), with SST:
// the wall distance the exact one to the cylinder and the channel's walls at each placement.
SwingSst swing_sst(int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  mesher::CylinderOversetSpec spec;
  spec.around = 32;
  spec.radial_cells = 8;
  spec.downstream_cells = 16;
  auto pair = mesher::cylinder_overset(spec);
  std::vector<fv::MovingOverset::Component> c;
  c.push_back({std::move(pair.cylinder), 1, std::move(pair.solid)});
  c.push_back({std::move(pair.background), 0, nullptr});
  fv::MovingOverset sys(std::move(c));
  const fv::Mesh& mesh = sys.mesh();
  const auto& ov = sys.overset();
  const Eigen::Vector3d centre(spec.cx, spec.cy, 0), pivot(0.1, 0.2, 0), spin(0, 0, 2.0);
  const auto distance = [&] {
    std::vector<double> d(static_cast<std::size_t>(mesh.cells()));
    const Eigen::Vector3d now = sys.axes(0) * centre;  // the cylinder's centre at its placement
    for (int cell = 0; cell < mesh.cells(); ++cell) {
      const Eigen::Vector3d x = ov.component_of(cell) == 0
                                    ? Eigen::Vector3d(sys.axes(0) * mesh.centre(cell))
                                    : mesh.centre(cell);
      const double to_cylinder = std::abs((x - now).head<2>().norm() - spec.radius);
      d[static_cast<std::size_t>(cell)] =
          std::max(1e-6, std::min({to_cylinder, x.y(), spec.height - x.y()}));
    }
    return d;
  };
  fv::PimpleSettings s;
  s.nu = 1e-3;
  s.dt = 0.02;
  s.outer_iterations = 2;
  fv::Pimple flow(mesh, s);
  flow.set_overset(&ov);
  turb::SstSettings ts;
  ts.nu = s.nu;
  ts.freestream = turb::freestream_from_intensity(0.2, 0.05, 10, s.nu);
  turb::SstModel sst(mesh, distance(), ts);
  flow.set_turbulence(&sst);
  for (const char* wall : {"cylinder/cylinder", "background/bottom", "background/top"})
    flow.wall(wall);
  flow.far_field("background/inlet");
  flow.far_field("background/outlet");
  sst.inlet("background/inlet");
  fv::FrameMotion body;
  body.stream = {0.2, 0, 0};
  std::fill(flow.U.c[0].cells.begin(), flow.U.c[0].cells.end(), 0.2);
  flow.set_motion({fv::placed_motion(body, sys.axes(0), spin, pivot), body});
  flow.initialise();
  SwingSst r;
  for (int k = 1; k <= 10; ++k) {
    std::vector<mesher::CellStatus> before(static_cast<std::size_t>(mesh.cells()));
    for (int cell = 0; cell < mesh.cells(); ++cell)
      before[static_cast<std::size_t>(cell)] = ov.status(cell);
    sys.place(0, turn_about(pivot, spin.z() * k * s.dt));
    sys.reassemble();
    sst.set_wall_distance(distance());
    flow.set_motion({fv::placed_motion(body, sys.axes(0), spin, pivot), body});
    // The neighbours' range of k and omega for the cells about to come out of a hole.
    std::vector<int> out;
    for (int cell = 0; cell < mesh.cells(); ++cell)
      if (before[static_cast<std::size_t>(cell)] == mesher::CellStatus::hole &&
          ov.status(cell) != mesher::CellStatus::hole)
        out.push_back(cell);
    r.came_out += static_cast<int>(out.size());
    const auto range = [&](const std::vector<double>& f) {
      double lo = 1e300, hi = -1e300;
      for (int cell : out)
        for (int face : mesh.cell_faces(cell)) {
          if (face >= mesh.internal_faces()) continue;
          const int o = mesh.owner(face) == cell ? mesh.neighbour(face) : mesh.owner(face);
          if (before[static_cast<std::size_t>(o)] == mesher::CellStatus::hole) continue;
          lo = std::min(lo, f[static_cast<std::size_t>(o)]);
          hi = std::max(hi, f[static_cast<std::size_t>(o)]);
        }
      return std::pair{lo, hi};
    };
    const std::array ranges{range(sst.k.cells), range(sst.omega.cells)};
    // A fringe cell out of a hole: its donors' (bounded) interpolation, at the new stencils, of
    // the present level and of the old one (n - 1 once the step has shifted the levels).
    std::vector<std::array<double, 4>> expected;  // k, k old, omega, omega old
    {
      std::vector<fv::TurbulenceModel::Carried> carried;
      sst.carried(carried);
      for (int cell : out)
        expected.push_back({ov.interpolate(sst.k.cells, cell, fv::Overset::Bound::donors),
                            ov.interpolate(*carried[0].old, cell, fv::Overset::Bound::donors),
                            ov.interpolate(sst.omega.cells, cell, fv::Overset::Bound::donors),
                            ov.interpolate(*carried[1].old, cell, fv::Overset::Bound::donors)});
    }
    flow.step();
    // After the step the model's levels n and n - 1 (state(): k_old_[0], k_old_[1], omega_old_[0],
    // omega_old_[1]) hold what the re-assembly carried into those cells.
    const auto state = sst.state();
    const std::array levels{state[6], state[7], state[8], state[9]};
    for (std::size_t j = 0; j < out.size(); ++j)
      for (std::size_t l = 0; l < 4; ++l) {
        const double v = (*levels[l])[static_cast<std::size_t>(out[j])];
        if (ov.status(out[j]) == mesher::CellStatus::fringe) {
          r.filled_right = r.filled_right && v == expected[j][l];
          r.came_out_fringe += l == 0 ? 1 : 0;
        } else if (l % 2 == 0) {
          const auto [lo, hi] = ranges[l / 2];
          r.filled_right = r.filled_right && v >= lo * (1 - 1e-12) && v <= hi * (1 + 1e-12);
        }
      }
  }
  for (int cell : ov.fringe_cells()) {
    const auto s_ = static_cast<std::size_t>(cell);
    r.fringe_mismatch = std::max(
        {r.fringe_mismatch,
         std::abs(sst.k.cells[s_] - ov.interpolate(sst.k.cells, cell, fv::Overset::Bound::donors)) /
             sst.k.cells[s_],
         std::abs(sst.omega.cells[s_] -
                  ov.interpolate(sst.omega.cells, cell, fv::Overset::Bound::donors)) /
             sst.omega.cells[s_]});
  }
  for (int cell : ov.active_cells()) {
    const auto s_ = static_cast<std::size_t>(cell);
    r.positive = r.positive && sst.k.cells[s_] > 0 && sst.omega.cells[s_] > 0 &&
                 std::isfinite(sst.k.cells[s_]) && std::isfinite(sst.omega.cells[s_]);
  }
  r.u = flow.U.c[0].cells;
  r.p = flow.p.cells;
  r.k = sst.k.cells;
  r.omega = sst.omega.cells;
  r.nu_t = sst.nu_t.cells;
  return r;
}
}  // namespace

TEST(SstOverset, ASwingingOGridCarriesKAndOmegaAndIsBitwiseOnOneTwoAndThreeThreads) {
  const auto a = swing_sst(1), b = swing_sst(2), c = swing_sst(3);
  EXPECT_GT(a.came_out_fringe, 0);
  EXPECT_LT(a.fringe_mismatch, 1e-12);
  EXPECT_TRUE(a.positive);
  EXPECT_TRUE(a.filled_right);
  for (const auto* x : {&b, &c})
    EXPECT_TRUE(a.u == x->u && a.p == x->p && a.k == x->k && a.omega == x->omega &&
                a.nu_t == x->nu_t);
}

namespace {
// An oblique stream (30 deg to x) through the turned box, every side of the background a far
// field (Pimple::far_field, SstModel::far_field): k and omega from the free stream where the
// flux enters (west and south), zero gradient where it leaves (east and north). The analytic
// decay runs along the stream from where each streamline entered; the outflow sides' cells are
// left out of the error (zero gradient: first order there).
struct Oblique {
  DecayError error;
  bool switched = true;  // west and south faces fixed, east and north zero gradient
};
Oblique oblique_decay(bool with_box) {
  const Eigen::Vector3d e(std::cos(std::numbers::pi / 6), std::sin(std::numbers::pi / 6), 0);
  const Eigen::Vector3d stream = kU * e;
  std::unique_ptr<fv::MovingOverset> sys;
  std::unique_ptr<fv::Mesh> alone;
  auto background = square(kHalf, 32, "background", mesher::PatchType::inlet);
  if (with_box) {
    std::vector<fv::MovingOverset::Component> c;
    c.push_back({square(0.6, 16, "box", mesher::PatchType::overset), 1, {}});
    c.push_back({std::move(background), 0, nullptr});
    sys = std::make_unique<fv::MovingOverset>(std::move(c));
    sys->place(0, turn_about(Eigen::Vector3d(0.3, 0.1, 0), std::numbers::pi / 6));
    sys->reassemble();
  } else {
    alone = std::make_unique<fv::Mesh>(background);
  }
  const fv::Mesh& mesh = with_box ? sys->mesh() : *alone;
  const fv::Overset* ov = with_box ? &sys->overset() : nullptr;
  fv::PimpleSettings s;
  s.nu = kNu;
  s.steady = true;
  s.relax_u = 0.7;
  s.relax_p = 0.3;
  s.tolerance = 1e-12;
  s.max_courant = 1e30;
  fv::Pimple flow(mesh, s);
  flow.set_overset(ov);
  turb::SstModel sst(mesh, std::vector<double>(static_cast<std::size_t>(mesh.cells()), 1e3),
                     decay_settings());
  flow.set_turbulence(&sst);
  const std::string bg = with_box ? "background/" : "";
  for (const char* side : {"west", "east", "south", "north"}) {
    flow.far_field(bg + side);
    sst.far_field(bg + side);
  }
  fv::FrameMotion body;
  body.stream = stream;
  const Eigen::Matrix3d R =
      with_box ? Eigen::Matrix3d(sys->axes(0).linear()) : Eigen::Matrix3d::Identity();
  for (int cell = 0; cell < mesh.cells(); ++cell) {
    const Eigen::Vector3d u = ov != nullptr && ov->component_of(cell) == 0
                                  ? Eigen::Vector3d(R.transpose() * stream)
                                  : stream;
    for (std::size_t i = 0; i < 3; ++i)
      flow.U.c[i].cells[static_cast<std::size_t>(cell)] = u[static_cast<Eigen::Index>(i)];
  }
  std::vector<fv::FrameMotion> motion{body};
  if (with_box)
    motion = {
        fv::placed_motion(body, sys->axes(0), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
        body};
  flow.set_motion(motion);
  flow.initialise();
  for (int k = 0; k < 150; ++k) flow.step();
  Oblique r;
  for (int cell = 0; cell < mesh.cells(); ++cell) {
    if (ov != nullptr && !ov->active(cell)) continue;
    const Eigen::Vector3d x = ov != nullptr && ov->component_of(cell) == 0
                                  ? Eigen::Vector3d(sys->axes(0) * mesh.centre(cell))
                                  : mesh.centre(cell);
    if (x.x() > kHalf - 0.25 || x.y() > kHalf - 0.25) continue;
    const double X = std::min((x.x() + kHalf) / e.x(), (x.y() + kHalf) / e.y());
    const auto exact = decay(X);
    const auto c = static_cast<std::size_t>(cell);
    const double err = std::max(std::abs(sst.k.cells[c] / exact.k - 1),
                                std::abs(sst.omega.cells[c] / exact.omega - 1));
    double& into = ov != nullptr && ov->component_of(cell) == 0 ? r.error.box : r.error.background;
    into = std::max(into, err);
  }
  for (const char* side : {"west", "east", "south", "north"}) {
    const double want = side[0] == 'w' || side[0] == 's' ? 1.0 : 0.0;
    for (const auto* field : {&sst.k, &sst.omega})
      for (double f :
           field->bcs[static_cast<std::size_t>(fv::patch_index(mesh, bg + side))].fraction)
        r.switched = r.switched && f == want;
  }
  return r;
}
}  // namespace

TEST(SstOverset, AFarFieldTakesTheFreeStreamWhereTheFlowEntersAnObliqueStream) {
  const auto single = oblique_decay(false), pair = oblique_decay(true);
  std::printf("oblique: single %.3e; overset box %.3e background %.3e\n", single.error.background,
              pair.error.box, pair.error.background);
  EXPECT_TRUE(single.switched);
  EXPECT_TRUE(pair.switched);
  EXPECT_LT(pair.error.box, single.error.background);
  EXPECT_LT(pair.error.background, 1.5 * single.error.background);
  // The single grid's largest error (3.3e-2) sits on the characteristic from the inflow corner,
  // where the decay's gradient jumps; with k and omega zero gradient where the flow enters it
  // would be of order one.
  EXPECT_LT(single.error.background, 5e-2);
}
