// SPDX-License-Identifier: GPL-3.0-or-later
// released-cylinder (issue 18, item 3; validation.hpp states the case): the 6-DOF coupling of a
// body with the flow, engine::Dfbi through Pimple::motion_correct, as the CFD plant runs it:
//   1. the unconfined cylinder's overset pair, a far field on the box's sides, the cylinder a
//      wall moving with its grid; the body's state at rest, both grids with its motion;
//   2. per step: Dfbi::begin_step (Euler on the first step, BDF2 after, as the flow), the
//      grids set to the predicted motion; after each outer iteration but the last the hook
//      takes the cylinder's force (fv::patch_force) plus F, corrects the body and moves the
//      grids for the next outer iteration; after the step the body accepts the iterate the
//      flow's last outer iteration moved with;
//   3. u', u and the last correction's change every step.
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "auvloop/engine/dfbi.hpp"
#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"
#include "coupled_pair.hpp"

namespace auvloop::engine::validation {

ReleasedCylinderResult released_cylinder(const mesher::UnconfinedCylinderSpec& g, double mass_ratio,
                                         double estimate_ratio, double relax, double nu, double dt,
                                         int steps, int outer_iterations) {
  const auto t0 = std::chrono::steady_clock::now();
  const CoupledPair coupled(mesher::unconfined_cylinder_overset(g));  // 1.
  const auto& mesh = coupled.mesh;
  fv::PimpleSettings s;
  s.nu = nu;
  s.dt = dt;
  s.outer_iterations = outer_iterations;
  s.tolerance = 1e-10;
  s.max_courant = 20;
  fv::Pimple flow(mesh, s);
  flow.set_overset(&coupled.overset);
  for (const char* side :
       {"background/west", "background/east", "background/south", "background/north"})
    flow.far_field(side);
  flow.wall("cylinder/cylinder");
  const double R = 0.5 * g.diameter, depth = g.thickness * g.diameter;
  const double m_a = std::numbers::pi * R * R * depth;  // per unit density (m^3)
  const double m = mass_ratio * m_a;
  const double F = m + m_a;  // so that potential flow gives u' = 1 m/s^2
  DfbiBody body;
  body.mass =
      rigid_body_mass(m, Eigen::Vector3d::Zero(), 0.5 * m * R * R * Eigen::Matrix3d::Identity());
  body.added_mass(0, 0) = body.added_mass(1, 1) = estimate_ratio * m_a;
  body.free = {true, true, false, false, false, false};
  body.relax = relax;
  Dfbi dfbi(body);
  dfbi.reset(BodyState{});
  const auto move_grids = [&] {
    fv::FrameMotion motion;
    motion.velocity = dfbi.iterate().nu.head<3>();
    flow.set_motion(std::vector<fv::FrameMotion>(2, motion));
  };
  move_grids();
  flow.initialise();
  flow.motion_correct = [&](int) {  // 2.
    Vector6d tau = Vector6d::Zero();
    tau.head<3>() = fv::patch_force(flow, "cylinder/cylinder").total();
    tau[0] += F;
    dfbi.correct(tau);
    move_grids();
  };
  ReleasedCylinderResult r;
  r.cells = mesh.cells();
  for (int n = 0; n < steps; ++n) {
    dfbi.begin_step(dt, flow.steps() > 0);
    move_grids();
    (void)flow.step();
    dfbi.accept();
    r.t.push_back(flow.time());  // 3.
    r.acceleration.push_back(dfbi.acceleration()[0]);
    r.u.push_back(dfbi.state().u());
    r.change.push_back(dfbi.change());
  }
  r.steps = steps;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace auvloop::engine::validation
