// SPDX-License-Identifier: GPL-3.0-or-later
// remus-overset (issue 17; validation.hpp): the REMUS 100 overset system in the flow, the
// acceptance run of the moving-overset solver.
//   1. the vehicle's grid system of a mesh preset, assembled at zero deflection
//      (fv::VehicleOverset); laminar or SST (k and omega on the coupling, the wall distance of
//      the composite mesh, turbulence::WallDistances), the body moving at `speed` along +x
//      through water at rest (the far field on the background's outer faces, every wall moving
//      with its grid);
//   2. `straight` seconds with the fins at rest, then `turning` seconds with the turning fin's
//      (or every fin's) deflection growing by fin_rate dt a step: the mesher's incremental
//      update at the new deflections (an orphan throws: no fringe cell is ever without active
//      donors), the wall distances re-measured where a fin may now be nearest (cells in the
//      flow only), the fin's axes turning about its post at fin_rate (VehicleOverset::motions),
//      Pimple::step carrying the fields onto the new statuses (a restart continues from its
//      checkpoint's step; RemusOversetRun::checkpoint_to writes one after a chosen step);
//   3. per step the continuity error over the active cells and the interface flux (Pimple's
//      report) and the hull's force (fv::patch_force on "hull/hull"); a DivergenceError ends the
//      run and is reported, with the steps done.
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/vehicle_overset.hpp"
#include "auvloop/engine/turbulence/sst_model.hpp"
#include "auvloop/engine/turbulence/wall_distance.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

