// SPDX-License-Identifier: GPL-3.0-or-later
// Cost of the PIMPLE solver: microseconds per cell per time step and per outer iteration, split by
// phase (momentum assembly, momentum solve, pressure correctors, the rest; gradient evaluations
// across all of them), for a pressure solver and a thread count. Not a test: nothing is asserted.
// Two cases:
//   cavity  the 3D lid-driven cavity (unit cube, lid u = 1 m/s, Re = 100 by default), N^3 cells;
//   hull    the hull grid of a mesher preset (REMUS 100, no fins, no overset): freestream
//           -U_inf x on the upstream part of its outer boundary (U fixed, p zero gradient), p = 0
//           and zero-gradient U on the downstream part, no-slip on the hull; sea water.
//   bench_cfd [--case cavity|hull] [--preset coarse] [--n N] [--steps K] [--outer M]
//             [--correctors C] [--pressure cholmod|cholmod-pcg|cg-ic|cg-dic|cg-jacobi|cg-amg]
//             [--momentum gauss-seidel|bicgstab|bicgstab-ilut] [--tolerance TOL]
//             [--momentum-tolerance TOL] [--residual-norm relative|normalised]
//             [--threads T[,T...]] [--repeat R] [--re RE] [--co COURANT] [--2d 1]
//             [--time bdf2|euler] [--convection van-leer|linear-upwind|upwind]
//             [--turbulence laminar|sst|both]
// --turbulence (hull only): SST k-omega (free stream: 1 % intensity, nu_t / nu = 10; wall
// distance to the hull), or both in turn per thread count, with the cost of an SST step against
// a laminar one printed run by run (issue 16's acceptance: at most 1.4).
// With several thread counts (--threads 1,2) each runs in turn on the same mesh, R times over
// (--repeat), and the speed-ups against the first are printed run by run: a ratio measured in
// the same process at the same machine load. The first step of each run (multigrid setup, first
// touch of every array) is timed apart; the figures are those of the steps after it.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include <tbb/global_control.h>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/turbulence/sst_model.hpp"
#include "auvloop/engine/turbulence/wall_distance.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/generators.hpp"
#include "auvloop/mesher/grid_system.hpp"
#include "auvloop/mesher/mesh_settings.hpp"
#include "hull_case.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {
struct Options {
  std::string case_name = "cavity", preset = "coarse", pressure, time = "bdf2";
  std::string convection = "van-leer", momentum, threads = "1", residual_norm = "relative";
  std::string turbulence = "laminar";
  int n = 32, steps = 10, outer = 1, correctors = 2, two_d = 0, repeat = 1;
  double re = 100, co = 1, tolerance = 1e-6, momentum_tolerance = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], v = argv[i + 1];
    std::map<std::string, std::string*> strings{
        {"--case", &o.case_name},        {"--preset", &o.preset},
        {"--pressure", &o.pressure},     {"--time", &o.time},
        {"--convection", &o.convection}, {"--momentum", &o.momentum},
        {"--threads", &o.threads},       {"--residual-norm", &o.residual_norm},
        {"--turbulence", &o.turbulence}};
    std::map<std::string, int*> ints{{"--n", &o.n},           {"--steps", &o.steps},
                                     {"--outer", &o.outer},   {"--correctors", &o.correctors},
                                     {"--repeat", &o.repeat}, {"--2d", &o.two_d}};
    if (strings.contains(key))
      *strings[key] = v;
    else if (ints.contains(key))
      *ints[key] = std::atoi(v.c_str());
    else if (key == "--re")
      o.re = std::atof(v.c_str());
    else if (key == "--co")
      o.co = std::atof(v.c_str());
    else if (key == "--tolerance")
      o.tolerance = std::atof(v.c_str());
    else if (key == "--momentum-tolerance")
      o.momentum_tolerance = std::atof(v.c_str());
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      std::exit(2);
    }
  }
  return o;
}

mesher::Grid cavity_grid(const Options& o) {
  const auto nodes = mesher::graded_nodes(0, 1, o.n);
  mesher::BoxPatches patches;
  patches.names = {"left", "right", "bottom", "lid", "front", "back"};
  if (o.two_d) patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  return mesher::cartesian_box(nodes, nodes, o.two_d ? std::vector<double>{0.0, 1.0 / o.n} : nodes,
                               patches, "cavity");
}

