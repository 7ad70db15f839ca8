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
//             [--correctors C] [--pressure cholmod|cholmod-pcg|cg-ic|cg-dic|cg-jacobi]
//             [--threads T] [--re RE] [--co COURANT] [--2d 1] [--time bdf2|euler]
//             [--convection van-leer|linear-upwind|upwind]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include <tbb/global_control.h>

#include "auvloop/engine/fv/pimple.hpp"
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
  std::string convection = "van-leer";
  int n = 32, steps = 10, outer = 1, correctors = 2, threads = 1, two_d = 0;
  double re = 100, co = 1;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], v = argv[i + 1];
    std::map<std::string, std::string*> strings{{"--case", &o.case_name},
                                                {"--preset", &o.preset},
                                                {"--pressure", &o.pressure},
                                                {"--time", &o.time},
                                                {"--convection", &o.convection}};
    std::map<std::string, int*> ints{{"--n", &o.n},
                                     {"--steps", &o.steps},
                                     {"--outer", &o.outer},
                                     {"--correctors", &o.correctors},
                                     {"--threads", &o.threads},
                                     {"--2d", &o.two_d}};
    if (strings.contains(key))
      *strings[key] = v;
    else if (ints.contains(key))
      *ints[key] = std::atoi(v.c_str());
    else if (key == "--re")
      o.re = std::atof(v.c_str());
    else if (key == "--co")
      o.co = std::atof(v.c_str());
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      std::exit(2);
    }
  }
  return o;
}

fv::Convection convection(const std::string& s) {
  if (s == "upwind") return fv::Convection::upwind;
  if (s == "linear-upwind") return fv::Convection::linear_upwind;
  if (s == "van-leer") return fv::Convection::van_leer;
  std::fprintf(stderr, "unknown convection scheme %s\n", s.c_str());
  std::exit(2);
}

mesher::Grid cavity_grid(const Options& o) {
  const auto nodes = mesher::graded_nodes(0, 1, o.n);
  mesher::BoxPatches patches;
  patches.names = {"left", "right", "bottom", "lid", "front", "back"};
  if (o.two_d) patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  return mesher::cartesian_box(nodes, nodes, o.two_d ? std::vector<double>{0.0, 1.0 / o.n} : nodes,
                               patches, "cavity");
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(o.threads));
  const bool hull = o.case_name == "hull";
  const Eigen::Vector3d u_inf(-1.54, 0, 0);  // REMUS 100 design speed, body frame (x forward)
  const mesher::Grid grid = hull ? bench::hull_freestream_grid(o.preset, u_inf) : cavity_grid(o);
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = hull ? 1.05e-6 : 1.0 / o.re;
  s.outer_iterations = o.outer;
  s.pressure_correctors = o.correctors;
  s.bdf2 = o.time == "bdf2";
  s.convection = convection(o.convection);
  if (!o.pressure.empty()) s.pressure_solver = fv::symmetric_method_from_string(o.pressure);
  s.tolerance = 1e-6;
  s.max_courant = 1e9;  // a benchmark: report, do not stop
  // Courant number `co` of the free stream in the smallest cell, or at the lid speed.
  s.dt = hull ? bench::freestream_dt(mesh, u_inf, o.co) : o.co / o.n;
  fv::Pimple flow(mesh, s);
  const std::string pressure = fv::to_string(*flow.settings().pressure_solver);
  if (hull) {
    bench::set_freestream(flow, mesh, u_inf);
  } else {
    for (const char* wall : {"left", "right", "bottom", "front", "back"})
      if (!o.two_d || wall[0] == 'l' || wall[0] == 'r' || wall[0] == 'b')
        flow.U.fix(mesh, wall, {0, 0, 0});
    flow.U.fix(mesh, "lid", {1, 0, 0});
  }
  flow.initialise();
  double assembly = 0, momentum = 0, pressure_s = 0, gradient = 0, max_co = 0;
  int pressure_iterations = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < o.steps; ++k) {
    const auto r = flow.step();
    assembly += r.seconds_assembly;
    momentum += r.seconds_momentum;
    pressure_s += r.seconds_pressure;
    gradient += r.seconds_gradient;
    pressure_iterations += r.pressure_iterations;
    max_co = std::max(max_co, r.max_courant);
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cells = mesh.cells();
  const double per_step = 1e6 * total / (cells * o.steps);
  std::printf(
      "%s%s n=%d cells=%d steps=%d outer=%d correctors=%d pressure=%s time=%s "
      "convection=%s threads=%d dt=%.3g max Co=%.3g\n",
      hull ? ("hull-" + o.preset).c_str() : "cavity", hull ? "" : (o.two_d ? "2d" : "3d"),
      hull ? 0 : o.n, mesh.cells(), o.steps, o.outer, o.correctors, pressure.c_str(),
      o.time.c_str(), o.convection.c_str(), o.threads, s.dt, max_co);
  std::printf("  us/cell/step %.3f   us/cell/outer %.3f   s/step %.4f\n", per_step,
              per_step / o.outer, total / o.steps);
  std::printf(
      "  phase split: assembly %.1f %%, momentum solve %.1f %%, pressure %.1f %%, other %.1f %%; "
      "gradients (within these) %.1f %%   (pressure Krylov iterations per step %.1f)\n",
      100 * assembly / total, 100 * (momentum - assembly) / total, 100 * pressure_s / total,
      100 * (total - momentum - pressure_s) / total, 100 * gradient / total,
      static_cast<double>(pressure_iterations) / o.steps);
  return 0;
}
