// SPDX-License-Identifier: GPL-3.0-or-later
// Validation on moving grids (issue 17; fv/motion.hpp). rotating-frame-at-rest:
//   1. the Schaefer-Turek overset pair (cylinder_overset_spec: the O-grid over the Cartesian
//      channel), both grids turning as one about the cylinder's axis at a constant rate through
//      fluid at rest: motion velocity -Omega x c and rate Omega for each grid (c the axis);
//   2. the cylinder a slip wall (a solid of revolution about the axis: turning it moves no
//      fluid), the channel's four sides a far field at rest, so that its faces switch between
//      inflow and outflow along each side (the grid velocity's normal component changes sign);
//   3. BDF2 steps from rest; the exact solution is u = 0 and p = 0. Measured: the largest |u|
//      over the active cells against the largest grid speed, and |p|, after every step.
// galilean-cylinder (unconfined_cylinder):
//   1. the O-grid over a square box 40 D across (mesher::unconfined_cylinder_overset), Re = 100
//      with U = 1 m/s, D = 1 m, nu = 0.01 m^2/s; the box's four sides a far field;
//   2. fixed: the stream U through grids at rest; towed: the grids moving at -U through fluid at
//      rest (the cylinder a wall moving with its grid); the same start in both frames: the
//      stream plus a cross-flow bump 0.2 U exp(-|x - (1.5 D, 0)|^2 / D^2) behind the cylinder,
//      which starts the shedding at once (the symmetric flow would wait for round-off);
//   3. cD and cL every step from the cylinder's force; St, mean cD and cL amplitude (half its
//      peak-to-peak) over the last whole periods of cL.
#include <chrono>
#include <cmath>
#include <memory>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "coupled_pair.hpp"
#include "signal.hpp"

