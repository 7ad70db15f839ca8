// SPDX-License-Identifier: GPL-3.0-or-later
// The overset share of a time step on the REMUS 100 system (issue 17: at most 15 % on coarse),
// and the explicit against the implicit coupling on it. Not a test: nothing is asserted.
//   1. validation::remus_overset (the remus-overset case's driver): laminar, the body at
//      1.54 m/s from an impulsive start, --straight steps with the fins at rest, then --steps
//      steps with one fin (--fin K) or every fin (--fin -1) turning at 30 deg/s;
//   2. per turning step: the re-assembly (the mesher's incremental update, before the step),
//      Pimple::step's wall clock and its overset part (StepReport::seconds_overset: status
//      carry-over, fringe rows, interpolation, mass balance, interface flux);
//   3. the share = (re-assembly + overset part) / (re-assembly + step), the median and the sum
//      over the turning steps; with the convergence figures of a step (initial momentum residual
//      of the last outer iteration, pressure iterations) and the mass figures (continuity error,
//      interface flux), per mass balance form, coupling and thread count in turn, in one
//      process: the ratios of one run are at the same machine load. The bordered balance's
//      extra work is inside the pressure solve, not in the overset part: compare the pressure
//      stage (StepReport::seconds_pressure) with --balance bordered,response; with
//      --balance off,bordered the bordered run also prices its extra pressure iterations over
//      the unbalanced run's (a count, the same on any machine) at its own cost per iteration.
//   bench_overset [--preset coarse] [--straight 5] [--steps 20] [--fin 0] [--dt 0.002]
//                 [--coupling explicit,implicit] [--threads 1,2] [--outer 3]
//                 [--balance bordered,response] [--sst]
//   --sst: SST k-omega on the coupling (remus-overset-sst's set-up, the fins' wall distances
//   followed in the re-assembly, which is then counted in it), the step the CFD plant takes;
//   --convection: of U (upwind, the case's default; linear-upwind; van-leer-skew). Each run ends
//   with the hull's drag at its last step, pressure and shear apart; --drag-csv FILE writes
//   t, drag, pressure drag of every step of the last run (m^4/s^2); --ambient and
//   --turbulence-gs: the SST's ambient sources and k, omega solver (RemusOversetRun).
//   --profile-csv FILE --profile-every S: every S seconds of the last run, the hull's drag in
//   --stations equal slices along x (pressure and shear apart, m^4/s^2) and, per slice, the
//   area-weighted mean over its wall faces of the first cell's k / (omega nu) (SST: the eddy
//   viscosity ratio away from the limiter) and of the wall face's nu_eff / nu (the law of the
//   wall's nu + nu_t,w): where a boundary layer is turbulent and where it relaminarises.
//   --checkpoint FILE --checkpoint-step N writes the last run's exact state after step N, and
//   --restart FILE continues every run from such a file (a straight-phase step, the same
//   options): a late event of a long run examined again in seconds.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/vehicle_overset.hpp"
#include "auvloop/engine/validation.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {
std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One hull profile (--profile-csv): per slice along x its wall area, drag (pressure, shear),
// and the area-weighted means of the first cell's k / (omega nu) and the face's nu_eff / nu.
void write_profile(std::ostream& out, const fv::Pimple& flow, int stations) {
  const auto& mesh = flow.mesh();
  const std::string hull = fv::VehicleOverset::hull_wall();
  const auto faces = fv::face_forces(flow, hull);
  const fv::ScalarField *k = nullptr, *omega = nullptr;
  if (const auto* model = flow.turbulence())
    for (const auto* field : model->fields()) {
      if (field->name == "k") k = field;
      if (field->name == "omega") omega = field;
    }
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < faces.counted.size(); ++i) {
    const double x = mesh.face_centre(faces.start + static_cast<int>(i)).x();
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const auto n = static_cast<std::size_t>(stations);
  std::vector<double> area(n), pressure(n), shear(n), nut(n), nu_eff(n);
  const double nu = flow.settings().nu;
  for (std::size_t i = 0; i < faces.counted.size(); ++i) {
    if (!faces.counted[i]) continue;
    const int f = faces.start + static_cast<int>(i);
    const double x = mesh.face_centre(f).x();
    const auto s = std::min(n - 1, static_cast<std::size_t>((x - lo) / (hi - lo) * stations));
    const double a = mesh.area(f).norm();
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    area[s] += a;
    pressure[s] -= faces.pressure[i].x();
    shear[s] -= faces.viscous[i].x();
    if (k != nullptr && omega != nullptr) nut[s] += a * k->cells[P] / (omega->cells[P] * nu);
    if (const auto* model = flow.turbulence())
      nu_eff[s] += a * model->nu_eff()[static_cast<std::size_t>(f)] / nu;
  }
  for (std::size_t s = 0; s < n; ++s) {
    const double a = area[s] > 0 ? area[s] : 1.0;
    out << flow.time() << ',' << lo + (hi - lo) * static_cast<double>(s) / stations << ','
        << lo + (hi - lo) * static_cast<double>(s + 1) / stations << ',' << area[s] << ','
        << pressure[s] << ',' << shear[s] << ',' << nut[s] / a << ',' << nu_eff[s] / a << '\n';
  }
  out.flush();
}

