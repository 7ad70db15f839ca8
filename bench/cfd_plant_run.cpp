// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant on a straight run, step by step: the measuring tool of the propeller's
// calibration and of the plant's cost (issue 18). Not a test: nothing is asserted.
//   1. engine::CfdPlant on the remus100 preset (--mesh), SST, --outer outer iterations, from the
//      body at --speed through water at rest (an impulsive start), fins at zero;
//   2. degrees of freedom --free: none (towed at --speed: the loads measured, the body held),
//      surge (self-propelled along x), horizontal (surge, sway, yaw) or 6dof; the propeller at
//      --rpm with the B-series curve of --pitch-ratio (Z 3, AE/A0 0.718) scaled in J by
//      --j-scale (KT(J) = KT_B(J / j_scale): an effective pitch; 1: the plain B-series);
//   3. per step a CSV row (--csv): t, u, v, r (rad/s), the walls' x force (pressure, shear), the
//      propeller's J, inflow speed, thrust and torque, the coupling's last change, the step's
//      wall clock and outer residual, its phases (s: fins, coupling, momentum, pressure,
//      turbulence, overset, other) and pressure iterations, then each wall's x force (pressure,
//      shear; N); a summary line every --every steps with the ETA.
//   --start-steps N --start-dt S: N steps of S first (an impulsive start's spike at the nose rim
//   needs a short step; then --dt).
//   --mesh-file F: F's [mesh] table (docs/mesher.md) on top of --mesh's preset (a grid study).
//   cfd_plant_run [--mesh coarse] [--dt 0.01] [--time 2] [--speed 1.54] [--rpm 1500]
//                 [--free none] [--pitch-ratio 0.5] [--j-scale 1] [--threads 2] [--csv F]
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "auvloop/engine/cfd_plant.hpp"
#include "auvloop/engine/vehicle_model.hpp"
#include "auvloop/geometry/input.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

using namespace auvloop;