namespace auvloop::engine::validation {

RemusOversetResult remus_overset(const RemusOversetRun& run) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  const auto vehicle = geometry::preset_vehicle("remus100");  // 1.
  fv::VehicleOverset sys(
      mesher::build_grid_system(vehicle, mesher::mesh_preset(run.preset, vehicle)), vehicle);
  const auto& mesh = sys.mesh();
  const auto fins = static_cast<std::size_t>(sys.fins());
  if (run.turning_fin < -1 || run.turning_fin >= sys.fins())
    throw std::invalid_argument("remus_overset: no fin " + std::to_string(run.turning_fin));
  fv::PimpleSettings s;
  s.nu = 1e-6;
  s.dt = run.dt;
  s.outer_iterations = run.outer_iterations;
  s.convection = run.convection;
  s.overset_coupling = run.coupling;
  s.mass_balance = run.mass_balance;
  s.max_courant = 500;  // the fin roots' tiny cells: a guard against divergence only
  fv::Pimple flow(mesh, s);
  flow.set_overset(&sys.overset());
  for (const auto& patch : mesh.grid().patches) {
    if (patch.type == mesher::PatchType::wall) {
      flow.wall(patch.name);
    } else if (patch.name.rfind("background/", 0) == 0 &&
               patch.type != mesher::PatchType::overset) {
      flow.far_field(patch.name);
    }
  }
  std::unique_ptr<turbulence::WallDistances> walls;
  std::unique_ptr<turbulence::SstModel> sst;
  if (run.sst) {
    walls = std::make_unique<turbulence::WallDistances>(mesh, sys.composite().cell_offset);
    turbulence::SstSettings ts;
    ts.nu = s.nu;
    ts.freestream = turbulence::freestream_from_intensity(run.speed, 0.01, 10, s.nu);
    ts.ambient_sources = run.ambient_sources;
    ts.solver = run.turbulence_solver;
    sst = std::make_unique<turbulence::SstModel>(mesh, walls->composite(), ts);
    for (const auto& patch : mesh.grid().patches)
      if (patch.name.rfind("background/", 0) == 0 && patch.type != mesher::PatchType::overset)
        sst->far_field(patch.name);
    flow.set_turbulence(sst.get());
  }
  // The wall distances at the fins' present axes, for the cells in the flow.
  const auto follow_walls = [&] {
    (void)walls->update(sys.component_axes(), sys.cells_in_flow());
    sst->set_wall_distance(walls->composite());
  };
  fv::FrameMotion body;
  body.velocity = Eigen::Vector3d(run.speed, 0, 0);
  std::vector<double> deflection = sys.deflections();
  const std::vector<double> at_rest(fins, 0.0);
  std::vector<double> rates(fins, 0.0);
  for (std::size_t k = 0; k < fins; ++k)
    if (run.turning_fin < 0 || static_cast<std::size_t>(run.turning_fin) == k)
      rates[k] = run.fin_rate;
  flow.set_motion(sys.motions(body, at_rest));
  flow.initialise();
  RemusOversetResult r;
  r.cells = mesh.cells();
  const int straight_steps = static_cast<int>(std::lround(run.straight / run.dt));
  r.planned_steps = straight_steps + static_cast<int>(std::lround(run.turning / run.dt));
  if (!run.restart.empty()) {
    flow.read_checkpoint(run.restart);
    if (flow.steps() > straight_steps)
      throw std::invalid_argument("remus_overset: " + run.restart.string() + " is at step " +
                                  std::to_string(flow.steps()) +
                                  ", after the straight phase (a restart holds no fin placements)");
  }
  for (int n = flow.steps(); n < r.planned_steps; ++n) {  // 2.
    const bool turn = n >= straight_steps;
    try {
      double reassembly = 0, wall_distance = 0;
      if (turn) {
        for (std::size_t k = 0; k < fins; ++k) deflection[k] += rates[k] * run.dt;
        const auto ta = std::chrono::steady_clock::now();
        sys.set_fins(deflection);
        if (sst) {
          const auto tw = std::chrono::steady_clock::now();
          follow_walls();
          wall_distance = seconds_since(tw);
        }
        reassembly = seconds_since(ta);
        r.assembly_seconds += reassembly;
        r.wall_distance_seconds += wall_distance;
      }
      flow.set_motion(sys.motions(body, turn ? rates : at_rest));
      const auto ts = std::chrono::steady_clock::now();
      const auto rep = flow.step();  // 3.
      const double step_seconds = seconds_since(ts);
      r.max_continuity = std::max(r.max_continuity, rep.continuity_error);
      r.max_interface_flux = std::max(r.max_interface_flux, rep.interface_flux);
      r.max_courant = std::max(r.max_courant, rep.max_courant);
      r.status_changes += rep.status_changes;
      r.uncovered_cells += rep.uncovered_cells;
      r.max_bounded_cells = std::max(r.max_bounded_cells, rep.turbulence.bounded_cells);
      if (run.on_step) run.on_step(rep, reassembly, wall_distance, step_seconds);
    } catch (const fv::DivergenceError& e) {
      r.failure = e.what();
      break;
    } catch (const std::invalid_argument& e) {  // an orphan in the update
      r.failure = e.what();
      break;
    }
    r.steps = n + 1;
    r.t.push_back(flow.time());
    const auto hull = fv::patch_force(flow, fv::VehicleOverset::hull_wall());
    r.drag.push_back(-hull.total().x());
    r.drag_pressure.push_back(-hull.pressure.x());
    if (run.after_step) run.after_step(flow);
    if (!run.checkpoint_to.empty() && r.steps == run.checkpoint_step)
      flow.write_checkpoint(run.checkpoint_to);
  }
  if (sst)
    for (const auto& y : sst->y_plus())
      if (y.patch == fv::VehicleOverset::hull_wall()) {
        r.hull_y_plus_mean = y.mean;
        r.hull_y_plus_max = y.max;
      }
  if (run.keep_fields) {
    for (std::size_t i = 0; i < 3; ++i) r.U[i] = flow.U.c[i].cells;
    r.p = flow.p.cells;
    r.phi = flow.phi;
  }
  r.seconds = seconds_since(t0);
  return r;
}

}  // namespace auvloop::engine::validation
