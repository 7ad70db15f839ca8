// SPDX-License-Identifier: GPL-3.0-or-later
// The REMUS 100 hull alone in a steady free stream with SST k-omega: its drag split into pressure
// and shear, on the preset's hull grid, against simpleFoam on the very same grid
// (bench/openfoam_hull.sh). The check of the remus-overset-sst drag (docs/overset-flow.md,
// "Session 23"). Not a test: nothing is asserted.
//   1. grid: bench::hull_freestream_grid (the hull grid, no fins, no overset), its outer boundary
//      split into "inflow" (faces with U_inf . S < 0: U, k, omega of the free stream fixed) and
//      "outflow" (p = 0, zero gradient for U, k, omega); the hull a no-slip wall with SST's wall
//      treatment (--wall); the stream U_inf = (-U, 0, 0), the vehicle running forward (+x);
//   2. steady SIMPLE (PimpleSettings::steady) from the free stream, U convected by --convection,
//      k and omega by --turbulence-convection, until the drag's change still to come
//      (extrapolated from the last two changes over --check-every iterations, as flat_plate_sst
//      does) is below --tolerance (relative);
//   3. the hull's force (fv::patch_force): the drag (the force along U_inf) apart in pressure and
//      shear, in m^4/s^2 and in N for sea water (rho = 1025 kg/m^3), and the ITTC-57 friction
//      line's shear on the wetted area for comparison; the hull's y+.
//   hull_drag_study [--preset coarse] [--speed 1.54] [--convection upwind] [--polymesh DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/output.hpp"
#include "auvloop/engine/turbulence/sst_model.hpp"
#include "auvloop/engine/turbulence/wall_distance.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/grid_io.hpp"
#include "hull_case.hpp"

using namespace auvloop;
namespace fv = engine::fv;
namespace turbulence = engine::turbulence;