int main(int argc, char** argv) {
  CLI::App app{"The CFD plant on a straight run (towed or self-propelled), step by step"};
  std::string mesh = "coarse", free = "none", csv, convection = "linear-upwind-limited";
  double dt = 0.01, time = 2, speed = 1.54, rpm = 1500, pitch_ratio = 0.5, j_scale = 1;
  int threads = 2, outer = 5, every = 10, start_steps = 0;
  double start_dt = 0.002, nu = engine::CfdPlantSettings{}.nu, intermediate_tolerance = 0;
  app.add_option("--mesh", mesh, "mesh preset")->check(CLI::IsMember({"coarse", "medium", "fine"}));
  app.add_option("--dt", dt, "time step (s)")->check(CLI::PositiveNumber);
  app.add_option("--start-steps", start_steps,
                 "this many steps of --start-dt first (the impulsive start's spike at the nose)");
  app.add_option("--start-dt", start_dt, "their time step (s)")->check(CLI::PositiveNumber);
  app.add_option("--time", time, "simulated time (s)")->check(CLI::PositiveNumber);
  app.add_option("--speed", speed, "initial (and, towed, held) speed (m/s)");
  app.add_option("--rpm", rpm, "propeller speed (rev/min)")->check(CLI::NonNegativeNumber);
  app.add_option("--free", free, "degrees of freedom")
      ->check(CLI::IsMember({"none", "surge", "horizontal", "6dof"}));
  app.add_option("--pitch-ratio", pitch_ratio, "B-series P/D of the curve's shape");
  app.add_option("--j-scale", j_scale, "KT(J) = KT_B(J / j_scale)")->check(CLI::PositiveNumber);
  app.add_option("--intermediate-tolerance", intermediate_tolerance,
                 "pressure tolerance of the outer iterations but the last (0: 1e-8)");
  app.add_option("--nu", nu, "kinematic viscosity (m^2/s)")->check(CLI::PositiveNumber);
  app.add_option("--outer", outer, "outer iterations per step")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "threads")->check(CLI::PositiveNumber);
  app.add_option("--every", every, "a summary line every this many steps");
  app.add_option("--csv", csv, "per-step CSV file");
  app.add_option("--convection", convection, "of U (fv::convection_from_string)");
  double relax_u = 1, relax_p = 1;
  app.add_option("--relax-u", relax_u, "U's under-relaxation, outer iterations but the last");
  app.add_option("--relax-p", relax_p, "p's under-relaxation, outer iterations but the last");
  int correctors = 2;
  app.add_option("--pressure-correctors", correctors, "per outer iteration")
      ->check(CLI::PositiveNumber);
  double tolerance = 1e-8;
  app.add_option("--tolerance", tolerance, "the last outer iteration's linear solves, relative")
      ->check(CLI::PositiveNumber);
  bool final_only = false;
  app.add_flag("--turbulence-final-only", final_only, "SST in the last outer iteration only");
  double max_courant = 0, max_speed = 20;
  app.add_option("--max-courant", max_courant, "divergence guard (0: none)");
  app.add_option("--max-speed", max_speed, "divergence guard on |U| (m/s; 0: none)");
  bool laminar = false;
  app.add_flag("--laminar", laminar, "no turbulence model");
  bool no_fins = false, no_propeller = false;
  app.add_flag("--no-fins", no_fins, "the hull alone (remus-resistance's bare hull)");
  app.add_flag("--no-propeller", no_propeller, "no disk at all (towed resistance; rpm 0)");
  std::string mesh_file;
  app.add_option("--mesh-file", mesh_file, "a TOML file whose [mesh] table goes on top of --mesh")
      ->check(CLI::ExistingFile);
  CLI11_PARSE(app, argc, argv);
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  const auto model = engine::load_vehicle_model("preset:remus100");
  auto vehicle = model.vehicle;
  if (no_fins) vehicle.fin_set.fins.clear();
  engine::CfdPlantSettings s;  // 1.
  s.mesh = mesh;
  if (!mesh_file.empty()) {
    try {
      auto doc = input::Document::load(mesh_file);
      s.mesh_settings = mesher::read_mesh_settings(doc.root().table("mesh"), vehicle, mesh);
      doc.check();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 2;
    }
  }
  s.outer_iterations = outer;
  s.nu = nu;
  s.intermediate_tolerance = intermediate_tolerance;
  s.reference_speed = speed;
  s.convection = engine::fv::convection_from_string(convection);
  s.relax_u = relax_u;
  s.relax_p = relax_p;
  s.pressure_correctors = correctors;
  s.tolerance = tolerance;
  s.turbulence_final_only = final_only;
  s.max_courant = max_courant;
  s.max_flow_speed = max_speed;
  s.propeller = !no_propeller;
  s.sst = !laminar;
  if (free == "none") {  // 2.
    s.free = {false, false, false, false, false, false};
  } else if (free == "surge") {
    s.free = {true, false, false, false, false, false};
  } else if (free == "horizontal") {
    s.free = engine::DfbiBody::horizontal;
  }
  s.added_mass = engine::prestero_added_mass(model.hydrodynamics);
  const engine::BSeries prop{3, pitch_ratio, 0.718};
  s.curve = [prop, j_scale](double J) {
    auto p = engine::b_series(prop, J / j_scale);
    p.J = J;
    return p;
  };
  const auto t0 = std::chrono::steady_clock::now();
  engine::CfdPlant plant(vehicle, s);
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  engine::BodyState initial;
  initial.nu[0] = speed;
  plant.reset(initial);
  std::printf("remus100 %s: %d cells, set up in %.1f s; dt %g s, %d outer iterations, %d threads\n",
              mesh.c_str(), plant.cells(), setup, dt, outer, threads);
  std::ofstream out;
  if (!csv.empty()) {
    out.open(csv);
  }
  bool header = false;  // written after the first step, when the walls' names are known
  const int steps =
      start_steps +
      static_cast<int>(std::lround(std::max(0.0, time - start_steps * start_dt) / dt));
  engine::ActuatorValues a;
  a.rpm = rpm;
  double spent = 0;
  for (int n = 1; n <= steps; ++n) {  // 3.
    const auto result = plant.advance(a, n <= start_steps ? start_dt : dt);
    if (const auto* f = std::get_if<engine::PlantFailure>(&result)) {
      std::printf("step %d failed: %s\n", n, f->reason.c_str());
      return 1;
    }
    const auto& r = plant.last();
    spent += r.seconds;
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
    for (const auto& [name, f] : r.walls) {
      p += f.pressure;
      v += f.viscous;
    }
    const auto& st = plant.state();
    if (out && !header) {
      out << "t,u,v,r,Fx_pressure,Fx_shear,J,inflow,thrust,torque,coupling_change,seconds,"
             "outer_residual,s_fins,s_coupling,s_momentum,s_pressure,s_turbulence,s_overset,"
             "s_other,pressure_iterations,courant,max_speed";
      for (const auto& [name, f] : r.walls) out << fmt::format(",Fx_p_{0},Fx_v_{0}", name);
      out << "\n";
      header = true;
    }
    if (out) {
      out << fmt::format(
          "{:.6g},{:.9g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},"
          "{:.3g},{:.4g},{:.3g}",
          r.time, st.u(), st.v(), st.r(), p.x(), v.x(), r.J, r.inflow_speed, r.thrust, r.torque,
          r.coupling_change, r.seconds, r.flow.outer_residual);
      const auto& fl = r.flow;
      out << fmt::format(",{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{},{:.4g},{:.4g}",
                         r.seconds_fins, r.seconds_coupling, fl.seconds_momentum,
                         fl.seconds_pressure, fl.seconds_turbulence, fl.seconds_overset,
                         fl.seconds_other, fl.pressure_iterations, fl.max_courant, fl.max_speed);
      for (const auto& [name, f] : r.walls)
        out << fmt::format(",{:.6g},{:.6g}", f.pressure.x(), f.viscous.x());
      out << "\n";
    }
    if (n % every == 0 || n == steps)
      std::printf(
          "t %.3f s: u %.4f m/s, walls Fx %.3f N (pressure %.3f, shear %.3f), J %.3f, V_a "
          "%.3f m/s, T %.3f N, Q %.4f N m; Courant %.3g, max |U| %.3g m/s; %.2f s/step, ETA "
          "%.0f s\n",
          r.time, st.u(), p.x() + v.x(), p.x(), v.x(), r.J, r.inflow_speed, r.thrust, r.torque,
          r.flow.max_courant, r.flow.max_speed, spent / n, spent / n * (steps - n));
    std::fflush(stdout);
  }
  return 0;
}
