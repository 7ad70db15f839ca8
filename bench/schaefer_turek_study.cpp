// SPDX-License-Identifier: GPL-3.0-or-later
// Grid and time-step study of the Schaefer-Turek cylinder: one run per invocation, one summary
// line against the published intervals, optionally the 2D-2 cD and cL histories as CSV. Not a
// test: `auvloop validate schaefer-turek-2d1|2d2` is the check; this is how its grid and time
// step were chosen (docs/cfd.md, "Schaefer-Turek").
//   schaefer_turek_study --case 2d2 --m 32 --dt 0.002 [--radial 1] [--radial-ratio 8]
//                        [--downstream 4] [--downstream-ratio 6] [--outer 2]
//                        [--convection van-leer-skew] [--end 4] [--csv history.csv]
//   schaefer_turek_study --case 2d1 --m 24 --dt 0.008
//   schaefer_turek_study --m 24 --downstream 4 --polymesh CASE_DIR   (the grid for a peer solver,
//                        as an OpenFOAM polyMesh: bench/openfoam_cylinder.sh; nothing is run)
#include <cstdio>
#include <fstream>
#include <string>

#include <CLI/CLI.hpp>

#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/grid_io.hpp"

using namespace auvloop::engine;

namespace {
void add_grid_options(CLI::App& app, validation::ChannelGrid& g) {
  app.add_option("--m", g.m, "cells per side of the O-grid's box")->check(CLI::Range(8, 256));
  app.add_option("--radial", g.radial_cells_per_side, "radial cells per m")
      ->check(CLI::Range(0.25, 8.0));
  app.add_option("--radial-ratio", g.radial_ratio, "radial grading, outermost / innermost")
      ->check(CLI::Range(1.0, 100.0));
  app.add_option("--downstream", g.downstream_cells_per_side, "cells box to outlet per m")
      ->check(CLI::Range(0.5, 16.0));
  app.add_option("--downstream-ratio", g.downstream_ratio, "downstream grading, last / first")
      ->check(CLI::Range(1.0, 20.0));
}

int run_2d1(const validation::ChannelGrid& g, double dt) {
  const auto r = validation::schaefer_turek_2d1(g, dt);
  std::printf(
      "2d1 m %d cells %d: cD %.4f [5.57, 5.59] cL %.5f [0.0104, 0.0110] dp %.5f [0.1172, 0.1176] "
      "L_a %.5f [0.0842, 0.0852] %d steps %.0f s\n",
      g.m, r.cells, r.cd, r.cl, r.dp, r.la, r.steps, r.seconds);
  return 0;
}

int run_2d2(const validation::SheddingCase& c, const std::string& convection,
            const std::string& csv) {
  const auto r = validation::schaefer_turek_2d2(c);
  std::printf(
      "2d2 m %d cells %d dt %.5f outer %d %s: St %.4f [0.295, 0.305] cD_max %.4f [3.22, 3.24] "
      "cL_max %.4f [0.99, 1.01] drift %.1e Co %.2f %.0f s\n",
      c.grid.m, r.cells, c.dt, c.outer_iterations, convection.c_str(), r.strouhal, r.cd_max,
      r.cl_max, r.period_drift, r.max_courant, r.seconds);
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "t,cD,cL\n";
    for (std::size_t i = 0; i < r.t.size(); ++i)
      out << r.t[i] << ',' << r.cd[i] << ',' << r.cl[i] << '\n';
  }
  return r.periods > 0 ? 0 : 1;
}
}  // namespace

int main(int argc, char** argv) {
  validation::SheddingCase c;
  std::string which = "2d2", convection = "van-leer-skew", csv, polymesh;
  CLI::App app{"Schaefer-Turek 2D-1 / 2D-2: one grid and time-step combination"};
  app.add_option("--case", which, "2d1 (steady, Re 20) or 2d2 (shedding, Re 100)")
      ->check(CLI::IsMember({"2d1", "2d2"}));
  add_grid_options(app, c.grid);
  app.add_option("--dt", c.dt, "time step (s); 2d1: pseudo-time step")
      ->check(CLI::Range(1e-5, 0.05));
  app.add_option("--outer", c.outer_iterations, "2d2: PIMPLE outer iterations per step")
      ->check(CLI::Range(1, 20));
  app.add_option("--end", c.end_time, "2d2: end time (s)")->check(CLI::Range(1.0, 20.0));
  app.add_option("--convection", convection, "2d2: convection scheme")
      ->check(CLI::IsMember({"van-leer-skew", "van-leer", "linear-upwind"}));
  app.add_option("--csv", csv, "2d2: write t, cD, cL per step to this file");
  app.add_option("--polymesh", polymesh, "write the grid as an OpenFOAM polyMesh into this case");
  CLI11_PARSE(app, argc, argv);
  if (!polymesh.empty()) {
    const auto spec = validation::cylinder_spec(c.grid);
    auvloop::mesher::write_openfoam_polymesh(polymesh, auvloop::mesher::cylinder_channel(spec));
    std::printf("thickness %.17g\n", spec.thickness);
    return 0;
  }
  if (which == "2d1") return run_2d1(c.grid, c.dt);
  c.convection = fv::convection_from_string(convection);
  return run_2d2(c, convection, csv);
}