// One row of --step-csv.
void write_step(std::ostream& out, const fv::Pimple& flow, const fv::StepReport& r) {
  // The hull's wall faces in the flow (no forces needed: face_forces would take U's gradients).
  const auto& mesh = flow.mesh();
  const auto& hull = mesh.grid().patches[static_cast<std::size_t>(
      fv::patch_index(mesh, fv::VehicleOverset::hull_wall()))];
  const auto* overset = flow.overset();
  double omega_min = 1e300, k_max = 0;
  if (const auto* model = flow.turbulence())
    for (const auto* field : model->fields())
      for (int f = hull.start; f < hull.start + hull.size; ++f) {
        const int cell = mesh.owner(f);
        if (overset != nullptr && !overset->in_flow(cell)) continue;
        const double v = field->cells[static_cast<std::size_t>(cell)];
        if (field->name == "omega") omega_min = std::min(omega_min, v);
        if (field->name == "k") k_max = std::max(k_max, v);
      }
  const auto& t = r.turbulence;
  out << flow.time() << ',' << r.pressure_iterations << ',' << t.k_iterations << ','
      << t.omega_iterations << ',' << t.k_residual << ',' << t.omega_residual << ','
      << t.bounded_cells << ',' << t.limited_cells << ',' << omega_min << ',' << k_max << '\n';
  out.flush();
}

