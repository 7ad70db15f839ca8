// SPDX-License-Identifier: GPL-3.0-or-later
// Grid study of the SST flat plate (NASA TMR 2DZP): one run per invocation, Cf(0.97) and the
// plate drag against the TMR's CFL3D and FUN3D values (validation-data.md, table 4), the plate's
// y+ range, and optionally Cf(x) as CSV. Not a test: `auvloop validate flat-plate-sst` is the
// check; this is how its grids and settings were studied (docs/cfd.md, "Turbulence").
//   flat_plate_study --level 2 [--first-height 1e-6] [--plate-cells 256] [--upstream-cells 64]
//                    [--normal-cells 192] [--max-iterations 20000] [--threads T]
//                    [--from-level L] (grid sequencing: levels L, L - 1, ..., --level)
//                    [--wall any-y+|wall-function|resolved]
//                    [--relax-u 0.7] [--relax-p 0.3] [--relax-turbulence 0.7] [--csv cf.csv]
//                    [--fields cells.csv]
//                    [--polymesh CASE_DIR]   (the grid for a peer solver, nothing is run)
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/flat_plate_grid.hpp"
#include "auvloop/mesher/grid_io.hpp"

using namespace auvloop::engine;

int main(int argc, char** argv) {
  CLI::App app{"SST k-omega on the TMR flat plate: Cf(0.97) and CD against CFL3D / FUN3D"};
  validation::FlatPlateCase c;
  std::string csv, polymesh;
  app.add_option("--level", c.level, "grid level: 0 finest, each next one halves both directions")
      ->check(CLI::Range(0, 5));
  app.add_option("--first-height", c.spec.first_height, "first cell height at level 0 (m)")
      ->check(CLI::PositiveNumber);
  app.add_option("--plate-cells", c.spec.plate_cells, "cells along the plate at level 0")
      ->check(CLI::Range(2, 100000));
  app.add_option("--upstream-cells", c.spec.upstream_cells, "cells ahead of it at level 0")
      ->check(CLI::Range(2, 100000));
  app.add_option("--normal-cells", c.spec.normal_cells, "wall-normal cells at level 0")
      ->check(CLI::Range(2, 100000));
  app.add_option("--max-iterations", c.max_iterations, "SIMPLE iterations at most")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--check-every", c.check_every, "iterations between convergence checks")
      ->check(CLI::Range(1, 100000));
  app.add_option("--tolerance", c.tolerance, "relative change of Cf(0.97) and CD per check")
      ->check(CLI::PositiveNumber);
  app.add_option("--relax-u", c.relax_u, "momentum under-relaxation")->check(CLI::Range(0.01, 1.0));
  app.add_option("--relax-p", c.relax_p, "pressure under-relaxation")->check(CLI::Range(0.01, 1.0));
  app.add_option("--relax-turbulence", c.relax_turbulence, "k and omega under-relaxation")
      ->check(CLI::Range(0.01, 1.0));
  bool upwind = false;
  const std::map<std::string, turbulence::WallTreatment> walls{
      {"any-y+", turbulence::WallTreatment::any_y_plus},
      {"wall-function", turbulence::WallTreatment::wall_function},
      {"resolved", turbulence::WallTreatment::resolved}};
  app.add_option("--wall", c.wall,
                 "wall treatment: any-y+ (blended by y+), wall-function (the first cell's omega "
                 "fixed, as OpenFOAM's omegaWallFunction) or resolved (the TMR's k = 0, omega_w = "
                 "60 nu / (beta1 d1^2); y+ < 1)")
      ->transform(CLI::CheckedTransformer(walls, CLI::ignore_case));
  app.add_flag("--upwind-turbulence", upwind, "first-order upwind convection of k and omega");
  app.add_flag("--laminar", c.laminar, "no turbulence model (checks the steady solver alone)");
  app.add_option("--p-tolerance", c.pressure_tolerance, "pressure solve tolerance (relative)")
      ->check(CLI::PositiveNumber);
  app.add_option("--transport-tolerance", c.transport_tolerance,
                 "U, k and omega solve tolerance (relative)")
      ->check(CLI::PositiveNumber);
  app.add_option("--csv", csv, "write x, Cf of every plate face here");
  std::string fields;
  app.add_option(
      "--fields", fields,
      "write every cell's i, j, x, y, u, v, p, k, omega here (CSV; cell (i, j) is the i-th "
      "along the plate, the j-th from the wall)");
  app.add_option("--polymesh", polymesh, "write the grid as an OpenFOAM case's polyMesh and stop");
  int threads = 0, from_level = -1;
  app.add_option("--from-level", from_level,
                 "grid sequencing: solve this coarser level first, then each finer one from it")
      ->check(CLI::Range(0, 5));
  app.add_option("--threads", threads, "threads (default: all the machine's)")
      ->check(CLI::Range(1, 1024));
  CLI11_PARSE(app, argc, argv);
  std::optional<tbb::global_control> limit;
  if (threads > 0)
    limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  if (upwind) c.turbulence_convection = fv::Convection::upwind;
  if (!polymesh.empty()) {
    auvloop::mesher::write_openfoam_polymesh(polymesh,
                                             auvloop::mesher::flat_plate(c.spec, c.level));
    return 0;
  }
  c.progress = [](const std::string& line) {
    std::printf("  %s\n", line.c_str());
    std::fflush(stdout);
  };
  // Grid sequencing: levels from_level, from_level - 1, ..., level, each from the one before.
  validation::FlatPlateResult r;
  for (int l = std::max(from_level, c.level); l >= c.level; --l) {
    validation::FlatPlateResult previous = std::move(r);
    validation::FlatPlateCase step = c;
    step.level = l;
    step.start = l < std::max(from_level, c.level) ? &previous : nullptr;
    r = validation::flat_plate_sst(step);
    if (l > c.level)
      std::printf("level %d: %d cells, %d iterations, %.1f s; Cf(0.97) %.6f, CD %.6f\n", l, r.cells,
                  r.iterations, r.seconds, r.cf_097, r.cd);
  }
  std::printf(
      "level %d: %d cells, %d iterations (%s), %.1f s; Cf(0.97) %.6f (CFL3D 545x385 0.00269085, "
      "%+.2f %%), CD %.6f (0.00285332, %+.2f %%); plate y+ %.3g-%.3g (mean %.3g); bounded cells "
      "%ld, limiter cells %ld; final residuals U %.2e p %.2e k %.2e omega %.2e\n",
      c.level, r.cells, r.iterations, r.converged ? "converged" : "NOT converged", r.seconds,
      r.cf_097, 100 * (r.cf_097 / 0.00269085 - 1), r.cd, 100 * (r.cd / 0.00285332 - 1),
      r.y_plus.min, r.y_plus.max, r.y_plus.mean, r.bounded_cells, r.limited_cells,
      r.final_residuals[0], r.final_residuals[1], r.final_residuals[2], r.final_residuals[3]);
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "x,cf\n";
    for (std::size_t i = 0; i < r.x.size(); ++i) out << r.x[i] << ',' << r.cf[i] << '\n';
  }
  if (!fields.empty()) {
    const auto grid = auvloop::mesher::flat_plate(c.spec, c.level);
    const fv::Mesh mesh(grid);
    std::ofstream out(fields);
    out << "i,j,x,y,u,v,p,k,omega\n";
    out.precision(17);
    for (int j = 0; j < r.ny; ++j)
      for (int i = 0; i < r.nx; ++i) {
        const int cell = i + r.nx * j;
        const auto s = static_cast<std::size_t>(cell);
        out << i << ',' << j << ',' << mesh.centre(cell).x() << ',' << mesh.centre(cell).y();
        for (const auto& f : r.fields) out << ',' << f[s];
        out << '\n';
      }
  }
  return r.converged ? 0 : 1;
}
