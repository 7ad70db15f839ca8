// SPDX-License-Identifier: GPL-3.0-or-later
// Unit checks of the PIMPLE solver: thread-count independence to the bit, mass conservation of
// the corrected fluxes, and the divergence diagnosis.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/mesher/generators.hpp"
#include "couette_flow.hpp"
#include "temp_dir.hpp"

using namespace auvloop;
using engine::fv::Pimple;

namespace {
mesher::Grid cavity(int n, bool two_d, bool periodic = false) {
  const auto nodes = mesher::graded_nodes(0, 1, n, 1.1, true);
  mesher::BoxPatches patches;
  patches.names = {"left", "right", "bottom", "lid", "front", "back"};
  if (two_d) patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  if (periodic) patches.types[4] = patches.types[5] = mesher::PatchType::periodic;
  return mesher::cartesian_box(nodes, nodes, two_d ? std::vector<double>{0, 0.1} : nodes, patches,
                               "cavity");
}

// The lid-driven cavity (n cells a side, lid 1 m/s, other walls at rest) with settings `s`,
// initialised.
struct LidCavity {
  explicit LidCavity(const engine::fv::PimpleSettings& s, int n = 24, bool two_d = true,
                     bool periodic = false)
      : grid(cavity(n, two_d, periodic)), mesh(grid), flow(mesh, s) {
    for (const auto& patch : grid.patches)
      if (patch.type == mesher::PatchType::wall) flow.U.fix(mesh, patch.name, {0, 0, 0});
    flow.U.fix(mesh, "lid", {1, 0, 0});
    flow.initialise();
  }
  mesher::Grid grid;
  engine::fv::Mesh mesh;
  Pimple flow;
};

struct Snapshot {
  std::vector<double> u, v, w, p, phi;
};

Snapshot run_cavity(
    int threads, int n, bool two_d, engine::fv::SymmetricMethod solver, bool periodic = false,
    engine::fv::AsymmetricMethod momentum = engine::fv::AsymmetricMethod::gauss_seidel) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  engine::fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 0.05;
  s.outer_iterations = 2;
  s.relax_u = 0.8;
  s.relax_p = 0.5;
  s.pressure_solver = solver;
  s.momentum_solver = momentum;
  LidCavity c(s, n, two_d, periodic);
  auto& flow = c.flow;
  for (int k = 0; k < 3; ++k) flow.step();
  return {flow.U.c[0].cells, flow.U.c[1].cells, flow.U.c[2].cells, flow.p.cells, flow.phi};
}
}  // namespace

bool same(const Snapshot& a, const Snapshot& b) {
  return a.u == b.u && a.v == b.v && a.w == b.w && a.p == b.p && a.phi == b.phi;
}

TEST(FvThreads, BitwiseIdenticalForOneTwoAndThreeThreads) {
  // 22^3 = 10,648 cells: 2 face blocks in the assembly scatters, 5 blocks in the hybrid
  // Gauss-Seidel smoother, 3 fixed blocks in every reduction, and loops split wherever they
  // exceed 1024 indices, so 2 and 3 threads share out every kind of parallel loop (on the team
  // that each time step opens, team.hpp).
  using engine::fv::AsymmetricMethod;
  using engine::fv::SymmetricMethod;
  constexpr int n = 22;
  for (auto solver : {SymmetricMethod::cg_jacobi, SymmetricMethod::cg_dic, SymmetricMethod::cg_amg,
                      SymmetricMethod::cholmod_pcg}) {
    const auto one = run_cavity(1, n, false, solver);
    for (int threads : {2, 3})
      EXPECT_TRUE(same(one, run_cavity(threads, n, false, solver)))
          << to_string(solver) << ", " << threads << " threads";
  }
  for (auto momentum : {AsymmetricMethod::bicgstab_jacobi, AsymmetricMethod::bicgstab_gs}) {
    const auto one = run_cavity(1, n, false, SymmetricMethod::cg_amg, false, momentum);
    for (int threads : {2, 3})
      EXPECT_TRUE(
          same(one, run_cavity(threads, n, false, SymmetricMethod::cg_amg, false, momentum)))
          << to_string(momentum) << ", " << threads << " threads";
  }
  // Periodic front and back: the coupled faces in the scatters, the smoother and the DIC sweeps.
  for (auto solver : {SymmetricMethod::cg_dic, SymmetricMethod::cg_amg}) {
    const auto one = run_cavity(1, n, false, solver, true);
    for (int threads : {2, 3})
      EXPECT_TRUE(same(one, run_cavity(threads, n, false, solver, true)))
          << "periodic, " << to_string(solver) << ", " << threads << " threads";
  }
}

