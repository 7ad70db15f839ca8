// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant (issue 18): the vehicle's overset grid system in an unsteady RANS flow, its
// propeller a body-force disk, its six degrees of freedom from the flow's loads (DFBI), behind
// the same Plant interface as the derivative plant. One advance(actuators, dt), with the hooks of
// ../shared/design (docs/cfd-plant.md states it whole):
//   1. fins (grids_moved): each fin's deflection from (delta_r, delta_s) by the vehicle file's
//      mixing (geometry::fin_deflection); when one changed, the mesher's incremental overset
//      update and the wall distances of the cells in the flow; each fin grid turns at
//      (new - old) / dt during the step;
//   2. predictor: Dfbi::begin_step (BDF2, Euler on the flow's first step), every grid set to the
//      iterate's motion (VehicleOverset::motions), the propeller's load from it (step 4);
//   3. the flow's outer iterations (fv::Pimple::step); after each but the last
//      (motion_correct): the loads, rho times the pressure and shear on every wall about the
//      body origin (fv::wall_forces) plus the propeller's reaction, thrust T along its axis and
//      torque -sense Q; the body corrected (Dfbi::correct, the added-mass estimate), the grids
//      moved at once, the propeller's load renewed;
//   4. propeller: V_a = the inflow plane's mean of n_hat . (w - U) (fv::DiskForce, the paper's
//      way), J = V_a / (n D) (0 when the water comes from behind), KT and KQ from the curve,
//      T = rho KT n^2 D^4 and Q = rho KQ n^2 D^5 spread over the disk's cells (Hough-Ordway);
//   5. accept: the body takes the iterate the last outer iteration moved with; the report.
// A diverging flow, an orphan in the overset update or a runaway motion return a PlantFailure
// naming it; state() is then the last good state and the flow keeps its last good fields.
// Results are bitwise the same for any number of threads (the solver's reductions are ordered).
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "auvloop/engine/dfbi.hpp"
#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/plant.hpp"
#include "auvloop/engine/propeller.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

