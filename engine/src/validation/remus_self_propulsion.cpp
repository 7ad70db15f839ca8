// SPDX-License-Identifier: GPL-3.0-or-later
// remus-self-propulsion (issue 18 item 8): the REMUS 100 driving itself with its body-force
// propeller at Prestero's trial rpm, as the CFD plant runs a manoeuvre's straight leg.
//   1. The vehicle: preset:remus100 with its calibrated open-water curve (the vehicle file's
//      table); the CFD plant with a case file's [cfd] defaults at `speed`, only surge free.
//   2. The straight run: towed at `speed` with the propeller at `rpm` for `spin_up` s
//      (CfdPlant::spin_up), then the body released onto it (reset) and advanced at `rpm`, the
//      fins at zero, for `time` s: the surge equation (mass plus the added-mass estimate) takes
//      the vehicle to the speed where the disk's thrust T meets the walls' drag with the disk
//      running, R_with.
//   3. Per step: u (m/s), the propeller's J, inflow speed V_a on its plane (m/s), thrust T (N),
//      torque Q (N m) and R_with (N, minus the walls' x force).
//   4. The self-propulsion point: their means over the last `window` s; the wake fraction
//      w = 1 - V_a / u, KT = T / (rho n^2 D^4), KQ = Q / (rho n^2 D^5) (n in rev/s). V_a is
//      sampled on the plane ahead of the disk, so it holds part of the disk's own suction, and
//      the curve's J scale s is calibrated through it (KT_B(V_a / (s n D))): w and s are one
//      parameter, and this w is the plant's, not comparable with a published wake fraction.
//      KT and KQ are the curve read at the mean J.
//   5. Surge momentum over the free steps: m (u_end - u_released) = dt sum (T - R_with), the
//      rigid body's mass against the loads' impulse (the walls' pressure carries the water's
//      added mass; the coupling's added-mass estimate only steadies the iterations).
//   6. The thrust deduction t = 1 - R_bare / T, with R_bare the towed resistance of hull + fins
//      without the disk at the self-propelled speed (remus_resistance at that speed, 4 s, the
//      last second's mean): the usual definition at the self-propulsion point, where T = R_with.
#include <chrono>
#include <cmath>

#include "auvloop/engine/case.hpp"
#include "auvloop/engine/cfd_plant.hpp"
#include "auvloop/engine/validation.hpp"

namespace auvloop::engine::validation {

SelfPropulsionResult remus_self_propulsion(const SelfPropulsionRun& run) {
  SelfPropulsionResult r;
  CaseSpec c;  // 1.
  c.vehicle = load_vehicle_model("preset:remus100");
  c.plant = PlantKind::cfd;
  c.cfd.mesh = run.mesh;
  c.initial_speed = run.speed;
  c.rpm = run.rpm;
  auto settings = cfd_plant_settings(c);
  settings.free = {true, false, false, false, false, false};
  const auto& v = c.vehicle.vehicle;
  r.density = v.mass.water_density;
  r.diameter = v.propeller.diameter;
  r.mass = v.mass.mass;
  r.released_at = run.speed;
  const auto t0 = std::chrono::steady_clock::now();
  CfdPlant plant(v, settings);
  r.cells = plant.cells();
  BodyState initial;
  initial.nu[0] = run.speed;
  const auto finish = [&](const std::string& why) {
    r.failure = why;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  if (const auto failure = plant.spin_up(initial, run.rpm, run.spin_up, run.dt))  // 2.
    return finish("the straight run: " + failure->reason);
  plant.reset(initial);
  ActuatorValues a;
  a.rpm = run.rpm;
  const int steps = static_cast<int>(std::lround(run.time / run.dt));
  for (int k = 1; k <= steps; ++k) {
    const auto step = plant.advance(a, run.dt);
    if (const auto* failure = std::get_if<PlantFailure>(&step)) return finish(failure->reason);
    const auto& last = plant.last();  // 3.
    double drag = 0;
    for (const auto& [name, f] : last.walls) drag -= f.total().x();
    r.t.push_back(k * run.dt);
    r.u.push_back(plant.state().nu[0]);
    r.J.push_back(last.J);
    r.inflow.push_back(last.inflow_speed);
    r.thrust.push_back(last.thrust);
    r.torque.push_back(last.torque);
    r.drag_with.push_back(drag);
    r.steps = k;
    if (run.on_step) run.on_step(k * run.dt, r.u.back());
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

SelfPropulsionResult::Point SelfPropulsionResult::point(double from, double to, double rpm) const {
  Point p;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] <= from + 1e-9 || t[i] > to + 1e-9) continue;
    p.u += u[i];
    p.J += J[i];
    p.inflow += inflow[i];
    p.thrust += thrust[i];
    p.torque += torque[i];
    p.drag_with += drag_with[i];
    ++n;
  }
  if (n == 0) {
    for (double* x : {&p.u, &p.J, &p.inflow, &p.thrust, &p.torque, &p.drag_with, &p.wake_fraction,
                      &p.KT, &p.KQ})
      *x = std::nan("");
    return p;
  }
  for (double* x : {&p.u, &p.J, &p.inflow, &p.thrust, &p.torque, &p.drag_with}) *x /= n;
  const double rps = rpm / 60;  // 4.
  p.wake_fraction = 1 - p.inflow / p.u;
  p.KT = p.thrust / (density * rps * rps * std::pow(diameter, 4));
  p.KQ = p.torque / (density * rps * rps * std::pow(diameter, 5));
  return p;
}

double SelfPropulsionResult::momentum_ratio(double dt) const {
  if (u.empty()) return std::nan("");
  double impulse = 0;  // N s
  for (std::size_t i = 0; i < u.size(); ++i) impulse += dt * (thrust[i] - drag_with[i]);
  return mass * (u.back() - released_at) / impulse;
}

}  // namespace auvloop::engine::validation
