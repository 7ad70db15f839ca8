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
#include <chrono>
#include <cmath>
#include <memory>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/composite_grid.hpp"

namespace auvloop::engine::validation {

RotatingRestResult rotating_frame_at_rest(const ChannelGrid& g, double rate, double dt, int steps) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto spec = cylinder_overset_spec(g);
  const auto pair = mesher::cylinder_overset(spec);
  const auto system =
      mesher::composite_system({{&pair.cylinder, 1, &pair.solid}, {&pair.background, 0, nullptr}});
  const fv::Mesh mesh(system.composite.grid);
  const fv::Overset overset(mesh, system.stencils, system.composite.cell_offset);
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

}  // namespace auvloop::engine::validation