struct Result {
  double per_step = 0, first_step = 0, assembly = 0, momentum = 0, pressure = 0, gradient = 0;
  double max_co = 0, pressure_iterations = 0, momentum_iterations = 0, turbulence = 0;
  double k_iterations = 0, omega_iterations = 0;
};

// One run on `threads` threads: the first step (multigrid setup, first touch of every array) is
// timed apart, the figures are those of the steps after it (as icoFoam's in
// bench/openfoam_cavity.sh, from its second step on).
Result run(const Options& o, const fv::Mesh& mesh, int threads, bool hull,
           const Eigen::Vector3d& u_inf, const fv::PimpleSettings& s,
           const std::vector<double>* wall_distance) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  fv::Pimple flow(mesh, s);
  std::unique_ptr<engine::turbulence::SstModel> sst;
  if (hull) {
    bench::set_freestream(flow, mesh, u_inf);
    if (wall_distance) {
      engine::turbulence::SstSettings ts;
      ts.nu = s.nu;
      ts.freestream = engine::turbulence::freestream_from_intensity(u_inf.norm(), 0.01, 10, s.nu);
      ts.tolerance = s.tolerance;
      sst = std::make_unique<engine::turbulence::SstModel>(mesh, *wall_distance, ts);
      sst->inlet("inflow");
      flow.set_turbulence(sst.get());
    }
  } else {
    for (const char* wall : {"left", "right", "bottom", "front", "back"})
      if (!o.two_d || wall[0] == 'l' || wall[0] == 'r' || wall[0] == 'b')
        flow.U.fix(mesh, wall, {0, 0, 0});
    flow.U.fix(mesh, "lid", {1, 0, 0});
  }
  flow.initialise();
  Result res;
  const auto t_first = std::chrono::steady_clock::now();
  flow.step();
  const auto t0 = std::chrono::steady_clock::now();
  res.first_step = std::chrono::duration<double>(t0 - t_first).count();
  for (int k = 1; k < o.steps; ++k) {
    const auto r = flow.step();
    res.assembly += r.seconds_assembly;
    res.momentum += r.seconds_momentum;
    res.pressure += r.seconds_pressure;
    res.gradient += r.seconds_gradient;
    res.pressure_iterations += r.pressure_iterations;
    res.momentum_iterations += r.momentum_iterations;
    res.turbulence += r.seconds_turbulence;
    res.k_iterations += r.turbulence.k_iterations;
    res.omega_iterations += r.turbulence.omega_iterations;
    res.max_co = std::max(res.max_co, r.max_courant);
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int timed = o.steps - 1;
  res.per_step = total / timed;
  for (double* v : {&res.assembly, &res.momentum, &res.pressure, &res.gradient, &res.turbulence})
    *v /= total;
  res.pressure_iterations /= timed;
  res.momentum_iterations /= timed;
  res.k_iterations /= timed;
  res.omega_iterations /= timed;
  return res;
}

