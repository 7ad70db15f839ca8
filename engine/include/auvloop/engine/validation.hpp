// SPDX-License-Identifier: GPL-3.0-or-later
// Verification and validation cases of the CFD engine, shared by the tests and `auvloop validate`.
// Each case runs the solver, compares with a reference nobody in this project produced (an exact
// solution, an observed order of accuracy, a published table; see
// shared/reference/validation-data.md) and returns one row per compared quantity. Tolerances are
// stated, with their source, where each case is defined.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "auvloop/engine/fv/operators.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/turbulence/sst_model.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/flat_plate_grid.hpp"
#include "auvloop/mesher/foil_grid.hpp"

namespace auvloop::engine::validation {

// What a geometrically converging sequence still changes, from its last two changes (Aitken):
// each change shrinks by q = change / change_before, so what remains, the last change counted,
// is change / (1 - q); infinite while the changes do not shrink (or there is no change before).
// A slowly converging iteration (q near 1) would stop far from its limit on the last change alone.
[[nodiscard]] inline double remaining_change(double change, double change_before) {
  const double q = change_before > 0 ? change / change_before : 1.0;
  return q < 1 ? change / (1 - q) : std::numeric_limits<double>::infinity();
}

struct Row {
  std::string quantity;
  double value = 0;      // auvloop's result
  double reference = 0;  // the published or exact value
  double error = 0;      // as the tolerance measures it (stated per row)
  double tolerance = 0;
  bool pass = false;
};

struct Result {
  std::string name;
  std::vector<Row> rows;
  std::vector<std::string> notes;  // grid sizes, timings, convergence history
  [[nodiscard]] bool pass() const;
};

struct Case {
  std::string name;
  std::string description;
  std::function<Result(bool quick)> run;  // quick: the CI-sized version (seconds)
};

// The implemented cases, in the order `auvloop validate --list` shows them.
const std::vector<Case>& cases();

// The grid convergence index of one quantity on three systematically refined grids (Celik et
// al. 2008; gci.cpp states the procedure), the finest first: cells N_i and values phi_i. Not
// computable (NaN; `converged` false) when a change is zero, a ratio is not above 1 or the
// apparent order's iteration does not converge to a positive order.
struct GridConvergence {
  double r21 = 0, r32 = 0;        // refinement ratios (N_fine / N_coarse)^(1/3)
  bool oscillatory = false;       // the two changes differ in sign
  bool converged = false;         // the apparent order's fixed-point iteration (mean_ratio: true)
  double p = 0;                   // apparent order
  double extrapolated = 0;        // Richardson's phi_ext21
  double e_a21 = 0, e_ext21 = 0;  // approximate and extrapolated relative errors (fractions)
  double gci21 = 0, gci32 = 0;    // the fine and the medium grid's GCI (fractions, Fs 1.25)
  double asymptotic = 0;          // GCI32 / (r21^p GCI21): near 1 in the asymptotic range
};
// The apparent order: Celik's iteration for unequal ratios, or one mean ratio (the paper's).
enum class OrderEstimate { celik, mean_ratio };
GridConvergence grid_convergence(const std::array<double, 3>& cells,
                                 const std::array<double, 3>& phi,
                                 OrderEstimate order = OrderEstimate::celik);

// Manufactured steady convection-diffusion on stretched, smoothly skewed hexahedra: the L2 and
// maximum errors for n^3 cells and the observed orders between successive grids.
struct MmsError {
  int n = 0;
  double l2 = 0, max = 0;
  int iterations = 0;  // deferred-correction iterations to convergence
};
MmsError mms_convection_diffusion(int n);

// Manufactured steady Navier-Stokes on an overset pair of stretched, skewed grids (an O-grid
// round a cylinder over a Cartesian background, mms_overset.cpp states the solution, grids and
// conditions): level m has 4 m x m O-grid cells and background cells of pi / (8 m) m. The
// errors of |U| (m/s) and p (m^2/s^2) over the active cells of both grids.
struct MmsOversetError {
  int m = 0, cells = 0, active_cells = 0;
  double l2_u = 0, max_u = 0, l2_p = 0, max_p = 0;
  int iterations = 0;  // pseudo-time steps to convergence
  bool converged = false;
  // The last step's continuity error over the active cells and interface flux relative to
  // the inflow (U0 per unit area).
  double continuity_error = 0, interface_flux = 0;
  double seconds = 0;
};
MmsOversetError mms_overset(int m, double nu = 0.01);  // nu in m^2/s

// Lid-driven cavity on n x n uniform cells: the largest deviations from Ghia et al. of u on the
// vertical and v on the horizontal centreline, in units of the lid speed.
struct CavityResult {
  int n = 0;
  double reynolds = 0;
  int steps = 0;               // pseudo-time steps to the steady state
  double final_change = 0;     // max |du/dt| at the last step (1/s)
  double max_deviation_u = 0;  // max over Ghia's points
  double max_deviation_v = 0;
  double seconds = 0;
};
CavityResult lid_driven_cavity(int n, double reynolds);
double cavity_pseudo_dt(int n, double reynolds);

// 2D Taylor-Green vortex on n x n cells of [0, pi]^2 to end_time in `steps` BDF2 steps.
struct TaylorGreenRun {
  std::vector<double> u, v, volumes;  // per cell at end_time
  double error_vs_exact = 0;          // volume-weighted L2 of the velocity error (m/s)
  int max_outer = 0;                  // outer iterations the slowest step needed
};
TaylorGreenRun taylor_green(int n, int steps, double end_time, double nu);
double l2_difference(const TaylorGreenRun& a, const TaylorGreenRun& b);

// The Schaefer-Turek cylinder grid (mesher::cylinder_channel) as a function of one refinement
// parameter m: m cells per side of the O-grid's square box (4 m round the cylinder), the other
// counts proportional to m with fixed gradings, so that refining m refines everywhere alike.
// The defaults resolve the Re = 100 wall layer and near wake (docs/cfd.md, "Schaefer-Turek 2D-2").
struct ChannelGrid {
  int m = 32;
  double radial_cells_per_side = 1;      // cylinder to box: radial_cells_per_side x m cells,
  double radial_ratio = 8;               //   graded outermost / innermost = radial_ratio
  double downstream_cells_per_side = 4;  // box to outlet: downstream_cells_per_side x m cells,
  double downstream_ratio = 6;           //   graded last / first = downstream_ratio
  // Overset only: the background's uniform cell size (m; 0: the O-grid's outer cell size).
  double background_spacing = 0;
};

// The mesher's specification of that grid.
mesher::CylinderChannelSpec cylinder_spec(const ChannelGrid& g);
// Its overset counterpart (issue 17): an O-grid of 4 m cells round the cylinder and m radial
// cells graded by radial_ratio out to 3 radii, over a Cartesian background of background_spacing
// (or the O-grid's outer cell size) with downstream_cells_per_side x m cells to the outlet.
mesher::CylinderOversetSpec cylinder_overset_spec(const ChannelGrid& g);

// Schaefer-Turek 2D-1 (steady, Re = 20) on the grid `g` by pseudo-time marching (Euler) with
// step dt until max |du/dt| < 1e-6 1/s.
struct CylinderResult {
  int cells = 0, steps = 0;
  double final_change = 0;
  double cd = 0, cl = 0, dp = 0, la = 0;  // drag and lift coefficients, p difference, L_a (m)
  double seconds = 0;
  // Overset: the active cells, and the last step's continuity error and interface flux (the
  // largest net flux a component passes to its fringe, over the inflow Ubar H per unit depth).
  int active_cells = 0;
  double continuity_error = 0, interface_flux = 0;
};
// `overset`: on the overset pair of cylinder_overset_spec(g) instead.
CylinderResult schaefer_turek_2d1(const ChannelGrid& g, double dt, bool overset = false);

// rotating-frame-at-rest (moving_grids.cpp): the overset pair of cylinder_overset_spec(g)
// turning as a whole about the cylinder's axis at `rate` (rad/s) through fluid at rest, with a
// slip cylinder and a far field on the channel's sides, for `steps` steps of dt. The exact
// solution is u = 0, p = 0.
struct RotatingRestResult {
  int cells = 0, active_cells = 0, steps = 0;
  double max_u = 0;           // largest |u| over the active cells and steps (m/s)
  double max_p = 0;           // largest |p| likewise (m^2/s^2)
  double max_grid_speed = 0;  // largest |w| over the cells (m/s)
  double continuity_error = 0, max_courant = 0;
  double turned = 0;  // the angle turned (rad)
  double seconds = 0;
};
RotatingRestResult rotating_frame_at_rest(const ChannelGrid& g, double rate, double dt, int steps);

// galilean-cylinder (moving_grids.cpp): the unconfined cylinder at Re = 100 (U = 1 m/s, D = 1
// m, nu = 0.01 m^2/s) on mesher::unconfined_cylinder_overset(g), a far field on the box's four
// sides, from the stream (plus a cross-flow bump that starts the shedding) to end_time with
// BDF2 steps of dt; `towed`: the grids move at -U through fluid at rest instead of the cylinder
// fixed in the stream. St, mean cD and the cL amplitude over the last `measured_periods`
// periods of cL (periods = 0 without settled shedding).
struct UnconfinedCylinderResult {
  int cells = 0, active_cells = 0, steps = 0, periods = 0;
  double strouhal = 0, cd_mean = 0, cl_amplitude = 0;
  double period_drift = 0;  // relative change of the window's length from the previous window
  double max_courant = 0, seconds = 0;
  std::vector<double> t, cd, cl;
};
// `convection`: of U (the case's van_leer_skew; a grid study may try another).
UnconfinedCylinderResult unconfined_cylinder(
    const mesher::UnconfinedCylinderSpec& g, bool towed, double dt, double end_time,
    int measured_periods, fv::Convection convection = fv::Convection::van_leer_skew);

// released-cylinder (moving_grids.cpp; issue 18, item 3): the 6-DOF coupling (engine::Dfbi
// through Pimple::motion_correct) against potential flow.
//   1. the unconfined cylinder's grids (g), water at rest (nu), the cylinder free in surge and
//      sway, every grid moving with it; its mass m = mass_ratio m_a with m_a = pi R^2 b the
//      displaced volume of potential flow's added mass (per unit density; b the grids'
//      thickness), from rest under a constant force F = (m + m_a) 1 m/s^2 along x;
//   2. the coupling's added-mass estimate estimate_ratio m_a in surge and sway, its relaxation
//      relax, one correction after every outer iteration but the last; BDF2 after an Euler
//      step, for body and flow alike;
//   3. per step the acceleration u' against potential flow's F / (m + m_a) = 1 m/s^2 (an
//      unbounded fluid: the far field extent / 2 diameters away changes m_a by about
//      (R / far)^2), while the boundary layer's share, about 2 sqrt(nu t) / R, stays small;
//      and the last correction's change of u' (the coupling's residual).
struct ReleasedCylinderResult {
  int cells = 0, steps = 0;
  double seconds = 0;
  std::vector<double> t, acceleration, u, change;  // u' (m/s^2), u (m/s), |a_k - a_{k-1}|
};
ReleasedCylinderResult released_cylinder(const mesher::UnconfinedCylinderSpec& g, double mass_ratio,
                                         double estimate_ratio, double relax, double nu, double dt,
                                         int steps, int outer_iterations);

// pitching-foil (pitching_foil.cpp): a NACA 0012 of chord c = 1 m in a stream U = 1 m/s at
// Re = U c / nu = 1000, pitching about its quarter chord as theta(t) = amplitude cos(omega t)
// (rad, counter-clockwise about +z: nose down for positive theta) from the uniform stream at
// t = 0, for BDF2 steps of dt to end_time. `overset`: the foil's O-grid
// turning over the background at rest (re-assembled every step; mesher::foil_grids(g).foil and
// .background); else the single body-fitted grid (.single) turning as a whole. cL and cM (about
// the pivot, counter-clockwise positive) every step, in the stream's axes.
struct PitchingFoilResult {
  int cells = 0, steps = 0;
  int came_out = 0;  // overset: cells that left a hole over the run
  double max_courant = 0, continuity_error = 0, seconds = 0;
  double assembly_seconds = 0;  // overset: the re-assemblies' share of `seconds`
  std::vector<double> t, theta, cl, cm;
  std::vector<int> changed;  // overset: cells whose status changed, per step
};
PitchingFoilResult pitching_foil(const mesher::FoilOversetSpec& g, bool overset, double amplitude,
                                 double omega, double dt, double end_time);

// remus-overset (remus_overset.cpp): the REMUS 100 overset system of a mesh preset (hull, four
// fin grids, background) in the flow, laminar or SST (nu = 1e-6 m^2/s), the body moving at `speed`
// (m/s) straight ahead through water at rest from an impulsive start: `straight` seconds with
// the fins at rest, then `turning` seconds with one fin or every fin turning at `fin_rate`
// (rad/s), steps of dt. Per step: the continuity error over the active cells, the largest
// interface flux, the hull's force, the re-assembly's time; `on_step` sees every step's report,
// its re-assembly's (the wall distances' update included, SST), the wall distances' alone and
// its Pimple::step's wall-clock seconds (progress, benchmarks).
struct RemusOversetRun {
  std::string preset = "coarse";
  double speed = 1.54, dt = 2e-3;        // m/s, s
  double straight = 2.0, turning = 1.0;  // s
  double fin_rate = 0.5235987755982988;  // rad/s (30 deg/s)
  int turning_fin = -1;                  // the fin that turns, or -1: every fin
  int outer_iterations = 3;
  fv::OversetCoupling coupling = fv::OversetCoupling::lagged;
  fv::MassBalance mass_balance = fv::MassBalance::bordered;
  // SST k-omega (default wall treatment; free stream 1 % intensity, nu_t / nu = 10, on the
  // far field's inflow faces, zero gradient on its outflow faces) with the composite's wall
  // distances, kept current as the fins turn; otherwise laminar.
  bool sst = false;
  // Convection of U (k and omega: the SST's own, van_leer_skew). Upwind by default (the laminar
  // case's): van Leer diverged in the first steps (session 16 at the tail face, session 22 at
  // the nose rim), but upwind's numerical viscosity triples the hull's pressure drag;
  // remus-overset-sst runs linear_upwind_limited with the ambient sources (docs/overset-flow.md,
  // "Session 23").
  fv::Convection convection = fv::Convection::upwind;
  // SST only: the ambient sources that hold the free stream (SstSettings::ambient_sources), and
  // the k and omega equations' solver.
  bool ambient_sources = false;
  fv::AsymmetricMethod turbulence_solver = fv::AsymmetricMethod::bicgstab_jacobi;
  bool keep_fields = false;  // the result holds the last step's fields
  // Exact restart (Pimple::write_checkpoint): with checkpoint_to set, the state after step
  // checkpoint_step is written there; with restart set, the run continues from such a file
  // (same preset and settings; the straight phase only: the fins' placements are not stored).
  std::filesystem::path checkpoint_to, restart;
  int checkpoint_step = 0;
  std::function<void(const fv::StepReport&, double reassembly_seconds, double wall_distance_seconds,
                     double step_seconds)>
      on_step;
  // After each step, the flow (its turbulence model and fields) for a caller's own figures.
  std::function<void(const fv::Pimple&)> after_step;
};
struct RemusOversetResult {
  int cells = 0, steps = 0, planned_steps = 0;
  std::string failure;  // empty, or the DivergenceError of the step that failed
  double max_continuity = 0, max_interface_flux = 0, max_courant = 0;
  int status_changes = 0, uncovered_cells = 0;
  double seconds = 0, assembly_seconds = 0;
  double wall_distance_seconds = 0;   // the part of assembly_seconds that updates wall distances
  std::vector<double> t, drag;        // hull force along -x (N per unit density, m^4/s^2)
  std::vector<double> drag_pressure;  // its pressure part (the rest is shear)
  double hull_y_plus_mean = 0, hull_y_plus_max = 0;  // SST: the hull's first cells at the end
  long max_bounded_cells = 0;  // SST: the most cells a step's bound raised to k_min or omega_min
  // With keep_fields: U's components and p per cell, phi per face, after the last step.
  std::array<std::vector<double>, 3> U;
  std::vector<double> p, phi;
};
RemusOversetResult remus_overset(const RemusOversetRun& run);

// remus-resistance (remus_resistance.cpp states the set-up): the REMUS 100 towed straight
// without its propeller by the CFD plant (a case file's [cfd] defaults on `mesh`), hull + fins or
// the hull alone, and the friction lines it is compared with.
struct FrictionReference {
  double hull_area = 0, hull_reynolds = 0, hull_form_factor = 0;  // m^2, -, -
  double hull_friction = 0;  // N: ITTC-57 on the curved wetted area, without the form factor
  double fin_area = 0, fin_reynolds = 0, fin_form_factor = 0;  // all fins; Re on the mean chord
  double fin_friction = 0;                                     // N, all fins
  // The same on twice the planform (a thin plate's wetted area, propeller.md's: the section's
  // perimeter is 2.04 chords, not 2).
  double fin_plate_area = 0, fin_plate_friction = 0;                              // m^2, N
  [[nodiscard]] double hull() const { return hull_friction * hull_form_factor; }  // N
  [[nodiscard]] double fins() const { return fin_friction * fin_form_factor; }    // N
};
FrictionReference friction_reference(const geometry::Vehicle& v, double speed, double nu);

struct ResistanceRun {
  std::string mesh = "coarse";
  bool fins = true;                                    // false: the hull alone
  double speed = 1.54, time = 4, dt = 0.01;            // m/s, s, s
  std::function<void(double t, double drag)> on_step;  // N; progress
};
struct ResistanceResult {
  int cells = 0, steps = 0;
  std::string failure;  // empty, or the plant's
  double seconds = 0;
  // Per step: the drag's parts (N, along -x) and the walls' force across the stream (N).
  std::vector<double> t, hull_pressure, hull_shear, fins_pressure, fins_shear, side_and_lift;
  struct Mean {
    double hull_pressure = 0, hull_shear = 0, fins_pressure = 0, fins_shear = 0;
    double side_and_lift = 0;  // the largest over the interval
    [[nodiscard]] double hull() const { return hull_pressure + hull_shear; }
    [[nodiscard]] double fins() const { return fins_pressure + fins_shear; }
    [[nodiscard]] double total() const { return hull() + fins(); }
  };
  [[nodiscard]] Mean mean(double from, double to) const;  // over the steps in (from, to]
};
ResistanceResult remus_resistance(const ResistanceRun& run);

// remus-self-propulsion (remus_self_propulsion.cpp states the procedure): the vehicle free in
// surge at `rpm` with the preset's calibrated curve, from the straight run towed at `speed`.
struct SelfPropulsionRun {
  std::string mesh = "coarse";
  double speed = 1.54, rpm = 1500;                  // m/s, rev/min
  double spin_up = 2, time = 4, dt = 0.01;          // s: towed, then free in surge; the step
  std::function<void(double t, double u)> on_step;  // progress (s, m/s), free steps only
};
struct SelfPropulsionResult {
  int cells = 0, steps = 0;  // steps: the free ones done
  std::string failure;       // empty, or the plant's (the series hold the steps before it)
  double seconds = 0;
  double density = 0, diameter = 0;  // kg/m^3, m (the propeller's)
  double mass = 0, released_at = 0;  // kg (the rigid body's), m/s (u when released)
  // Per free step: u (m/s), J, V_a (m/s), T (N), Q (N m), the walls' drag with the disk (N).
  std::vector<double> t, u, J, inflow, thrust, torque, drag_with;
  struct Point {
    double u = 0, J = 0, inflow = 0, thrust = 0, torque = 0, drag_with = 0;
    double wake_fraction = 0, KT = 0, KQ = 0;  // 1 - V_a / u; T / (rho n^2 D^4); Q / (.. D^5)
  };
  // The means over the steps in (from, to] and what follows from them at `rpm` (NaN when no
  // step lies there).
  [[nodiscard]] Point point(double from, double to, double rpm) const;
  // Surge momentum over the free steps: m (u_end - u_released) over dt times the sum of the
  // net surge force T - R_with (1 when the body moved as the loads on it say; NaN without steps).
  [[nodiscard]] double momentum_ratio(double dt) const;
};
SelfPropulsionResult remus_self_propulsion(const SelfPropulsionRun& run);

// The propeller's body-force disk in a uniform stream against annular momentum theory
// (actuator_disk.cpp states the set-up): the disk-mean axial speed the solver gives and the one
// the theory gives for the same loading.
struct ActuatorDiskCase {
  double speed = 1.54;                      // m/s
  double nu = 1e-6;                         // m^2/s
  double thrust = 3.86 / 1025;              // m^4/s^2 (Prestero's 3.86 N in sea water)
  double radius = 0.07, hub_radius = 0.02;  // m
  double cell = 0.007;                      // the core's cube side (m); the disk is two cells thick
  double upstream = 0.7, downstream = 1.4, half_width = 0.5;  // m
  double growth = 1.15;
  int max_iterations = 2000;
};
struct ActuatorDiskResult {
  int cells = 0, disk_cells = 0, iterations = 0;
  double disk_speed = 0;    // the solver's (m/s): the disk cells' volume-mean axial velocity
  double face_speed = 0;    // the mid-plane faces' flux over their area (m/s)
  double theory_speed = 0;  // annular momentum theory's (m/s)
  double light_loading_induction = 0;  // T / (2 u_d A), the operating point's correction (m/s)
  double last_change = 0;              // of the disk speed over the last iteration (m/s)
  double seconds = 0;
};
ActuatorDiskResult actuator_disk(const ActuatorDiskCase& c);

// Schaefer-Turek 2D-2 (Re = 100, periodic shedding) from rest to end_time with BDF2 at fixed dt;
// St, cD max and cL max over the last `measured_periods` periods of cL (upward crossings of its
// mean). periods = 0 when fewer than measured_periods + 2 periods developed (no shedding).
struct SheddingResult {
  int cells = 0, active_cells = 0, steps = 0, periods = 0;
  double strouhal = 0, cd_max = 0, cl_max = 0;
  double period_drift = 0;    // relative change of the window's length from the previous window
  double shedding_onset = 0;  // time of the first upward crossing of cL (s)
  double max_courant = 0;
  // Overset: the largest continuity error of a step (over the active cells) and the largest
  // interface flux of a step relative to the inflow (Ubar H per unit depth).
  double max_continuity = 0, max_interface_flux = 0;
  double seconds = 0;
  std::vector<double> t, cd, cl;  // the histories, one sample per time step
};
struct SheddingCase {
  ChannelGrid grid;
  double dt = 0.002;      // s
  double end_time = 4.0;  // s
  int measured_periods = 3;
  int outer_iterations = 2;  // PIMPLE outer iterations per step
  fv::Convection convection = fv::Convection::van_leer_skew;
  bool overset = false;  // on cylinder_overset_spec(grid)'s pair instead of the single grid
};
SheddingResult schaefer_turek_2d2(const SheddingCase& c);

// NASA TMR 2DZP (zero-pressure-gradient flat plate, Re = 5e6 per metre) with SST k-omega,
// solved steady (SIMPLE) on mesher::flat_plate(spec, level) until Cf(0.97) and the plate drag
// settle: Cf along the plate, Cf(0.97), CD (reference length 2), the plate's y+ range.
struct FlatPlateResult;
struct FlatPlateCase {
  mesher::FlatPlateSpec spec;
  int level = 2;
  int max_iterations = 20000;
  int check_every = 100;    // iterations between convergence checks
  double tolerance = 1e-5;  // relative change of Cf(0.97) and CD still to come (extrapolated)
  double relax_u = 0.7, relax_p = 0.3, relax_turbulence = 0.7;
  // Linear solves per SIMPLE iteration, |b - A x| <= tol |b|: p, and U, k, omega.
  double pressure_tolerance = 1e-8, transport_tolerance = 1e-6;
  std::function<void(const std::string&)> progress;  // one line per check; may be empty
  bool laminar = false;  // no turbulence model (a check of the steady solver itself)
  fv::Convection turbulence_convection = fv::Convection::van_leer_skew;
  turbulence::WallTreatment wall = turbulence::WallTreatment::any_y_plus;
  // Grid sequencing: the converged solution of the next coarser level (level + 1, same spec) as
  // the start, each of its cells giving its value to the four it splits into; nullptr: the
  // free stream.
  const FlatPlateResult* start = nullptr;
};
struct FlatPlateResult {
  int cells = 0, iterations = 0;
  bool converged = false;
  double cf_097 = 0, cd = 0;
  std::vector<double> x, cf;  // per plate face
  turbulence::WallYPlus y_plus;
  long bounded_cells = 0;                   // summed over the iterations
  long limited_cells = 0;                   // in the last iteration
  std::array<double, 4> final_residuals{};  // U, p, k, omega (initial, last iteration)
  double seconds = 0;
  int level = 0, nx = 0, ny = 0;              // the grid: cell (i, j) is i + nx j
  std::array<std::vector<double>, 5> fields;  // per cell: u, v, p, k, omega
  // The top row's largest relative error against the free stream's analytic decay, x >= 0.2.
  double freestream_omega_error = 0, freestream_k_error = 0;
  double outlet_dx = 0;  // m, the streamwise size of the outlet cells
};
FlatPlateResult flat_plate_sst(const FlatPlateCase& c);

}  // namespace auvloop::engine::validation