struct Turning {  // the turning steps' figures of one run
  std::vector<double> share, step, reassembly, walls, overset, residual;
  std::vector<double> pressure_iterations, pressure_seconds;
  double continuity = 0, interface_flux = 0;
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "The overset share of a REMUS time step with fins turning at 30 deg/s, per coupling and "
      "thread count (issue 17)"};
  engine::validation::RemusOversetRun base;
  int straight_steps = 5, turning_steps = 20;
  std::string couplings = "explicit,implicit", threads = "1,2", balances = "bordered";
  base.turning_fin = 0;
  app.add_option("--preset", base.preset, "Mesh preset")->capture_default_str();
  app.add_option("--straight", straight_steps, "Steps with the fins at rest first")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--steps", turning_steps, "Steps with the fin(s) turning (measured)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--fin", base.turning_fin, "The fin that turns (0-3), or -1 for every fin")
      ->capture_default_str()
      ->check(CLI::Range(-1, 3));
  app.add_option("--dt", base.dt, "Time step (s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--outer", base.outer_iterations, "Outer iterations a step")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--coupling", couplings, "Comma-separated: explicit, implicit")
      ->capture_default_str();
  app.add_option("--threads", threads, "Comma-separated thread counts")->capture_default_str();
  app.add_option("--balance", balances,
                 "Comma-separated overset mass balance forms: bordered (one bordered pressure "
                 "solve; cg-amg and the explicit coupling only, else the response form), "
                 "response (one more solve per open component), off (none: the baseline "
                 "that prices the balance)")
      ->capture_default_str();
  std::string convection = "upwind";
  app.add_option("--convection", convection, "Convection of U")
      ->capture_default_str()
      ->check(CLI::IsMember({"upwind", "linear-upwind", "linear-upwind-limited", "van-leer-skew"}));
  std::string drag_csv;
  app.add_option("--drag-csv", drag_csv, "Write t, drag, pressure drag per step of the last run");
  std::string profile_csv;
  double profile_every = 0.25;
  int stations = 32;
  app.add_option("--profile-csv", profile_csv,
                 "Write the hull's drag and eddy viscosity per slice along x every "
                 "--profile-every seconds of the last run");
  std::string step_csv;
  app.add_option("--step-csv", step_csv,
                 "Write per step of the last run: the turbulence solves' iterations, residuals "
                 "and bounded cells, and the hull's first cells' smallest omega and largest k");
  app.add_option("--profile-every", profile_every, "Seconds between hull profiles")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--stations", stations, "Slices along x of a hull profile")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  std::string checkpoint_to, restart;
  app.add_option("--checkpoint", checkpoint_to,
                 "Write the state after step --checkpoint-step of the last run to this file");
  app.add_option("--checkpoint-step", base.checkpoint_step, "The step --checkpoint writes")
      ->check(CLI::PositiveNumber);
  app.add_option("--restart", restart,
                 "Continue every run from this --checkpoint file (a straight-phase step, the "
                 "same options)")
      ->check(CLI::ExistingFile);
  app.add_flag("--ambient", base.ambient_sources,
               "SST: ambient sources that hold the free stream (Spalart-Rumsey)");
  bool gs = false;
  app.add_flag("--turbulence-gs", gs,
               "SST: k and omega by BiCGSTAB preconditioned by Gauss-Seidel sweeps (default: "
               "Jacobi)");
  app.add_flag("--sst", base.sst,
               "SST k-omega (the wall distances of the turned fins are part of the re-assembly)");
  CLI11_PARSE(app, argc, argv);
  if (gs) base.turbulence_solver = fv::AsymmetricMethod::bicgstab_gs;
  base.convection = fv::convection_from_string(convection);
  base.restart = restart;
  if (!checkpoint_to.empty() && base.checkpoint_step <= 0) {
    std::fprintf(stderr, "--checkpoint needs --checkpoint-step\n");
    return 2;
  }
  base.straight = straight_steps * base.dt;
  base.turning = turning_steps * base.dt;
  base.fin_rate = 30 * std::numbers::pi / 180;

  std::printf(
      "REMUS %s, %s, U by %s, fin %s turning at 30 deg/s, dt %g s, %d straight + %d turning steps, "
      "%d outer iterations\n",
      base.preset.c_str(), base.sst ? "SST k-omega" : "laminar", convection.c_str(),
      base.turning_fin < 0 ? "(every)" : std::to_string(base.turning_fin).c_str(), base.dt,
      straight_steps, turning_steps, base.outer_iterations);
  // Per coupling and thread count: the unbalanced run's median step less its overset part (the
  // step without overset work), when --balance lists off before the other forms.
  std::map<std::string, double> plain, plain_iterations;
  for (const auto& balance : split(balances)) {
    try {
      base.mass_balance = fv::mass_balance_from_string(balance);
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "--balance: %s\n", e.what());
      return 2;
    }
    for (const auto& coupling : split(couplings)) {
      for (const auto& t : split(threads)) {
        const int n_threads = std::stoi(t);
        if (n_threads < 1) {
          std::fprintf(stderr, "--threads: thread counts >= 1, got %s\n", t.c_str());
          return 2;
        }
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(n_threads));
        auto run = base;
        run.checkpoint_to = checkpoint_to;
        try {
          run.coupling = fv::overset_coupling_from_string(coupling);
        } catch (const std::invalid_argument& e) {
          std::fprintf(stderr, "--coupling: %s\n", e.what());
          return 2;
        }
        Turning m;
        run.on_step = [&](const fv::StepReport& r, double reassembly, double walls,
                          double seconds) {
          if (r.step <= straight_steps) return;  // the run's step number, a restart's too
          m.share.push_back((reassembly + r.seconds_overset) / (reassembly + seconds));
          m.step.push_back(reassembly + seconds);
          m.reassembly.push_back(reassembly);
          m.walls.push_back(walls);
          m.overset.push_back(r.seconds_overset);
          m.residual.push_back(r.outer_residual);
          m.pressure_iterations.push_back(r.pressure_iterations);
          m.pressure_seconds.push_back(r.seconds_pressure);
          m.continuity = std::max(m.continuity, r.continuity_error);
          m.interface_flux = std::max(m.interface_flux, r.interface_flux);
        };
        std::ofstream profile;
        double next_profile = profile_every;
        if (!profile_csv.empty()) {
          profile.open(profile_csv);
          if (!profile) {
            std::fprintf(stderr, "--profile-csv: cannot write %s\n", profile_csv.c_str());
            return 2;
          }
          profile << "t,x_lo,x_hi,area,drag_pressure,drag_shear,nut_over_nu,nu_eff_over_nu\n";
          run.after_step = [&](const fv::Pimple& flow) {
            if (flow.time() + 0.5 * run.dt < next_profile) return;
            next_profile += profile_every;
            write_profile(profile, flow, stations);
          };
        }
        std::ofstream steps;
        fv::StepReport last;
        if (!step_csv.empty()) {
          steps.open(step_csv);
          if (!steps) {
            std::fprintf(stderr, "--step-csv: cannot write %s\n", step_csv.c_str());
            return 2;
          }
          steps << "t,pressure_iterations,k_iterations,omega_iterations,k_residual,omega_residual,"
                   "bounded_cells,limited_cells,hull_omega_min,hull_k_max\n";
          const auto on_step = run.on_step;
          run.on_step = [&, on_step](const fv::StepReport& r, double a, double w, double s) {
            last = r;
            on_step(r, a, w, s);
          };
          const auto after = run.after_step;
          run.after_step = [&, after](const fv::Pimple& flow) {
            if (after) after(flow);
            write_step(steps, flow, last);
          };
        }
        const auto result = engine::validation::remus_overset(run);
        if (!result.failure.empty())
          std::printf("  %s, %d threads: failed after %d steps: %s\n", coupling.c_str(), n_threads,
                      result.steps, result.failure.c_str());
        if (!result.drag.empty())
          std::printf("  hull drag at t = %.4f s: %.5e m^4/s^2 (pressure %.5e, shear %.5e)\n",
                      result.t.back(), result.drag.back(), result.drag_pressure.back(),
                      result.drag.back() - result.drag_pressure.back());
        if (!drag_csv.empty()) {
          std::ofstream out(drag_csv);
          out << "t,drag,drag_pressure\n";
          for (std::size_t i = 0; i < result.t.size(); ++i)
            out << result.t[i] << ',' << result.drag[i] << ',' << result.drag_pressure[i] << '\n';
        }
        double total = 0, overset = 0;
        std::vector<double> rest;
        for (std::size_t k = 0; k < m.step.size(); ++k) {
          total += m.step[k];
          overset += m.reassembly[k] + m.overset[k];
          rest.push_back(m.step[k] - m.reassembly[k] - m.overset[k]);
        }
        const std::string key = coupling + "/" + t;
        if (run.mass_balance == fv::MassBalance::off) {
          plain[key] = median(rest);
          plain_iterations[key] = median(m.pressure_iterations);
        }
        std::printf(
            "  %-8s %-8s %d thread(s): s/step median %.3f (re-assembly %.3f of which wall "
            "distances %.3f, in-step overset %.3f, pressure stage %.3f); overset share median "
            "%.1f %%, over the %zu steps %.1f %%; last outer momentum residual median %.2e, "
            "pressure iterations median %.0f; continuity <= %.1e, interface flux <= %.1e "
            "m^3/s\n",
            coupling.c_str(), balance.c_str(), n_threads, median(m.step), median(m.reassembly),
            median(m.walls), median(m.overset), median(m.pressure_seconds), 100 * median(m.share),
            m.step.size(), total > 0 ? 100 * overset / total : 0.0, median(m.residual),
            median(m.pressure_iterations), m.continuity, m.interface_flux);
        // Against the unbalanced baseline: everything this form's step costs beyond the step
        // without overset work (re-assembly, interpolation, and the balance wherever it runs,
        // inside the pressure solve too). A difference of medians of two runs: noisy.
        if (const auto it = plain.find(key);
            it != plain.end() && run.mass_balance != fv::MassBalance::off)
          std::printf(
              "  %-8s %-8s %d thread(s): against the unbalanced run's step without overset work "
              "(%.3f s), the overset share is %.1f %%\n",
              coupling.c_str(), balance.c_str(), n_threads, it->second,
              100 * (median(m.step) - it->second) / median(m.step));
        // The same run priced alone: the balance's extra pressure iterations (iteration counts
        // do not depend on the machine's load) at this run's own cost per pressure iteration
        // (the pressure stage over its iterations: an upper bound, the stage also assembles).
        if (const auto it = plain_iterations.find(key);
            it != plain_iterations.end() && run.mass_balance == fv::MassBalance::bordered) {
          const double iterations = median(m.pressure_iterations);
          const double extra =
              (iterations - it->second) * median(m.pressure_seconds) / std::max(iterations, 1.0);
          std::printf(
              "  %-8s %-8s %d thread(s): its %.0f extra pressure iterations (against %.0f) at "
              "this run's %.2f ms each: %.3f s a step; overset share with them %.1f %%\n",
              coupling.c_str(), balance.c_str(), n_threads, iterations - it->second, it->second,
              1e3 * median(m.pressure_seconds) / std::max(iterations, 1.0), extra,
              100 * (median(m.reassembly) + median(m.overset) + extra) / median(m.step));
        }
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
