// SPDX-License-Identifier: GPL-3.0-or-later
// Time stepping: BDF2 on variable steps, the adaptive (Courant-number) control, and exact
// checkpoint/restart.
//   - Taylor-Green vortex (exact solution, Dirichlet values from it on [0, pi]^2 as in
//     `auvloop validate`) with steps alternating dt and 2 dt: the observed order from successive
//     solutions at halved steps (Roache 2002; the spatial error cancels) must be 2 with the
//     variable-step coefficients (the fixed-step ones, 3/2, -2, 1/2, on this sequence gave
//     order 0.47 on this sequence when tried while this was written).
//   - the adaptive control reaches the target Courant number, growing by the set factor.
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include <unistd.h>

#include <gtest/gtest.h>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/geometry/file_io.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {
constexpr double kPi = std::numbers::pi;

Eigen::Vector3d exact(const Eigen::Vector3d& x, double nu, double t) {
  const double F = std::exp(-2 * nu * t);
  return {-std::cos(x.x()) * std::sin(x.y()) * F, std::sin(x.x()) * std::cos(x.y()) * F, 0.0};
}

void impose(const fv::Mesh& mesh, fv::Pimple& flow, double nu, double t) {
  const auto& patches = mesh.grid().patches;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (patches[p].type == mesher::PatchType::empty) continue;
    for (int i = 0; i < patches[p].size; ++i) {
      const auto u = exact(mesh.face_centre(patches[p].start + i), nu, t);
      for (std::size_t c = 0; c < 3; ++c)
        flow.U.c[c].bcs[p].value[static_cast<std::size_t>(i)] = u[static_cast<Eigen::Index>(c)];
    }
  }
}

// u, v at t = 1 s after `pairs` pairs of steps (dt, 2 dt), nu = 1 (BDF2's error dominates).
std::vector<double> taylor_green(int pairs) {
  const double nu = 1;
  const auto nodes = mesher::graded_nodes(0, kPi, 24);
  mesher::BoxPatches patches;
  patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  const auto grid = mesher::cartesian_box(nodes, nodes, {0.0, kPi / 24}, patches, "tg");
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = nu;
  const double dt = 1.0 / (3 * pairs);
  s.dt = dt;
  s.outer_iterations = 60;
  s.outer_tolerance = 1e-10;
  s.tolerance = 1e-12;
  fv::Pimple flow(mesh, s);
  for (const char* side : {"xmin", "xmax", "ymin", "ymax"}) flow.U.fix(mesh, side, {0, 0, 0});
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto& x = mesh.centre(c);
    const auto u = exact(x, nu, 0);
    flow.U.c[0].cells[static_cast<std::size_t>(c)] = u.x();
    flow.U.c[1].cells[static_cast<std::size_t>(c)] = u.y();
    flow.p.cells[static_cast<std::size_t>(c)] = -0.25 * (std::cos(2 * x.x()) + std::cos(2 * x.y()));
  }
  impose(mesh, flow, nu, 0);
  flow.initialise();
  for (int k = 0; k < 2 * pairs; ++k) {
    const double step = k % 2 == 0 ? dt : 2 * dt;
    flow.set_time_step(step);
    impose(mesh, flow, nu, flow.time() + step);
    flow.step();
  }
  EXPECT_NEAR(flow.time(), 1.0, 1e-12);
  std::vector<double> out;
  for (int c = 0; c < mesh.cells(); ++c) {
    out.push_back(flow.U.cell(c).x());
    out.push_back(flow.U.cell(c).y());
  }
  return out;
}

double rms_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum / static_cast<double>(a.size()));
}

double observed_order() {
  const auto u1 = taylor_green(4);
  const auto u2 = taylor_green(8);
  const auto u3 = taylor_green(16);
  return std::log2(rms_difference(u1, u2) / rms_difference(u2, u3));
}
}  // namespace

TEST(FvTime, VariableStepBdf2IsSecondOrderOnAlternatingSteps) {
  const double order = observed_order();
  std::printf("alternating dt, 2 dt: observed order %.3f\n", order);
  EXPECT_GT(order, 1.8);
}

