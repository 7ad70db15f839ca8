// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant's validation cases on the REMUS 100 (issue 18 item 8) and their pass criteria.
//
// remus-resistance (remus_resistance.cpp runs one mesh): towed at 1.54 m/s in sea water
// (nu 1.19e-6 m^2/s) for 4 s, the drag the mean of the last second (about 3.3 hull lengths
// travelled before it). Held on medium, as the acceptance: the hull alone within 8 % of
// ITTC-57 times Hoerner's form factor (propeller.md section 4: 3.67 N x 1.10 = 4.05 N), hull +
// fins within 8 % of that plus the fins' friction times their section form factor (0.66 N);
// the drag's drift over the last second within 1 % (else the mean is not the steady drag).
// Coarse and fine are reported beside it, with the GCI of the three (Celik et al. 2008; and the
// paper's mean-ratio order). Quick (CI): the references' arithmetic against propeller.md's
// printed figures, and 20 steps (ten of 2 ms, ten of 10 ms) of each configuration on coarse:
// every step done, and the force
// across the stream of a vehicle symmetric in y and z under 1 % of its drag.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "auvloop/engine/cfd_plant.hpp"
#include "auvloop/engine/vehicle_model.hpp"
#include "rows.hpp"

namespace auvloop::engine::validation {

namespace {

constexpr double kSpeed = 1.54;  // m/s, Prestero's trial point
constexpr double kNu = 1.19e-6;  // m^2/s, sea water at 15 C (the [cfd] default)

// Rows holding what the references compute against the figures propeller.md section 4 prints:
// the hull's within half a unit of their last printed digit; the fins' "about 0.52 N" and
// "0.66 N" within 2 % (the second is not 0.52 x 1.252 = 0.651 rounded: the "about" covers
// rounding and the section's perimeter, which the thin plates leave out).
void reference_rows(Result& res, const FrictionReference& f) {
  const auto printed = [&](std::string quantity, double value, double figure, double half_unit) {
    Row r{std::move(quantity), value, figure, std::abs(value - figure), half_unit, false};
    r.pass = r.error <= half_unit;
    res.rows.push_back(r);
  };
  const auto about = [&](std::string quantity, double value, double figure) {
    res.rows.push_back(relative_to(std::move(quantity), value, figure, 0.02));
  };
  printed("hull wetted area (m^2), propeller.md", f.hull_area, 0.7195, 5e-5);
  printed("hull ITTC-57 friction (N), propeller.md", f.hull_friction, 3.67, 5e-3);
  printed("Hoerner's form factor, propeller.md", f.hull_form_factor, 1.10, 5e-3);
  printed("fins' area as thin plates (m^2), propeller.md", f.fin_plate_area, 0.0507, 5e-5);
  about("their ITTC-57 friction (N), propeller.md", f.fin_plate_friction, 0.52);
  about("with the form factor (N), propeller.md", f.fin_plate_friction * f.fin_form_factor, 0.66);
}

std::string parts(const ResistanceResult::Mean& m) {
  return fmt::format(
      "hull {:.3f} N (pressure {:.3f}, shear {:.3f}), fins {:.3f} N (pressure "
      "{:.3f}, shear {:.3f}), total {:.3f} N",
      m.hull(), m.hull_pressure, m.hull_shear, m.fins(), m.fins_pressure, m.fins_shear, m.total());
}

}  // namespace

Result run_remus_resistance(bool quick) {
  Result res{"remus-resistance", {}, {}};
  const auto vehicle = load_vehicle_model("preset:remus100").vehicle;
  const auto ref = friction_reference(vehicle, kSpeed, kNu);
  res.notes.push_back(fmt::format(
      "references at {} m/s, nu {} m^2/s: hull Re_L {:.3g}, S {:.4f} m^2, ITTC-57 {:.3f} N x "
      "Hoerner {:.3f} = {:.3f} N; fins Re_c {:.3g}, S {:.4f} m^2 (the sections' perimeter; "
      "{:.4f} as thin plates), {:.3f} N x {:.3f} = {:.3f} N; hull + fins {:.3f} N. Prestero's "
      "build-up: hull 3.39 N, fins 0.62 N (4.01 N)",
      kSpeed, kNu, ref.hull_reynolds, ref.hull_area, ref.hull_friction, ref.hull_form_factor,
      ref.hull(), ref.fin_reynolds, ref.fin_area, ref.fin_plate_area, ref.fin_friction,
      ref.fin_form_factor, ref.fins(), ref.hull() + ref.fins()));
  if (quick) reference_rows(res, ref);
  constexpr double kTime = 4, kWindow = 1;
  const double time = quick ? 0.12 : kTime;  // quick: ten 2 ms steps and ten of 10 ms
  const std::vector<std::string> meshes =
      quick ? std::vector<std::string>{"coarse"}
            : std::vector<std::string>{"coarse", "medium", "fine"};
  std::vector<std::array<double, 2>> drag;  // per mesh: hull alone, hull + fins (N)
  std::vector<double> cells;                // per mesh, hull + fins
  for (const auto& mesh : meshes) {
    std::array<double, 2> d{};
    for (bool fins : {false, true}) {
      ResistanceRun run;
      run.mesh = mesh;
      run.fins = fins;
      run.speed = kSpeed;
      run.time = time;
      const auto r = remus_resistance(run);
      const std::string what = fmt::format("{}, {}", mesh, fins ? "hull + fins" : "hull alone");
      if (!r.failure.empty()) res.notes.push_back(what + ": failed: " + r.failure);
      const double planned = CfdPlant::spin_up_steps(time, run.dt);
      res.rows.push_back(
          bound_row("steps not completed / planned, " + what, 1.0 - r.steps / planned, 0.0));
      if (quick) {
        const auto m = r.mean(0.02, time);
        res.notes.push_back(fmt::format("{}: {} cells, {} steps in {:.0f} s; the 10 ms steps' {}",
                                        what, r.cells, r.steps, r.seconds, parts(m)));
        res.rows.push_back(
            bound_row("|side force, lift| / drag, " + what, m.side_and_lift / m.total(), 1e-2));
        continue;
      }
      const auto last = r.mean(time - kWindow, time);
      const auto before = r.mean(time - 2 * kWindow, time - kWindow);
      const double drift = (last.total() - before.total()) / last.total();
      res.notes.push_back(fmt::format(
          "{}: {} cells, {} steps in {:.0f} s; the last second's mean {}; its change from the "
          "second before {:+.2f} %",
          what, r.cells, r.steps, r.seconds, parts(last), 100 * drift));
      d[fins ? 1 : 0] = last.total();
      if (fins) cells.push_back(r.cells);
      if (mesh != "medium") continue;
      res.rows.push_back(
          bound_row("drag drift over the last second, " + what, std::abs(drift), 0.01));
      res.rows.push_back(
          fins ? relative_to("hull + fins drag (N), medium", last.total(), ref.hull() + ref.fins(),
                             0.08)
               : relative_to("hull alone drag (N), medium", last.total(), ref.hull(), 0.08));
    }
    drag.push_back(d);
  }
  if (!quick && cells.size() == 3) {
    for (auto order : {OrderEstimate::celik, OrderEstimate::mean_ratio}) {
      const auto g = grid_convergence({cells[2], cells[1], cells[0]},
                                      {drag[2][1], drag[1][1], drag[0][1]}, order);
      res.notes.push_back(fmt::format(
          "GCI of the hull + fins drag ({}): r21 {:.3f}, r32 {:.3f}, p {:.2f}{}, extrapolated "
          "{:.3f} N, GCI21 {:.2f} %, GCI32 {:.2f} %, asymptotic check {:.3f}",
          order == OrderEstimate::celik ? "Celik's iteration" : "the paper's mean ratio", g.r21,
          g.r32, g.p, g.oscillatory ? " (oscillatory)" : "", g.extrapolated, 100 * g.gci21,
          100 * g.gci32, g.asymptotic));
    }
  }
  return res;
}

// remus-self-propulsion (remus_self_propulsion.cpp runs one mesh): free in surge at 1500 rpm
// from the straight run towed at 1.54 m/s (2 s), for 4 s; the self-propulsion point the means
// of the last second. Held, full (coarse and medium): the speed's drift over the last second
// within 0.2 % (the surge time constant, (m + m_a) over the balance's slope of about 38 N per
// m/s, is 0.8 s: 4 s are five of them), and on medium the speed within 0.5 % of 1.54 m/s. The
// preset's curve is calibrated on medium towed at 1.54 m/s (docs/cfd-plant.md), which predicts
// 0.06 %: this holds the free vehicle where the towed calibration put it, not an independent
// validation of the speed; coarse's speed shows the grid's share. Reported, not held: the thrust
// deduction (the towed bare drag at the self-propelled speed, 4 s), T and Q beside Prestero's, w,
// KT and KQ (remus_self_propulsion.cpp: w is tied to the calibrated scale). Quick (CI): coarse, the
// straight run's first 0.12 s, then 0.1 s free: every step done, and surge momentum over the free
// steps, m (u_end - u_released) against the impulse of T - R_with, within 25 %: the body moves as
// the walls' loads say (a load's sign, a mass or a unit wrong is off by far more; BDF2's start
// from rest gives about 5 %: measured 0.949). The young flow's thrust is small there (0.29 N
// against 5.9 N of drag: J is high before the wake forms), so the thrust's reaction is checked by
// the full run's speed, not here. Not held on the full run, whose net force is near zero.
Result run_remus_self_propulsion(bool quick) {
  Result res{"remus-self-propulsion", {}, {}};
  constexpr double kRpm = 1500, kTime = 4, kWindow = 1;
  const std::vector<std::string> meshes =
      quick ? std::vector<std::string>{"coarse"} : std::vector<std::string>{"coarse", "medium"};
  for (const auto& mesh : meshes) {
    SelfPropulsionRun run;
    run.mesh = mesh;
    run.speed = kSpeed;
    run.rpm = kRpm;
    run.spin_up = quick ? 0.12 : 2;
    run.time = quick ? 0.1 : kTime;
    const auto r = remus_self_propulsion(run);
    if (!r.failure.empty()) res.notes.push_back(mesh + ": failed: " + r.failure);
    const double planned = std::round(run.time / run.dt);
    res.rows.push_back(
        bound_row("free steps not completed / planned, " + mesh, 1.0 - r.steps / planned, 0.0));
    const double from = quick ? 0 : run.time - kWindow;
    const auto p = r.point(from, run.time, kRpm);
    const auto before = r.point(from - kWindow, from, kRpm);
    const double drift = (p.u - before.u) / p.u;
    const double balance = (p.thrust - p.drag_with) / p.thrust;

    res.notes.push_back(fmt::format(
        "{}: {} cells, {} free steps in {:.0f} s; {} at {} rpm: u {:.4f} m/s{}, J {:.4f}, V_a "
        "{:.4f} m/s, w {:.3f}, T {:.3f} N, R_with {:.3f} N (T - R_with {:+.2f} % of T), Q "
        "{:.4f} N m, KT {:.4f}, KQ {:.5f}",
        mesh, r.cells, r.steps, r.seconds, quick ? "the free steps' means" : "the last second's",
        kRpm, p.u,
        quick ? "" : fmt::format(" (change over the last second {:+.3f} %)", 100 * drift), p.J,
        p.inflow, p.wake_fraction, p.thrust, p.drag_with, 100 * balance, p.torque, p.KT, p.KQ));
    if (quick) {
      res.rows.push_back(relative_to("surge momentum over the free steps / impulse, " + mesh,
                                     r.momentum_ratio(run.dt), 1.0, 0.25));
      continue;
    }
    res.rows.push_back(
        bound_row("speed drift over the last second, " + mesh, std::abs(drift), 2e-3));
    if (mesh == "medium")
      res.rows.push_back(
          relative_to("self-propelled speed at 1500 rpm (m/s), medium", p.u, kSpeed, 0.005));
    if (!r.failure.empty()) continue;  // no self-propulsion point to tow at
    ResistanceRun bare;                // 6.
    bare.mesh = mesh;
    bare.speed = p.u;
    const auto towed = remus_resistance(bare);
    const double r_bare = towed.mean(bare.time - kWindow, bare.time).total();
    res.notes.push_back(fmt::format(
        "{}: towed without the disk at {:.4f} m/s: R_bare {:.3f} N{}; thrust deduction t = 1 - "
        "R_bare / T = {:.3f} (propeller.md: about 0.1); T {:.3f} N against Prestero's X_prop "
        "3.86 N (his drag model), Q {:.4f} N m against his K_prop 0.543 N m",
        mesh, p.u, r_bare, towed.failure.empty() ? "" : " (failed: " + towed.failure + ")",
        1 - r_bare / p.thrust, p.thrust, p.torque));
  }
  return res;
}

}  // namespace auvloop::engine::validation
