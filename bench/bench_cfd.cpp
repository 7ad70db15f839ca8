// SPDX-License-Identifier: GPL-3.0-or-later
// Cost of the PIMPLE solver on the 3D lid-driven cavity (unit cube, lid u = 1 m/s, Re = 100 by
// default): microseconds per cell per time step and per outer iteration, split by phase
// (momentum assembly and solve, pressure correctors, the rest), for a pressure solver and a
// thread count. Not a test: nothing is asserted.
//   bench_cfd [--n N] [--steps K] [--outer M] [--correctors C] [--pressure cholmod|cg-ic|cg-jacobi]
//             [--threads T] [--re RE] [--co COURANT] [--2d 1]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <tbb/global_control.h>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;

int main(int argc, char** argv) {
  int n = 32, steps = 10, outer = 1, correctors = 2, threads = 1, two_d = 0;
  double re = 100, co = 1;
  std::string pressure;  // empty: the solver's default for the grid
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const char* v = argv[i + 1];
    if (key == "--n")
      n = std::atoi(v);
    else if (key == "--steps")
      steps = std::atoi(v);
    else if (key == "--outer")
      outer = std::atoi(v);
    else if (key == "--correctors")
      correctors = std::atoi(v);
    else if (key == "--pressure")
      pressure = v;
    else if (key == "--threads")
      threads = std::atoi(v);
    else if (key == "--re")
      re = std::atof(v);
    else if (key == "--co")
      co = std::atof(v);
    else if (key == "--2d")
      two_d = std::atoi(v);
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  const auto nodes = mesher::graded_nodes(0, 1, n);
  mesher::BoxPatches patches;
  patches.names = {"left", "right", "bottom", "lid", "front", "back"};
  if (two_d) patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  const auto grid = mesher::cartesian_box(
      nodes, nodes, two_d ? std::vector<double>{0.0, 1.0 / n} : nodes, patches, "cavity");
  const engine::fv::Mesh mesh(grid);
  engine::fv::PimpleSettings s;
  s.nu = 1.0 / re;
  s.dt = co / n;  // Courant number `co` at the lid speed
  s.outer_iterations = outer;
  s.pressure_correctors = correctors;
  if (!pressure.empty()) s.pressure_solver = engine::fv::symmetric_method_from_string(pressure);
  s.tolerance = 1e-6;
  engine::fv::Pimple flow(mesh, s);
  pressure = engine::fv::to_string(*flow.settings().pressure_solver);
  for (const char* wall : {"left", "right", "bottom", "front", "back"})
    if (!two_d || wall[0] == 'l' || wall[0] == 'r' || wall[0] == 'b')
      flow.U.fix(mesh, wall, {0, 0, 0});
  flow.U.fix(mesh, "lid", {1, 0, 0});
  flow.initialise();
  double momentum = 0, pressure_s = 0, other = 0;
  int pressure_iterations = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    const auto r = flow.step();
    momentum += r.seconds_momentum;
    pressure_s += r.seconds_pressure;
    other += r.seconds_other;
    pressure_iterations += r.pressure_iterations;
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cells = mesh.cells();
  const double per_step = 1e6 * total / (cells * steps);
  std::printf("cavity%s n=%d cells=%d steps=%d outer=%d correctors=%d pressure=%s threads=%d\n",
              two_d ? "2d" : "3d", n, mesh.cells(), steps, outer, correctors, pressure.c_str(),
              threads);
  std::printf("  us/cell/step %.3f   us/cell/outer %.3f   s/step %.4f\n", per_step,
              per_step / outer, total / steps);
  std::printf(
      "  phase split: momentum %.1f %%, pressure %.1f %%, other %.1f %%   "
      "(pressure Krylov iterations per step %.1f)\n",
      100 * momentum / total, 100 * pressure_s / total,
      100 * (total - momentum - pressure_s) / total,
      static_cast<double>(pressure_iterations) / steps);
  return 0;
}
