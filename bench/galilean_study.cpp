// SPDX-License-Identifier: GPL-3.0-or-later
// Grid, time-step and scheme study of the unconfined cylinder at Re = 100 on its overset pair
// (the O-grid over a square box: `auvloop validate galilean-cylinder` is the check, this is how
// its grid is chosen; docs/cfd.md, "galilean-cylinder"). One run per invocation, fixed in the
// stream unless --towed; one summary line against the published ranges (validation-data.md
// section 3), optionally the cD and cL histories as CSV.
//   galilean_study [--around 64] [--radial 32] [--radial-ratio 8] [--outer-radius 1.5]
//                  [--extent 40] [--core-downstream 6] [--core-side 2] [--core-upstream 2]
//                  [--growth 1.1] [--dt 0.02] [--end 150] [--periods 5]
//                  [--convection van-leer-skew] [--towed] [--threads 2] [--csv history.csv]
#include <cstdio>
#include <fstream>
#include <string>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "auvloop/engine/validation.hpp"

using namespace auvloop;
namespace fv = engine::fv;

int main(int argc, char** argv) {
  mesher::UnconfinedCylinderSpec g;
  double dt = 0.02, end = 150;
  int periods = 5, threads = 2;
  bool towed = false;
  std::string convection = "van-leer-skew", csv;
  CLI::App app{"The unconfined cylinder at Re = 100 on its overset pair: one grid per run"};
  app.add_option("--around", g.around, "O-grid cells round the cylinder")
      ->capture_default_str()
      ->check(CLI::Range(16, 1024));
  app.add_option("--radial", g.radial_cells, "O-grid cells out to its outer radius")
      ->capture_default_str()
      ->check(CLI::Range(4, 512));
  app.add_option("--radial-ratio", g.radial_ratio, "O-grid grading, outermost / innermost")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  app.add_option("--outer-radius", g.outer_radius, "O-grid outer radius (diameters)")
      ->capture_default_str()
      ->check(CLI::Range(0.75, 10.0));
  app.add_option("--extent", g.extent, "box side (diameters)")
      ->capture_default_str()
      ->check(CLI::Range(10.0, 200.0));
  app.add_option("--core-upstream", g.core_upstream, "uniform core ahead (diameters)")
      ->capture_default_str();
  app.add_option("--core-downstream", g.core_downstream, "uniform core behind (diameters)")
      ->capture_default_str();
  app.add_option("--core-side", g.core_side, "uniform core to each side (diameters)")
      ->capture_default_str();
  app.add_option("--growth", g.growth, "largest cell-to-cell ratio outside the core")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1.5));
  app.add_option("--dt", dt, "time step (s; D = 1 m, U = 1 m/s)")
      ->capture_default_str()
      ->check(CLI::Range(1e-4, 0.2));
  app.add_option("--end", end, "end time (s)")->capture_default_str()->check(CLI::Range(1.0, 1e4));
  app.add_option("--periods", periods, "cL periods measured at the end")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  app.add_option("--convection", convection, "convection of U")
      ->capture_default_str()
      ->check(CLI::IsMember(
          {"upwind", "linear-upwind", "linear-upwind-limited", "van-leer", "van-leer-skew"}));
  app.add_flag("--towed", towed, "tow the grids through fluid at rest instead");
  app.add_option("--threads", threads, "threads")->capture_default_str()->check(CLI::Range(1, 64));
  app.add_option("--csv", csv, "write t, cD, cL per step to this file");
  CLI11_PARSE(app, argc, argv);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  const auto r = engine::validation::unconfined_cylinder(g, towed, dt, end, periods,
                                                         fv::convection_from_string(convection));
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "t,cd,cl\n";
    for (std::size_t i = 0; i < r.t.size(); ++i)
      out << r.t[i] << ',' << r.cd[i] << ',' << r.cl[i] << '\n';
  }
  std::printf(
      "%s around %d radial %d ratio %.3g outer %.3g extent %.3g core %.3g/%.3g/%.3g growth %.3g "
      "dt %.4g end %.4g %s: %d cells (%d active), max Courant %.2f; St %.4f [0.164, 0.165] mean "
      "cD %.4f [1.33, 1.35] cL amplitude %.4f [0.33, 0.339] over %d periods (drift %.1e); "
      "%.0f s\n",
      towed ? "towed" : "fixed", g.around, g.radial_cells, g.radial_ratio, g.outer_radius, g.extent,
      g.core_upstream, g.core_downstream, g.core_side, g.growth, dt, end, convection.c_str(),
      r.cells, r.active_cells, r.max_courant, r.strouhal, r.cd_mean, r.cl_amplitude, r.periods,
      r.period_drift, r.seconds);
  return r.periods > 0 ? 0 : 1;
}
