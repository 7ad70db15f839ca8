// SPDX-License-Identifier: GPL-3.0-or-later
// remus-resistance (issue 18 item 8): the REMUS 100 towed straight at 1.54 m/s without its
// propeller, as the CFD plant runs it, hull alone and hull + fins, against the friction lines
// (../shared/reference/propeller.md section 4).
//   1. The vehicle: preset:remus100; the hull alone empties its fin set (the mesher then grids the
//      hull without the fins' zone).
//   2. The CFD plant with a case file's [cfd] defaults (cfd_plant_settings), every degree of
//      freedom held, without the propeller's disk, towed from the impulsive start:
//      CfdPlant::spin_up's ten 2 ms steps, then 10 ms ones, to `time`.
//   3. The drag: minus the x force of the walls' pressure and shear (N), per part (the hull; the
//      fins together), its mean over the last `window` s; the drift: that mean less the mean of
//      the window before, over the mean (what the drag still changed).
//   4. The references: the ITTC-57 line C_F = 0.075 / (log10 Re - 2)^2 times 1/2 rho U^2 S:
//      the hull on its curved wetted area (Re on its length) times Hoerner's body-of-revolution
//      form factor 1 + 1.5 (d/L)^1.5 + 7 (d/L)^3; each fin on its wetted area (the section's
//      perimeter times the span's mean chord, times the span; Re on the mean chord) times the
//      section form factor 1 + 2 t/c + 60 (t/c)^4. Prestero's build-up (3.39 N hull, 0.62 N
//      fins, his thesis Table 5.2) is reported beside them.
//   5. Over three meshes, the grid convergence index of the hull + fins drag (gci.cpp).
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/engine/cfd_plant.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/geometry/myring.hpp"

namespace auvloop::engine::validation {

namespace {

double ittc57(double reynolds) {
  const double d = std::log10(reynolds) - 2;
  return 0.075 / (d * d);
}

// The perimeter of the unit-chord section (both faces), by the polyline through 20,000 points
// spaced as 1 - cos: the leading edge's square-root shape is resolved to round-off.
double section_perimeter(const geometry::NacaSection& s) {
  constexpr int n = 20000;
  double length = 0;
  for (int side : {1, -1}) {
    Eigen::Vector2d last = s.surface(0, side);
    for (int i = 1; i <= n; ++i) {
      const double x = 0.5 * (1 - std::cos(std::numbers::pi * i / n));
      const Eigen::Vector2d next = s.surface(x, side);
      length += (next - last).norm();
      last = next;
    }
  }
  return length;
}

}  // namespace

FrictionReference friction_reference(const geometry::Vehicle& v, double speed, double nu) {
  FrictionReference f;
  const double q = 0.5 * v.mass.water_density * speed * speed;  // Pa
  const geometry::MyringProfile profile(v.hull);
  const auto hull = geometry::hull_properties(profile);
  f.hull_area = hull.wetted_area_curved;
  f.hull_reynolds = speed * hull.length / nu;
  const double d_over_l = 2 * profile.max_radius() / hull.length;
  f.hull_form_factor = 1 + 1.5 * std::pow(d_over_l, 1.5) + 7 * std::pow(d_over_l, 3);
  f.hull_friction = q * f.hull_area * ittc57(f.hull_reynolds);
  const auto& fins = v.fin_set;
  const double chord = 0.5 * (fins.root_chord + fins.tip_chord);
  const double t_over_c = 0.01 * fins.section.thickness_percent;
  f.fin_area =
      static_cast<double>(fins.fins.size()) * section_perimeter(fins.section) * chord * fins.span;
  f.fin_reynolds = speed * chord / nu;
  f.fin_form_factor = 1 + 2 * t_over_c + 60 * std::pow(t_over_c, 4);
  f.fin_friction = q * f.fin_area * ittc57(f.fin_reynolds);
  f.fin_plate_area = static_cast<double>(fins.fins.size()) * 2 * chord * fins.span;
  f.fin_plate_friction = q * f.fin_plate_area * ittc57(f.fin_reynolds);
  return f;
}

ResistanceResult remus_resistance(const ResistanceRun& run) {
  ResistanceResult r;
  CaseSpec c;  // 1.
  c.vehicle = load_vehicle_model("preset:remus100");
  if (!run.fins) c.vehicle.vehicle.fin_set.fins.clear();
  c.plant = PlantKind::cfd;
  c.cfd.mesh = run.mesh;
  c.initial_speed = run.speed;
  c.rpm = 0;
  auto settings = cfd_plant_settings(c);  // 2.
  settings.free = {false, false, false, false, false, false};
  settings.propeller = false;
  const auto t0 = std::chrono::steady_clock::now();
  CfdPlant plant(c.vehicle.vehicle, settings);
  r.cells = plant.cells();
  BodyState initial;
  initial.nu[0] = run.speed;
  const auto failure = plant.spin_up(initial, 0, run.time, run.dt, [&](double t) {  // 3.
    const auto& last = plant.last();
    double hull_p = 0, hull_v = 0, fins_p = 0, fins_v = 0;
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (const auto& [name, f] : last.walls) {
      const bool hull = name.rfind("hull", 0) == 0;
      (hull ? hull_p : fins_p) -= f.pressure.x();
      (hull ? hull_v : fins_v) -= f.viscous.x();
      total += f.total();
    }
    r.t.push_back(t);
    r.hull_pressure.push_back(hull_p);
    r.hull_shear.push_back(hull_v);
    r.fins_pressure.push_back(fins_p);
    r.fins_shear.push_back(fins_v);
    r.side_and_lift.push_back(std::hypot(total.y(), total.z()));
    r.steps = static_cast<int>(r.t.size());
    if (run.on_step) run.on_step(t, hull_p + hull_v + fins_p + fins_v);
  });
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (failure) r.failure = failure->reason;
  return r;
}

ResistanceResult::Mean ResistanceResult::mean(double from, double to) const {
  Mean m;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] <= from + 1e-9 || t[i] > to + 1e-9) continue;
    m.hull_pressure += hull_pressure[i];
    m.hull_shear += hull_shear[i];
    m.fins_pressure += fins_pressure[i];
    m.fins_shear += fins_shear[i];
    m.side_and_lift = std::max(m.side_and_lift, side_and_lift[i]);
    ++n;
  }
  if (n == 0) return m;
  m.hull_pressure /= n;
  m.hull_shear /= n;
  m.fins_pressure /= n;
  m.fins_shear /= n;
  return m;
}

}  // namespace auvloop::engine::validation