TEST(FvPimple, CorrectedFluxesConserveMassInEveryCell) {
  // The exact Cholesky solve makes the final pressure equation hold to round-off, so every
  // cell's net outflow is round-off of the face fluxes (lid speed 1 m/s, faces ~0.1 m^2 / 24).
  engine::fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 0.05;
  s.pressure_solver = engine::fv::SymmetricMethod::cholmod;
  LidCavity cavity_flow(s);
  const auto& mesh = cavity_flow.mesh;
  auto& flow = cavity_flow.flow;
  for (int k = 0; k < 3; ++k) flow.step();
  const auto d = engine::fv::div(mesh, flow.phi);
  for (int c = 0; c < mesh.cells(); ++c)
    EXPECT_LT(std::abs(d[static_cast<std::size_t>(c)] * mesh.volume(c)), 1e-12) << c;
}

std::string divergence_message(Pimple& flow) {
  try {
    flow.step();
  } catch (const engine::fv::DivergenceError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no divergence reported";
  return "";
}

TEST(FvPimple, DivergenceNamesStepAndCellAndKeepsTheLastGoodFields) {
  // A Courant limit of 0.5 with dt = 0.05 s on 1/24 m cells at 1 m/s (Co about 1.2): the first
  // step exceeds it; the fields must be those before the step, in memory and in the divergence
  // directory.
  const test::TempDir tmp;
  engine::fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 0.05;
  s.max_courant = 0.5;
  s.divergence_directory = tmp.path() / "diverged";
  LidCavity c(s);
  auto& flow = c.flow;
  const auto before = flow.U.c[0].cells;
  const std::string what = divergence_message(flow);
  std::printf("%s\n", what.c_str());
  EXPECT_NE(what.find("step 1"), std::string::npos) << what;
  EXPECT_NE(what.find("Courant number"), std::string::npos) << what;
  EXPECT_NE(what.find("in cell"), std::string::npos) << what;
  EXPECT_NE(what.find("last-good.checkpoint"), std::string::npos) << what;
  EXPECT_EQ(flow.U.c[0].cells, before);
  EXPECT_EQ(flow.steps(), 0);
  EXPECT_TRUE(std::filesystem::exists(s.divergence_directory / "last-good.pvd"));
  // The checkpoint holds the restored fields.
  LidCavity restarted(s);
  restarted.flow.U.c[0].cells.assign(before.size(), 7.0);
  restarted.flow.read_checkpoint(s.divergence_directory / "last-good.checkpoint");
  EXPECT_EQ(restarted.flow.U.c[0].cells, before);
}

TEST(FvPimple, ASpeedGuardStopsTheStepThatPassesIt) {
  // The lid (1 m/s) drives the cavity: after a step the largest |U| in a cell is below the
  // lid's. A guard at half that largest speed stops the same step in a fresh cavity, names the
  // cell and keeps the fields before the step.
  engine::fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 0.05;
  LidCavity free(s);
  const auto r = free.flow.step();
  EXPECT_GT(r.max_speed, 0.1);
  EXPECT_LT(r.max_speed, 1.0);
  s.max_speed = 0.5 * r.max_speed;
  LidCavity guarded(s);
  const auto before = guarded.flow.U.c[0].cells;
  const std::string what = divergence_message(guarded.flow);
  EXPECT_NE(what.find("step 1"), std::string::npos) << what;
  EXPECT_NE(what.find("beyond the limit"), std::string::npos) << what;
  EXPECT_NE(what.find("in cell"), std::string::npos) << what;
  EXPECT_EQ(guarded.flow.U.c[0].cells, before);
}

TEST(FvPimple, ALinearSolveThatFailsNamesItsEquationAndCell) {
  // A tolerance no Krylov solver reaches: the first solve fails; the message says which.
  engine::fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 0.01;
  s.tolerance = 1e-300;
  s.pressure_solver = engine::fv::SymmetricMethod::cg_dic;
  LidCavity c(s);
  const auto before = c.flow.p.cells;
  const std::string what = divergence_message(c.flow);
  std::printf("%s\n", what.c_str());
  EXPECT_NE(what.find("momentum equation Ux"), std::string::npos) << what;
  EXPECT_NE(what.find("largest residual in cell"), std::string::npos) << what;
  EXPECT_EQ(c.flow.p.cells, before);
}

TEST(FvPimple, CouetteFlowIsExactAndGivesTheWallShear) {
  // Plane Couette flow (tests/support/couette_flow.hpp): velocity linear in y is reproduced
  // exactly by every operator, so the steady solution and the wall forces nu U / H per area are
  // exact to the solver tolerance (1e-10 relative after the steady state).
  const test::CouetteFlow couette;
  const auto& mesh = couette.mesh;
  const auto& flow = couette.flow;
  const double U = test::CouetteFlow::U, H = test::CouetteFlow::H;
  for (int c = 0; c < mesh.cells(); ++c)
    EXPECT_NEAR(flow.U.c[0].cells[static_cast<std::size_t>(c)], U * mesh.centre(c).y() / H, 1e-9);
  const double shear = test::CouetteFlow::shear();
  const auto top = engine::fv::patch_force(flow, "top");
  const auto bottom = engine::fv::patch_force(flow, "bottom");
  EXPECT_NEAR(top.viscous.x(), -shear, 1e-9 * shear);
  EXPECT_NEAR(bottom.viscous.x(), shear, 1e-9 * shear);
}

TEST(FvPimple, SlipWallsKeepAUniformStreamUniform) {
  // Uniform flow between two slip (symmetry) walls: no shear, no normal velocity, so the exact
  // solution is the inflow everywhere with uniform pressure. No-slip walls would grow boundary
  // layers (u at the wall cells would drop by O(0.1) within the channel). Measured deviation:
  // 3e-9, the level of the iterative solvers; the bound 1e-6 sits between the two.
  mesher::BoxPatches patches;
  patches.names = {"inlet", "outlet", "bottom", "top", "front", "back"};
  patches.types = {mesher::PatchType::inlet,    mesher::PatchType::outlet,
                   mesher::PatchType::symmetry, mesher::PatchType::symmetry,
                   mesher::PatchType::empty,    mesher::PatchType::empty};
  const auto grid =
      mesher::cartesian_box(mesher::graded_nodes(0, 1, 10), mesher::graded_nodes(0, 0.2, 6, 1.2),
                            {0, 0.05}, patches, "slip-channel");
  const engine::fv::Mesh mesh(grid);
  engine::fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 0.1;
  s.outer_iterations = 3;
  s.tolerance = 1e-12;
  Pimple flow(mesh, s);
  flow.U.fix(mesh, "inlet", {1, 0, 0});
  flow.slip("bottom");
  flow.slip("top");
  flow.p.fix(mesh, "outlet", 0.0);
  flow.initialise();
  for (int k = 0; k < 30; ++k) flow.step();
  for (int c = 0; c < mesh.cells(); ++c) {
    EXPECT_NEAR(flow.U.c[0].cells[static_cast<std::size_t>(c)], 1.0, 1e-6) << c;
    EXPECT_NEAR(flow.U.c[1].cells[static_cast<std::size_t>(c)], 0.0, 1e-6) << c;
  }
}

// PimpleSettings::intermediate_tolerance loosens the pressure solves of the outer iterations but
// the last only: fewer pressure iterations, and the step still ends with the last iteration's
// pressure equation solved to `tolerance`, so mass is conserved as tightly as without it.
TEST(FvPimple, IntermediateToleranceLoosensOnlyTheEarlierOuterIterations) {
  const auto run = [](double intermediate) {
    engine::fv::PimpleSettings s;
    s.nu = 0.01;
    s.dt = 0.05;
    s.outer_iterations = 3;
    s.relax_u = 0.8;
    s.relax_p = 0.5;
    s.pressure_solver = engine::fv::SymmetricMethod::cg_amg;
    s.tolerance = 1e-10;
    s.intermediate_tolerance = intermediate;
    LidCavity c(s, 24);
    int iterations = 0;
    double continuity = 0;
    for (int k = 0; k < 3; ++k) {
      const auto r = c.flow.step();
      iterations += r.pressure_iterations;
      continuity = std::max(continuity, r.continuity_error);
    }
    return std::pair{iterations, continuity};
  };
  const auto [tight_iterations, tight_continuity] = run(0);
  const auto [loose_iterations, loose_continuity] = run(1e-3);
  EXPECT_LT(loose_iterations, 0.8 * tight_iterations);
  std::printf("pressure iterations %d -> %d; continuity %g -> %g\n", tight_iterations,
              loose_iterations, tight_continuity, loose_continuity);
  EXPECT_LT(loose_continuity, 10 * tight_continuity + 1e-15);
}
