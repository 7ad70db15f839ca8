// SPDX-License-Identifier: GPL-3.0-or-later
// pitching-foil (issue 17; validation.hpp): a NACA 0012 pitching about its quarter chord in a
// stream, in its own overset grid turning over a background at rest, against the same motion
// of a single body-fitted grid that turns as a whole. Both share every cell near the foil
// (mesher::foil_grids), so the difference is what the relative motion adds: the re-assembly of
// every step, the cells coming out of the foil's hole in the background, the velocity turned
// between the two grids' axes.
//   1. theta(t) = amplitude cos(omega t) about +z through the pivot (the origin), rate theta'
//      (zero at the start: an impulsive start of the rotation would put an impulse into both);
//      the foil's axes at the new time level: a rotation by theta (fv::placed_motion with the
//      body at rest, the stream (U, 0, 0) resolved in the foil's axes);
//   2. overset: place the foil grid, re-assemble (fv::MovingOverset), the background at rest in
//      the stream; single: the one grid's motion is the foil's;
//   3. BDF2 steps from the uniform stream (in each grid's axes) at t = 0 (a stream rising from
//      rest instead needs a pressure gradient across the domain that a far field fixing p on its
//      outflow half cannot carry: the far field is then left disturbed for many flow-through
//      times); far field on the outer boundary, the foil a wall moving with its grid;
//   4. the foil's force and moment (fv::patch_force, in the foil's axes, moment about the pivot)
//      turned into the stream's axes: cL = F_y / q c s, cM = M_z / q c^2 s, q = U^2 / 2, s the
//      span (the grids' thickness).
#include <chrono>
#include <cmath>
#include <memory>

#include <Eigen/Geometry>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/moving_overset.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"

namespace auvloop::engine::validation {

PitchingFoilResult pitching_foil(const mesher::FoilOversetSpec& g, bool overset, double amplitude,
                                 double omega, double dt, double end_time) {
  const auto t0 = std::chrono::steady_clock::now();
  const double U = 1.0, c = g.chord, nu = U * c / 1000;
  auto grids = mesher::foil_grids(g);
  std::unique_ptr<fv::MovingOverset> sys;
  std::unique_ptr<fv::Mesh> single;
  if (overset) {
    std::vector<fv::MovingOverset::Component> parts;
    parts.push_back({std::move(grids.foil), 1, std::move(grids.solid)});
    parts.push_back({std::move(grids.background), 0, nullptr});
    sys = std::make_unique<fv::MovingOverset>(std::move(parts));
  } else {
    single = std::make_unique<fv::Mesh>(grids.single);
  }
  const fv::Mesh& mesh = overset ? sys->mesh() : *single;
  fv::PimpleSettings s;
  s.nu = nu;
  s.dt = dt;
  s.outer_iterations = 3;
  s.non_orthogonal_correctors = 1;  // the cells beside the trailing-edge fan
  s.tolerance = 1e-8;
  s.max_courant = 2000;  // the trailing-edge prisms are tiny: a guard against divergence only
  fv::Pimple flow(mesh, s);
  if (overset) {
    flow.set_overset(&sys->overset());
    for (const char* side :
         {"background/west", "background/east", "background/south", "background/north"})
      flow.far_field(side);
    flow.wall("foil/foil");
  } else {
    flow.far_field("far");
    flow.wall("foil");
  }
  fv::FrameMotion body;  // 1.
  body.stream = {U, 0, 0};
  const Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  const auto axes = [&](double t) {
    return Eigen::Isometry3d(
        Eigen::AngleAxisd(amplitude * std::cos(omega * t), Eigen::Vector3d::UnitZ()));
  };
  const auto motion = [&](double t) {
    const Eigen::Vector3d rate(0, 0, -amplitude * omega * std::sin(omega * t));
    const auto foil = fv::placed_motion(body, axes(t), rate, pivot);
    return overset ? std::vector<fv::FrameMotion>{foil, body} : std::vector<fv::FrameMotion>{foil};
  };
  if (overset) {  // the foil grid at its initial angle, as the single grid's motion has it
    sys->place(0, axes(0));
    sys->reassemble();
  }
  const auto initial = motion(0);  // 3.
  for (int cell = 0; cell < mesh.cells(); ++cell) {
    const auto& m =
        initial[overset ? static_cast<std::size_t>(sys->overset().component_of(cell)) : 0];
    for (std::size_t i = 0; i < 2; ++i)
      flow.U.c[i].cells[static_cast<std::size_t>(cell)] = m.stream[static_cast<Eigen::Index>(i)];
  }
  flow.set_motion(initial);
  flow.initialise();
  PitchingFoilResult r;
  r.cells = mesh.cells();
  const double span = g.thickness * c, q = 0.5 * U * U;
  const std::string wall = overset ? "foil/foil" : "foil";
  while (flow.time() < end_time - 0.5 * dt) {
    const double t = flow.time() + dt;
    if (overset) {  // 2.
      const auto ta = std::chrono::steady_clock::now();
      sys->place(0, axes(t));
      sys->reassemble();
      r.assembly_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - ta).count();
    }
    flow.set_motion(motion(t));
    const auto rep = flow.step();
    if (overset) {
      r.changed.push_back(rep.status_changes);
      r.came_out += rep.uncovered_cells;
    }
    r.max_courant = std::max(r.max_courant, rep.max_courant);
    r.continuity_error = std::max(r.continuity_error, rep.continuity_error);
    const auto f = fv::patch_force(flow, wall, pivot);  // 4.
    const Eigen::Matrix3d R = axes(t).linear();
    const Eigen::Vector3d force = R * f.total(), moment = R * f.total_moment();
    r.t.push_back(flow.time());
    r.theta.push_back(amplitude * std::cos(omega * t));
    r.cl.push_back(force.y() / (q * c * span));
    r.cm.push_back(moment.z() / (q * c * c * span));
  }
  r.steps = static_cast<int>(r.t.size());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace auvloop::engine::validation
