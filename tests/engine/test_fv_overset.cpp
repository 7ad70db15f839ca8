// SPDX-License-Identifier: GPL-3.0-or-later
// fv::Overset and Pimple's explicit overset coupling on the mesher's cylinder O-grid over a
// Cartesian channel (a coarse Schaefer-Turek pair): the invariants the constructor checks, mass
// conserved across the interface (overset_mass.cpp), fringe values equal to their donors'
// interpolation after a step, bit-identical results for one and two threads, and a restart from a
// checkpoint that continues bitwise.
#include <cmath>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/overset.hpp"

using namespace auvloop;
using engine::fv::Overset;

namespace {
constexpr double kUbar = 0.2;  // mean inflow (m/s)

struct Pair {
  mesher::Grid grid;
  mesher::CompositeStencils stencils;
  std::vector<int> offsets;
};

Pair coarse_pair() {
  mesher::CylinderOversetSpec spec;
  spec.around = 32;
  spec.radial_cells = 8;
  spec.downstream_cells = 16;
  const auto pair = mesher::cylinder_overset(spec);
  auto system =
      mesher::composite_system({{&pair.cylinder, 1, &pair.solid}, {&pair.background, 0, nullptr}});
  return {std::move(system.composite.grid), std::move(system.stencils),
          std::move(system.composite.cell_offset)};
}

struct Run {
  std::vector<double> u, v, p, phi;
  double interface_flux = 0, continuity = 0, fringe_mismatch = 0;
};

// `restart_after` > 0: the flow is checkpointed after that many steps and a second solver,
// built alike, reads the checkpoint and runs the rest (the first one is discarded).
Run run(int threads, int restart_after = 0) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  auto pair = coarse_pair();
  const engine::fv::Mesh mesh(pair.grid);
  const Overset overset(mesh, pair.stencils, pair.offsets);
  engine::fv::PimpleSettings s;
  s.nu = 1e-3;
  s.dt = 0.02;
  s.outer_iterations = 2;
  s.relax_u = 0.8;
  s.relax_p = 0.5;
  s.tolerance =
      1e-12;  // so that the conservation measured below is the coupling's, not the solver's
  // An iterative pressure solver: a restart from cholmod-pcg is not exact (pimple.hpp).
  s.pressure_solver = engine::fv::SymmetricMethod::cg_amg;
  auto make = [&] {
    auto flow = std::make_unique<engine::fv::Pimple>(mesh, s);
    flow->set_overset(&overset);
    for (const char* wall : {"background/bottom", "background/top", "cylinder/cylinder"})
      flow->U.fix(mesh, wall, {0, 0, 0});
    flow->U.fix(mesh, "background/inlet", {kUbar, 0, 0});  // a plug inflow is enough here
    flow->p.fix(mesh, "background/outlet", 0.0);
    flow->initialise();
    return flow;
  };
  auto owner = make();
  Run r;
  for (int k = 0; k < 4; ++k) {
    if (restart_after > 0 && k == restart_after) {
      const auto file = std::filesystem::path(::testing::TempDir()) / "overset.checkpoint";
      owner->write_checkpoint(file);
      owner = make();
      owner->read_checkpoint(file);
    }
    auto& flow = *owner;
    const auto rep = flow.step();
    r.interface_flux = std::max(r.interface_flux, rep.interface_flux);
    r.continuity = std::max(r.continuity, rep.continuity_error);
  }
  const auto& flow = *owner;
  for (int c : overset.fringe_cells())
    r.fringe_mismatch =
        std::max(r.fringe_mismatch, std::abs(flow.U.c[0].cells[static_cast<std::size_t>(c)] -
                                             overset.interpolate(flow.U.c[0].cells, c)));
  r.u = flow.U.c[0].cells;
  r.v = flow.U.c[1].cells;
  r.p = flow.p.cells;
  r.phi = flow.phi;
  return r;
}
}  // namespace

TEST(FvOverset, ChecksItsInvariants) {
  auto pair = coarse_pair();
  const engine::fv::Mesh mesh(pair.grid);
  const Overset ok(mesh, pair.stencils, pair.offsets);
  EXPECT_EQ(ok.components(), 2);
  EXPECT_GT(ok.fringe_cells().size(), 0u);
  EXPECT_LT(ok.active_cells().size(), static_cast<std::size_t>(mesh.cells()));
  // Every face between two cells that are not active carries no flux.
  for (int f = 0; f < mesh.internal_faces(); ++f)
    if (!ok.active(mesh.owner(f)) && !ok.active(mesh.neighbour(f))) {
      EXPECT_FALSE(ok.live(f));
    }
  // A fringe cell whose donor is not active, and stencils for another mesh, are refused.
  auto bad = pair.stencils;
  const int fringe = ok.fringe_cells().front();
  const auto k = static_cast<std::size_t>(bad.offsets[static_cast<std::size_t>(fringe)]);
  bad.donors[k] = ok.fringe_cells().back();
  EXPECT_THROW(Overset(mesh, bad, pair.offsets), std::invalid_argument);
  auto short_status = pair.stencils;
  short_status.status.pop_back();
  EXPECT_THROW(Overset(mesh, short_status, pair.offsets), std::invalid_argument);
}

TEST(FvOverset, ConservesMassAndKeepsFringeOnItsDonors) {
  const auto r = run(1);
  // The inflow is Ubar H t; the interface passes none of it (solver tolerance), every active
  // cell's continuity holds, and the fringe velocity is its donors' interpolation.
  const double inflow = kUbar * 0.41 * 0.01;
  EXPECT_LT(r.interface_flux / inflow, 1e-8);
  EXPECT_LT(r.continuity, 1e-10);
  EXPECT_LT(r.fringe_mismatch, 1e-12);
}

TEST(FvOverset, BitwiseIdenticalForOneAndTwoThreads) {
  const auto a = run(1), b = run(2);
  EXPECT_TRUE(a.u == b.u && a.v == b.v && a.p == b.p && a.phi == b.phi);
}

TEST(FvOverset, RestartFromACheckpointContinuesBitwise) {
  const auto a = run(1), b = run(1, 2);
  EXPECT_TRUE(a.u == b.u && a.v == b.v && a.p == b.p && a.phi == b.phi);
}