int main(int argc, char** argv) {
  CLI::App app{
      "The REMUS 100 hull alone in a steady stream with SST k-omega: drag in pressure and shear "
      "(peer: bench/openfoam_hull.sh, simpleFoam on the same grid)"};
  std::string preset = "coarse", convection = "upwind", turbulence_convection = "upwind";
  std::string wall = "any-y-plus", polymesh, vtk;
  double speed = 1.54, relax_u = 0.7, relax_p = 0.3, relax_turbulence = 0.7;
  double tolerance = 1e-4, intensity = 0.01, viscosity_ratio = 10, nu = 1e-6;
  int max_iterations = 5000, check_every = 50, threads = 0;
  bool laminar = false;
  app.add_option("--preset", preset, "mesh preset of the hull grid")->capture_default_str();
  app.add_option("--speed", speed, "the vehicle's speed (m/s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--convection", convection, "convection of U")
      ->capture_default_str()
      ->check(CLI::IsMember(
          {"upwind", "linear-upwind", "linear-upwind-limited", "van-leer", "van-leer-skew"}));
  app.add_option("--turbulence-convection", turbulence_convection, "convection of k and omega")
      ->capture_default_str()
      ->check(CLI::IsMember({"upwind", "linear-upwind-limited", "van-leer", "van-leer-skew"}));
  const std::map<std::string, turbulence::WallTreatment> walls{
      {"any-y-plus", turbulence::WallTreatment::any_y_plus},
      {"wall-function", turbulence::WallTreatment::wall_function}};
  app.add_option("--wall", wall,
                 "SST wall treatment: any-y-plus (auvloop's default), wall-function "
                 "(OpenFOAM's omegaWallFunction + nutUSpaldingWallFunction counterpart)")
      ->capture_default_str()
      ->check(CLI::IsMember({"any-y-plus", "wall-function"}));
  app.add_option("--nu", nu, "kinematic viscosity (m^2/s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--intensity", intensity, "free-stream turbulence intensity")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--viscosity-ratio", viscosity_ratio, "free-stream nu_t / nu")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--max-iterations", max_iterations, "SIMPLE iterations at most")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--check-every", check_every, "iterations between convergence checks")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--tolerance", tolerance, "relative change of the drag still to come")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--relax-u", relax_u, "momentum under-relaxation")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 1.0));
  app.add_option("--relax-p", relax_p, "pressure under-relaxation")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 1.0));
  app.add_option("--relax-turbulence", relax_turbulence, "k and omega under-relaxation")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 1.0));
  app.add_flag("--laminar", laminar, "no turbulence model");
  app.add_option("--polymesh", polymesh,
                 "write the grid (patches hull, inflow, outflow) as an OpenFOAM case's polyMesh "
                 "and stop");
  app.add_option("--vtk", vtk,
                 "write the converged fields (U, p, k, omega, nu_t) into this directory");
  app.add_option("--threads", threads, "threads (default: all the machine's)")
      ->check(CLI::Range(1, 1024));
  CLI11_PARSE(app, argc, argv);
  std::optional<tbb::global_control> limit;
  if (threads > 0)
    limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));

  // 1.
  const Eigen::Vector3d u_inf(-speed, 0, 0);
  const mesher::Grid grid = bench::hull_freestream_grid(preset, u_inf);
  if (!polymesh.empty()) {
    mesher::write_openfoam_polymesh(polymesh, grid);
    return 0;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const fv::Mesh mesh(grid);
  const fv::Mesh* meshes[] = {&mesh};
  const turbulence::WallDistances distances(meshes);
  fv::PimpleSettings s;
  s.nu = nu;
  s.steady = true;
  s.dt = 1;  // a label: steady
  s.outer_iterations = 1;
  s.pressure_correctors = 1;
  s.relax_u = relax_u;
  s.relax_p = relax_p;
  s.tolerance = 1e-8;
  s.momentum_tolerance = 1e-6;
  s.max_courant = 1e30;
  s.convection = fv::convection_from_string(convection);
  fv::Pimple flow(mesh, s);
  turbulence::SstSettings ts;
  ts.nu = nu;
  ts.freestream = turbulence::freestream_from_intensity(speed, intensity, viscosity_ratio, nu);
  ts.relax = relax_turbulence;
  ts.convection = fv::convection_from_string(turbulence_convection);
  ts.wall = walls.at(wall);
  ts.tolerance = 1e-6;
  const auto d = distances.of(0);
  turbulence::SstModel sst(mesh, {d.begin(), d.end()}, ts);
  bench::set_freestream(flow, mesh, u_inf);
  sst.inlet("inflow");
  if (!laminar) flow.set_turbulence(&sst);
  flow.initialise();
  std::printf(
      "REMUS 100 hull alone (%s hull grid, %d cells), U %.3g m/s, nu %.3g m^2/s, %s, U by %s, "
      "k and omega by %s, wall %s; free stream k %.3g m^2/s^2, omega %.3g 1/s\n",
      preset.c_str(), mesh.cells(), speed, nu, laminar ? "laminar" : "SST k-omega",
      convection.c_str(), turbulence_convection.c_str(), wall.c_str(), ts.freestream.k,
      ts.freestream.omega);

  // 2. and 3.
  const Eigen::Vector3d along = u_inf.normalized();
  const auto drag = [&] {
    const auto f = fv::patch_force(flow, "hull");
    return std::pair{f.pressure.dot(along), f.viscous.dot(along)};
  };
  double previous = 0, change_before = 0;
  bool converged = false;
  int it = 1;
  for (; it <= max_iterations; ++it) {
    fv::StepReport report;
    try {
      report = flow.step();
    } catch (const fv::DivergenceError& e) {
      std::printf("diverged at iteration %d: %s\n", it, e.what());
      return 1;
    }
    if (it % check_every != 0) continue;
    const auto [pressure, shear] = drag();
    const double total = pressure + shear;
    std::printf(
        "  iteration %d: drag %.6e m^4/s^2 (pressure %.6e, shear %.6e); residuals U %.2e p "
        "%.2e k %.2e omega %.2e\n",
        it, total, pressure, shear, report.momentum_residual, report.pressure_residual,
        report.turbulence.k_residual, report.turbulence.omega_residual);
    std::fflush(stdout);
    // What is still to come, from the last two changes (geometric convergence: Aitken).
    const double change = std::abs(total - previous);
    if (previous != 0 && engine::validation::remaining_change(change, change_before) <=
                             tolerance * std::abs(total)) {
      converged = true;
      break;
    }
    change_before = previous != 0 ? change : 0.0;
    previous = total;
  }
  const auto [pressure, shear] = drag();
  double wetted = 0;
  const auto& hull = grid.patches[static_cast<std::size_t>(fv::patch_index(mesh, "hull"))];
  for (int i = 0; i < hull.size; ++i) wetted += mesh.area(hull.start + i).norm();
  double length = 0;
  {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < hull.size; ++i) {
      lo = std::min(lo, mesh.face_centre(hull.start + i).x());
      hi = std::max(hi, mesh.face_centre(hull.start + i).x());
    }
    length = hi - lo;
  }
  const double re = speed * length / nu;
  const double cf_ittc = 0.075 / std::pow(std::log10(re) - 2, 2);
  const double ittc = cf_ittc * 0.5 * speed * speed * wetted;
  constexpr double rho = 1025;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "%s after %d iterations (%.0f s): drag %.5e m^4/s^2 = %.3f N in sea water: pressure %.5e "
      "(%.3f N), shear %.5e (%.3f N); ITTC-57 shear on the wetted area %.4f m^2 (Re_L %.3g over "
      "L %.3f m) %.5e (%.3f N)\n",
      converged ? "converged" : "NOT converged", std::min(it, max_iterations), seconds,
      pressure + shear, rho * (pressure + shear), pressure, rho * pressure, shear, rho * shear,
      wetted, re, length, ittc, rho * ittc);
  if (!laminar)
    for (const auto& y : sst.y_plus())
      std::printf("y+ on %s: min %.3g, mean %.3g, max %.3g\n", y.patch.c_str(), y.min, y.mean,
                  y.max);
  if (!vtk.empty()) {
    fv::VtkSeries out(vtk, "hull");
    out.write(flow, {{"k", &sst.k}, {"omega", &sst.omega}, {"nu_t", &sst.nu_t}});
    std::printf("fields: %s\n", out.pvd().c_str());
  }
  return converged ? 0 : 3;
}