TEST(FvTime, AdaptiveStepReachesTheTargetCourantNumber) {
  const auto nodes = mesher::graded_nodes(0, 1, 16);
  mesher::BoxPatches patches;
  patches.names = {"left", "right", "bottom", "lid", "front", "back"};
  patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  const auto grid = mesher::cartesian_box(nodes, nodes, {0.0, 0.1}, patches, "cavity");
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 1e-4;
  s.target_courant = 0.8;
  s.max_dt_growth = 1.2;
  fv::Pimple flow(mesh, s);
  for (const char* wall : {"left", "right", "bottom"}) flow.U.fix(mesh, wall, {0, 0, 0});
  flow.U.fix(mesh, "lid", {1, 0, 0});
  flow.initialise();
  double dt_prev = 0;
  fv::StepReport r;
  for (int k = 0; k < 60; ++k) {
    r = flow.step();
    if (k > 0) {
      EXPECT_LE(r.dt, 1.2 * dt_prev * (1 + 1e-12)) << k;
    }
    dt_prev = r.dt;
  }
  EXPECT_NEAR(r.max_courant, 0.8, 0.02);  // the flux changes little over the last step
  s.max_dt_growth = 3;
  EXPECT_THROW(fv::Pimple(mesh, s), std::invalid_argument);
}

namespace {
struct CavityState {
  std::vector<double> u, v, p, phi;
  double time = 0;
};

// A 2D cavity with a periodic pair (x) and an adaptive step, so the checkpoint must carry the dt
// history: N steps straight, or k steps, checkpoint, a fresh solver, restart, N - k steps.
CavityState cavity_run(int total, int split, const std::filesystem::path& checkpoint) {
  const auto nodes = mesher::graded_nodes(0, 1, 12, 1.1, true);
  mesher::BoxPatches patches;
  patches.names = {"left", "right", "bottom", "lid", "front", "back"};
  patches.types = {mesher::PatchType::periodic, mesher::PatchType::periodic,
                   mesher::PatchType::wall,     mesher::PatchType::wall,
                   mesher::PatchType::empty,    mesher::PatchType::empty};
  const auto grid = mesher::cartesian_box(nodes, nodes, {0.0, 0.1}, patches, "cavity");
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = 0.01;
  s.dt = 0.01;
  s.target_courant = 1;
  s.outer_iterations = 2;
  s.relax_u = 0.8;
  s.pressure_solver = fv::SymmetricMethod::cg_dic;
  auto make = [&] {
    auto flow = std::make_unique<fv::Pimple>(mesh, s);
    flow->U.fix(mesh, "bottom", {0, 0, 0});
    flow->U.fix(mesh, "lid", {1, 0, 0});
    flow->initialise();
    return flow;
  };
  auto flow = make();
  for (int k = 0; k < split; ++k) flow->step();
  if (split < total) {
    flow->write_checkpoint(checkpoint);
    flow = make();
    flow->read_checkpoint(checkpoint);
    for (int k = split; k < total; ++k) flow->step();
  }
  return {flow->U.c[0].cells, flow->U.c[1].cells, flow->p.cells, flow->phi, flow->time()};
}
}  // namespace

TEST(FvCheckpoint, RestartContinuesBitwise) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("auvloop_checkpoint_" + std::to_string(::getpid()) + ".bin");
  const CavityState straight = cavity_run(12, 12, file);
  const CavityState restarted = cavity_run(12, 5, file);
  EXPECT_EQ(straight.time, restarted.time);
  EXPECT_TRUE(straight.u == restarted.u && straight.v == restarted.v);
  EXPECT_TRUE(straight.p == restarted.p && straight.phi == restarted.phi);
  // A truncated file is refused and names itself.
  const auto bytes = read_file_text(file);
  write_file_atomically(file, bytes.substr(0, bytes.size() / 2));
  const auto nodes = mesher::graded_nodes(0, 1, 12, 1.1, true);
  mesher::BoxPatches patches;
  patches.types = {mesher::PatchType::periodic, mesher::PatchType::periodic,
                   mesher::PatchType::wall,     mesher::PatchType::wall,
                   mesher::PatchType::empty,    mesher::PatchType::empty};
  const auto grid = mesher::cartesian_box(nodes, nodes, {0.0, 0.1}, patches, "cavity");
  const fv::Mesh mesh(grid);
  fv::Pimple flow(mesh, {});
  flow.initialise();
  try {
    flow.read_checkpoint(file);
    FAIL() << "truncated checkpoint accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  EXPECT_EQ(flow.steps(), 0);
  std::filesystem::remove(file);
}