namespace auvloop::engine {

struct CfdPlantSettings {
  std::string mesh = "coarse";  // mesher preset: coarse, medium, fine
  // The grids' settings when they are not the preset's own (a case file's [mesh] table on top of
  // the preset; mesher::read_mesh_settings). Fin deflections must be left empty: the plant turns
  // the fins.
  std::optional<mesher::MeshSettings> mesh_settings;
  int outer_iterations = 5;  // the paper's
  bool sst = true;           // SST k-omega; else laminar
  // Water: kinematic viscosity (m^2/s; sea water at 15 C) and the free stream's turbulence for
  // SST (intensity of `reference_speed`, eddy-viscosity ratio).
  double nu = 1.19e-6;
  double reference_speed = 1.54;  // m/s
  double intensity = 0.01, viscosity_ratio = 10;
  // The flow's numerics, as remus-overset-sst runs them (docs/overset-flow.md).
  fv::Convection convection = fv::Convection::linear_upwind_limited;
  // Under-relaxation of U and p in every outer iteration but the last (fv::PimpleSettings).
  double relax_u = 1.0, relax_p = 1.0;
  int pressure_correctors = 2;  // per outer iteration
  // SST in the last outer iteration only (fv::PimpleSettings::turbulence_final_only).
  bool turbulence_final_only = false;
  // The linear solves' relative tolerance (|b - A x| <= tolerance |b|) in the last outer
  // iteration, and in the others (0: the same; fv::PimpleSettings::intermediate_tolerance).
  double tolerance = 1e-8;
  double intermediate_tolerance = 0;
  // Degrees of freedom (u v w p q r): all, or DfbiBody::horizontal.
  std::array<bool, 6> free{true, true, true, true, true, true};
  double relax = 1.0;  // of the body's acceleration in the coupling
  // The coupling's added-mass estimate (kg, kg m, kg m^2; body axes about the origin), e.g.
  // prestero_added_mass(); zero for plain relaxed coupling.
  Matrix6d added_mass = Matrix6d::Zero();
  // Buoyancy: true takes B = W (horizontal-plane manoeuvres without depth control, as the
  // derivative plant's default); false the vehicle file's.
  bool neutral_buoyancy = true;
  // The propeller's open-water curve (empty: the vehicle file's [propeller.open_water]; one of
  // the two is required when rpm > 0) and its inflow plane's offset ahead of the disk (m; < 0:
  // a quarter of the diameter).
  std::function<OpenWaterPoint(double J)> curve;
  double inflow_offset = -1;
  // false: no disk at all (a resistance run towed without its propeller; rpm must stay 0). A
  // grid without the fins' zone may have no cells on the disk's inflow plane.
  bool propeller = true;
  int sense = 1;              // the propeller turns right-handed about +x (REMUS: K_prop < 0)
  double runaway_speed = 20;  // m/s; beyond it the run stops as diverged
  // The flow's divergence guards (fv::PimpleSettings::max_speed, max_courant; 0: none): water
  // faster than this anywhere in the flow (m/s; the water round a vehicle at a few m/s moves at
  // a few m/s) stops the run as diverged. No Courant guard by default: the Courant number grows
  // as a grid is refined, and medium's nose-rim cells pass 2e4 at 10 ms (docs/cfd-plant.md).
  double max_flow_speed = 20, max_courant = 0;
  // Where a diverging flow writes its last good fields (empty: kept in memory).
  std::filesystem::path divergence_directory;
};

// What the flow looks like at one instant, for pictures (issue 18 item 6; results renders them,
// flow_snapshot.cpp computes them). Body axes, lengths in m.
struct FlowSnapshot {
  double time = 0;  // s
  // The horizontal mid-plane z = 0 around the stern (the paper's Figure 20): the water's speed
  // relative to the grid that holds it (m/s: the vehicle's own motion taken out, a fin grid's
  // turning too) at nx x ny points x0 + i h, y0 + j h, index j nx + i; NaN in a solid. Each
  // point takes the value of the cell that holds it (VehicleOverset::locate): no smoothing.
  double x0 = 0, y0 = 0, h = 0;
  int nx = 0, ny = 0;
  std::vector<double> speed;
  // The upper fin (the one reaching highest above the axis; on the REMUS the upper rudder, the
  // paper's Figure 21): per wall face, the centre's x and height above the axis (-z) with the
  // fin at zero deflection, the side (+1: starboard face, -1: port: the sign of the outward
  // normal's y; 0: the tip and the root, |n_y| < 0.2) and the pressure (Pa, gauge against the far
  // field's outflow) of its cell.
  struct Face {
    double x = 0, height = 0;
    int side = 0;
    double p = 0;
  };
  std::string fin;
  double deflection = 0;  // rad, the fin's now
  std::vector<Face> faces;
};

// What one advance() did, beside the state.
struct CfdStepReport {
  double time = 0;                          // s, the flow's
  double rpm = 0, J = 0, inflow_speed = 0;  // rev/min, -, m/s
  double thrust = 0, torque = 0;            // N, N m (on the fluid: the vehicle gets -torque)
  std::vector<std::pair<std::string, fv::PatchForce>> walls;  // N, N m about the origin
  std::vector<double> deflections;                            // rad, per fin
  double coupling_change = 0;  // Dfbi::change() of the last correction (m/s^2, rad/s^2)
  fv::StepReport flow;
  // Wall clock: the whole advance; the fins' update (re-assembly, wall distances); the coupling
  // between outer iterations (the wall loads, the 6-DOF correction, the grids' motion, the disk).
  // The flow's own phases are in `flow`.
  double seconds = 0, seconds_fins = 0, seconds_coupling = 0;
};

class CfdPlant final : public Plant {
 public:
  // Builds the grid system of settings.mesh at zero deflection and the solver. Throws
  // std::invalid_argument naming a bad setting, a propeller disk off the grid, or an orphan.
  CfdPlant(const geometry::Vehicle& vehicle, CfdPlantSettings settings);
  ~CfdPlant() override;
  CfdPlant(const CfdPlant&) = delete;
  CfdPlant& operator=(const CfdPlant&) = delete;