std::vector<int> thread_list(const std::string& s) {
  std::vector<int> t;
  std::size_t pos = 0;
  while (pos <= s.size()) {
    const auto comma = s.find(',', pos);
    const int v = std::atoi(s.substr(pos, comma - pos).c_str());
    if (v < 1) {
      std::fprintf(stderr, "--threads: a comma-separated list of thread counts >= 1, got %s\n",
                   s.c_str());
      std::exit(2);
    }
    t.push_back(v);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  if (o.steps < 2) {
    std::fprintf(stderr, "--steps must be at least 2 (the first step is timed apart)\n");
    return 2;
  }
  const std::vector<int> threads = thread_list(o.threads);
  const bool hull = o.case_name == "hull";
  const Eigen::Vector3d u_inf(-1.54, 0, 0);  // REMUS 100 design speed, body frame (x forward)
  const mesher::Grid grid = hull ? bench::hull_freestream_grid(o.preset, u_inf) : cavity_grid(o);
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = hull ? 1.05e-6 : 1.0 / o.re;
  s.outer_iterations = o.outer;
  s.pressure_correctors = o.correctors;
  s.bdf2 = o.time == "bdf2";
  try {
    s.convection = fv::convection_from_string(o.convection);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  if (!o.pressure.empty()) s.pressure_solver = fv::symmetric_method_from_string(o.pressure);
  if (!o.momentum.empty()) s.momentum_solver = fv::asymmetric_method_from_string(o.momentum);
  s.tolerance = o.tolerance;
  s.residual_norm = fv::residual_norm_from_string(o.residual_norm);
  if (o.momentum_tolerance > 0) s.momentum_tolerance = o.momentum_tolerance;
  s.max_courant = 1e9;  // a benchmark: report, do not stop
  // Courant number `co` of the free stream in the smallest cell, or at the lid speed.
  s.dt = hull ? bench::freestream_dt(mesh, u_inf, o.co) : o.co / o.n;
  const std::string pressure = fv::to_string(*fv::Pimple(mesh, s).settings().pressure_solver);
  std::printf(
      "%s%s n=%d cells=%d steps=%d (1 + %d timed) outer=%d correctors=%d pressure=%s momentum=%s "
      "time=%s convection=%s dt=%.3g tolerance p %.3g U %.3g (%s)\n",
      hull ? ("hull-" + o.preset).c_str() : "cavity", hull ? "" : (o.two_d ? "2d" : "3d"),
      hull ? 0 : o.n, mesh.cells(), o.steps, o.steps - 1, o.outer, o.correctors, pressure.c_str(),
      fv::to_string(s.momentum_solver), o.time.c_str(), o.convection.c_str(), s.dt, s.tolerance,
      s.momentum_tolerance > 0 ? s.momentum_tolerance : s.tolerance,
      fv::to_string(s.residual_norm));
  if (o.turbulence != "laminar" && o.turbulence != "sst" && o.turbulence != "both") {
    std::fprintf(stderr, "--turbulence: laminar, sst or both, got %s\n", o.turbulence.c_str());
    return 2;
  }
  if (!hull && o.turbulence != "laminar") {
    std::fprintf(stderr, "--turbulence sst needs --case hull (the cavity has no inflow)\n");
    return 2;
  }
  std::vector<double> distance;
  if (o.turbulence != "laminar") {
    const engine::fv::Mesh* meshes[] = {&mesh};
    const engine::turbulence::WallDistances walls(meshes);
    distance.assign(walls.of(0).begin(), walls.of(0).end());
  }
  std::vector<const std::vector<double>*> models;  // nullptr: laminar
  if (o.turbulence != "sst") models.push_back(nullptr);
  if (o.turbulence != "laminar") models.push_back(&distance);
  std::vector<Result> results, sst_results;
  for (int r = 0; r < o.repeat; ++r) {
    for (const int t : threads) {
      for (const auto* model : models) {
        const Result res = run(o, mesh, t, hull, u_inf, s, model);
        if (model && models.size() > 1) {
          sst_results.push_back(res);
        } else {
          results.push_back(res);
        }
        if (model)
          std::printf("turbulence SST k-omega (%.1f %% of the step): ", 100 * res.turbulence);
        const double us = 1e6 * res.per_step / mesh.cells();
        std::printf(
            "threads=%d  us/cell/step %.3f   us/cell/outer %.3f   s/step %.4f   first step %.3f s  "
            " "
            "max Co %.3g\n",
            t, us, us / o.outer, res.per_step, res.first_step, res.max_co);
        std::printf(
            "  phase split: assembly %.1f %%, momentum solve %.1f %%, pressure %.1f %%, other %.1f "
            "%%; gradients (within these) %.1f %%   (iterations per step: pressure %.1f, momentum "
            "%.1f)\n",
            100 * res.assembly, 100 * (res.momentum - res.assembly), 100 * res.pressure,
            100 * (1 - res.momentum - res.pressure), 100 * res.gradient, res.pressure_iterations,
            res.momentum_iterations);
        if (model)
          std::printf("  k and omega iterations per step: %.1f, %.1f\n", res.k_iterations,
                      res.omega_iterations);
      }
    }
  }
  if (!sst_results.empty()) {
    for (std::size_t i = 0; i < sst_results.size(); ++i)
      std::printf("SST step / laminar step, %d thread(s), run %zu: %.3f\n",
                  threads[i % threads.size()], i / threads.size() + 1,
                  sst_results[i].per_step / results[i].per_step);
  }
  if (threads.size() > 1) {  // speed-ups against the first thread count, run by run
    for (int r = 0; r < o.repeat; ++r) {
      const auto base = results[static_cast<std::size_t>(r) * threads.size()].per_step;
      std::printf("speed-up against %d thread(s), run %d:", threads[0], r + 1);
      for (std::size_t k = 1; k < threads.size(); ++k)
        std::printf("  %d threads %.3f", threads[k],
                    base / results[static_cast<std::size_t>(r) * threads.size() + k].per_step);
      std::printf("\n");
    }
  }
  return 0;
}