namespace auvloop::engine::validation {

RotatingRestResult rotating_frame_at_rest(const ChannelGrid& g, double rate, double dt, int steps) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto spec = cylinder_overset_spec(g);
  const CoupledPair coupled(mesher::cylinder_overset(spec));
  const auto& mesh = coupled.mesh;
  const auto& overset = coupled.overset;
  fv::PimpleSettings s;
  s.nu = 1e-3;
  s.dt = dt;
  s.outer_iterations = 2;
  s.tolerance = 1e-10;
  fv::Pimple flow(mesh, s);
  flow.set_overset(&overset);
  flow.slip("cylinder/cylinder");  // 2.
  for (const char* side :
       {"background/inlet", "background/outlet", "background/bottom", "background/top"})
    flow.far_field(side);
  fv::FrameMotion m;  // 1.
  m.rate = {0, 0, rate};
  m.velocity = -m.rate.cross(Eigen::Vector3d(spec.cx, spec.cy, 0));
  const std::vector<fv::FrameMotion> motion(2, m);
  flow.set_motion(motion);
  flow.initialise();
  RotatingRestResult r;
  r.cells = mesh.cells();
  r.active_cells = static_cast<int>(overset.active_cells().size());
  for (int c = 0; c < mesh.cells(); ++c)
    r.max_grid_speed = std::max(r.max_grid_speed, m.at(mesh.centre(c)).norm());
  for (int k = 0; k < steps; ++k) {  // 3.
    flow.set_motion(motion);
    const auto rep = flow.step();
    r.max_courant = std::max(r.max_courant, rep.max_courant);
    r.continuity_error = std::max(r.continuity_error, rep.continuity_error);
    for (int c : overset.active_cells()) {
      r.max_u = std::max(r.max_u, flow.U.cell(c).norm());
      r.max_p = std::max(r.max_p, std::abs(flow.p.cells[static_cast<std::size_t>(c)]));
    }
    r.steps = k + 1;
  }
  r.turned = rate * dt * steps;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

UnconfinedCylinderResult unconfined_cylinder(const mesher::UnconfinedCylinderSpec& g, bool towed,
                                             double dt, double end_time, int measured_periods,
                                             fv::Convection convection) {
  const auto t0 = std::chrono::steady_clock::now();
  constexpr double U = 1.0;  // m/s
  const double D = g.diameter;
  const CoupledPair coupled(mesher::unconfined_cylinder_overset(g));  // 1.
  const auto& mesh = coupled.mesh;
  const auto& overset = coupled.overset;
  fv::PimpleSettings s;
  s.nu = U * D / 100;
  s.dt = dt;
  s.outer_iterations = 2;
  s.tolerance = 1e-8;
  s.max_courant = 20;
  s.convection = convection;
  fv::Pimple flow(mesh, s);
  flow.set_overset(&overset);
  for (const char* side :
       {"background/west", "background/east", "background/south", "background/north"})
    flow.far_field(side);
  flow.wall("cylinder/cylinder");
  fv::FrameMotion m;  // 2.
  const Eigen::Vector3d stream(U, 0, 0);
  if (towed) {
    m.velocity = -stream;
  } else {
    m.stream = stream;
  }
  const std::vector<fv::FrameMotion> motion(2, m);
  for (int c = 0; c < mesh.cells(); ++c) {
    const Eigen::Vector3d x = mesh.centre(c) / D;
    const double bump = 0.2 * U * std::exp(-(std::pow(x.x() - 1.5, 2) + x.y() * x.y()));
    const Eigen::Vector3d u = m.stream + Eigen::Vector3d(0, bump, 0);
    for (std::size_t i = 0; i < 2; ++i)
      flow.U.c[i].cells[static_cast<std::size_t>(c)] = u[static_cast<Eigen::Index>(i)];
  }
  flow.set_motion(motion);
  flow.initialise();
  UnconfinedCylinderResult r;
  r.cells = mesh.cells();
  r.active_cells = static_cast<int>(overset.active_cells().size());
  const double q = 0.5 * U * U * D * g.thickness * D;  // per unit density
  while (flow.time() < end_time - 0.5 * dt) {          // 3.
    flow.set_motion(motion);
    const auto rep = flow.step();
    r.max_courant = std::max(r.max_courant, rep.max_courant);
    const Eigen::Vector3d force = fv::patch_force(flow, "cylinder/cylinder").total();
    r.t.push_back(flow.time());
    r.cd.push_back(force.x() / q);
    r.cl.push_back(force.y() / q);
  }
  r.steps = static_cast<int>(r.t.size());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto up = upward_crossings(r.t, r.cl);
  if (static_cast<int>(up.size()) < measured_periods + 2) return r;
  const auto n = static_cast<std::size_t>(measured_periods);
  const double ta = up[up.size() - 1 - n], tb = up.back();
  const double tp = up[up.size() - 2 - n];
  r.periods = measured_periods;
  r.strouhal = D * measured_periods / ((tb - ta) * U);
  r.period_drift = std::abs((tb - ta) - (up[up.size() - 2] - tp)) / (tb - ta);
  std::vector<double> wl, wn;
  double cd_sum = 0, weight = 0;
  for (std::size_t i = 1; i < r.t.size(); ++i)
    if (r.t[i - 1] >= ta && r.t[i] <= tb) {  // trapezoidal mean of cD over whole periods
      const double h = r.t[i] - r.t[i - 1];
      cd_sum += 0.5 * h * (r.cd[i - 1] + r.cd[i]);
      weight += h;
    }
  for (std::size_t i = 0; i < r.t.size(); ++i)
    if (r.t[i] >= ta && r.t[i] <= tb) {
      wl.push_back(r.cl[i]);
      wn.push_back(-r.cl[i]);
    }
  r.cd_mean = weight > 0 ? cd_sum / weight : 0;
  r.cl_amplitude = 0.5 * (peak(wl) + peak(wn));
  return r;
}

}  // namespace auvloop::engine::validation