  [[nodiscard]] std::string name() const override { return "cfd"; }
  // The body at `initial` with the settings' degrees of freedom free. The flow: the straight
  // run of spin_up() when it was at the same body velocity (the flow in the body's axes does not
  // depend on heading or position), else water at rest around the body (an impulsive start),
  // the fins at zero.
  void reset(const BodyState& initial) override;
  // The straight run a manoeuvre starts from: the body towed at initial.nu (every degree of
  // freedom held), the propeller at rpm, the fins at zero, for `duration` seconds of steps of dt,
  // the first kStartSteps of them no longer than kStartDt (an impulsive start's pressure spike
  // at the nose rim; docs/cfd-plant.md). progress(t) after every step. A failure is returned;
  // the plant is then as after a reset to water at rest.
  std::optional<PlantFailure> spin_up(const BodyState& initial, double rpm, double duration,
                                      double dt,
                                      const std::function<void(double t)>& progress = {});
  static constexpr int kStartSteps = 10;
  static constexpr double kStartDt = 0.002;  // s
  // The steps spin_up(duration, dt) takes.
  static int spin_up_steps(double duration, double dt);
  PlantResult advance(const ActuatorValues& actuators, double dt) override;
  [[nodiscard]] const BodyState& state() const override { return dfbi_.state(); }
  // Exact checkpoint: the body (Dfbi::history), the fins' deflections, the flow with its old time
  // levels and the turbulence model's fields (fv::Pimple::write_checkpoint), and whether the flow
  // is spin_up()'s. load() re-assembles the grids at the stored deflections first; it throws
  // std::runtime_error on a record of another grid (the plant is then as after reset()).
  void save(StateWriter& out) const override;
  void load(StateReader& in) override;

  // Recorded every step (Plant::signal_columns): the propeller's J, inflow speed V_a (on its
  // plane), thrust T and torque Q (on the fluid), then for every wall part (the hull, each fin
  // by name) the force X Y Z (N) and moment K M N (N m) about the body origin in body axes,
  // pressure ("_p") and viscous ("_v") apart: "hull.X_p", "upper_rudder.N_v", ...
  [[nodiscard]] std::vector<std::pair<std::string, std::string>> signal_columns() const override;
  [[nodiscard]] std::vector<double> signal_values() const override { return signals_; }
  // Phases: fins (re-assembly, wall distances), coupling (wall loads, 6-DOF, grid motion, disk),
  // momentum, pressure, turbulence, flow-other (the step's end), rest; "overset" is not a phase
  // of its own: its share of momentum, pressure and flow-other is given as "of which overset".
  [[nodiscard]] std::vector<std::pair<std::string, double>> wall_clock() const override;

  // The flow now, for pictures (FlowSnapshot): the stern plane on a lattice of spacing h (m)
  // from `aft` m behind the hull's tail to `ahead` m in front of it and `half_width` m to
  // either side.
  // FlowSnapshot::time is `time` (s; the loop's clock: the flow's counts the straight run too).
  [[nodiscard]] FlowSnapshot snapshot(double time, double h = 0.002, double aft = 0.25,
                                      double ahead = 0.35, double half_width = 0.15) const;
  // The fields for ParaView (VTK unstructured grid, written atomically): the grid system with
  // the fins at their deflections, per cell U (the water's velocity, body axes, m/s), U_rel (it
  // relative to the grid that holds it), p (Pa), the turbulence model's fields, and status
  // (0 active, 1 fringe, 2 hole: threshold below 2 to hide the holes).
  void write_fields(const std::filesystem::path& vtu) const;

  [[nodiscard]] const CfdStepReport& last() const { return report_; }
  [[nodiscard]] const fv::Pimple& flow() const;
  [[nodiscard]] int cells() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Dfbi dfbi_;
  CfdStepReport report_;
  std::optional<Vector6d> spun_up_;  // the body velocity of spin_up()'s flow, while it holds
  std::vector<std::string> parts_;   // the wall patches, in the flow's order
  std::vector<double> signals_;      // signal_values(): of report_, kept across save/load
  std::array<double, 8> clock_{};    // wall_clock()'s sums, s
  void record_signals();
};

}  // namespace auvloop::engine
