// SPDX-License-Identifier: GPL-3.0-or-later
// Incompressible Navier-Stokes (constant density, kinematic pressure p / rho) on a fv::Mesh with
// the PIMPLE algorithm: collocated velocity and pressure, Rhie-Chow face fluxes consistent with
// the time step, BDF2 in time (Euler for the first step). docs/cfd.md states the algorithm as
// numbered steps; engine/src/fv/pimple.cpp follows them.
//
// Usage: construct on a mesh, set boundary conditions on U and p (U.fix for walls, moving walls
// and inlets; p.fix for pressure outlets; slip patches via `slip`), set initial U, call
// initialise(), then step() once per time step.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "auvloop/engine/fv/field.hpp"
#include "auvloop/engine/fv/linear_solver.hpp"
#include "auvloop/engine/fv/motion.hpp"
#include "auvloop/engine/fv/operators.hpp"
#include "auvloop/engine/fv/overset.hpp"
#include "auvloop/engine/fv/turbulence_model.hpp"
#include "auvloop/engine/state_archive.hpp"

namespace auvloop::engine::fv {

// How the components of an overset mesh are coupled (overset.hpp, docs/overset-flow.md).
enum class OversetCoupling {
  lagged,    // explicit: fringe values from the donors' current values, refreshed before each
             // momentum solve and each corrector (every solve on its own grid)
  implicit,  // the interpolation rows in the matrices, one solve for all grids (FGMRES
             // preconditioned by the explicit coupling's solver; momentum_solver is not used)
};
const char* to_string(OversetCoupling c);  // "explicit", "implicit"
OversetCoupling overset_coupling_from_string(const std::string& s);

// The overset mass balance (overset_mass.cpp): the open components' interface flux to zero.
enum class MassBalance {
  flux,      // the open components' fringe ring takes its flux from the donors' velocity, the
             // mismatch spread over its faces by area, no pressure shift (overset_ring.cpp;
             // measured better on a steady case, worse on shedding: not the default)
  bordered,  // one bordered pressure solve (cg-amg with the explicit coupling; else response)
  response,  // one more pressure solve per open component for its response (the reference)
  off,       // none: the interpolation's mismatch leaves the flow at the interface (0.3 % of
             // the inflow on a coarse cylinder pair). For measuring the balance's cost only.
};
const char* to_string(MassBalance b);  // "flux", "bordered", "response", "off"
MassBalance mass_balance_from_string(const std::string& s);

struct PimpleSettings {
  double nu = 1e-6;  // kinematic viscosity (m^2/s)
  double dt = 1e-3;  // time step (s); the first one when adaptive
  // Adaptive time step: > 0 sets dt before each step so that the maximum Courant number of the
  // current flux approaches this, growing by at most max_dt_growth per step (BDF2 on variable
  // steps is zero-stable for ratios below 1 + sqrt 2) and never beyond max_dt (0: no bound).
  double target_courant = 0;
  double max_dt_growth = 1.2;
  double max_dt = 0;
  bool bdf2 = true;             // second order in time after the first step
  int outer_iterations = 1;     // PIMPLE outer loop (1: PISO); the paper uses 5
  int pressure_correctors = 2;  // per outer iteration
  int non_orthogonal_correctors = 0;
  double relax_u = 1.0;  // momentum under-relaxation (all but the final outer iteration)
  double relax_p = 1.0;  // pressure under-relaxation (all but the final outer iteration)
  Convection convection = Convection::van_leer_skew;
  // Fastest measured (docs/cfd.md, "Pressure solver"): cholmod-pcg on 2D grids, cg-amg in 3D,
  // where the Cholesky factor fills in too much; empty means choose by the grid.
  std::optional<SymmetricMethod> pressure_solver;
  // Momentum predictor: Jacobi-preconditioned BiCGSTAB, measured fastest (docs/cfd.md,
  // "Performance": on the 64^3 cavity 29 iterations per step against 44 symmetric Gauss-Seidel
  // sweep pairs, 0.61 against 0.71 s per step on one thread).
  AsymmetricMethod momentum_solver = AsymmetricMethod::bicgstab_jacobi;
  double tolerance = 1e-8;        // tolerance of the iterative linear solvers, in...
  double momentum_tolerance = 0;  // the momentum predictor's, if > 0 (else `tolerance`)
  // The linear solves' tolerance (pressure, momentum, a turbulence model's) in the outer
  // iterations but the last, if > 0 (else their own): those iterates only carry the outer loop
  // to the step's solution, which the last iteration's solves reach at their own tolerance
  // (OpenFOAM's p and pFinal, U and UFinal). Transient runs only (a steady solve has no last
  // iteration: it keeps its own). With outer_tolerance, a step that stops early ends on an
  // iteration solved at this tolerance.
  double intermediate_tolerance = 0;
  // ...this norm (linear_solver.hpp); `normalised` with 1e-6 / 1e-5 is OpenFOAM's p / U setting
  // in its tutorials and in bench/openfoam_cavity.sh.
  ResidualNorm residual_norm = ResidualNorm::relative;
  double max_courant = 50;  // a step beyond this stops the run (divergence)
  // A step whose largest |U| over the cells in the flow passes this (m/s) stops the run as well
  // (0: no such guard). Unlike the Courant number it does not grow as a grid is refined: the
  // guard for a run on a grid whose smallest cells pass large Courant numbers in a smooth flow.
  double max_speed = 0;
  // On divergence the last good fields are written here (created if missing) as
  // last-good.vtu / .pvd (ParaView) and last-good.checkpoint (restart); empty: kept in memory.
  std::filesystem::path divergence_directory;
  // A turbulence model's equations in the last outer iteration only, the eddy viscosity of the
  // step before in the others (OpenFOAM's turbOnFinalIterOnly, its pimpleFoam default); a
  // steady solve corrects it every iteration.
  bool turbulence_final_only = false;
  double outer_tolerance = 0;  // stop the outer loop once momentum's initial residual is below
  // A steady solve (SIMPLE): no time derivative, and every outer iteration under-relaxed (U by
  // relax_u, p by relax_p, a turbulence model by its own): a step is one pass of the
  // iteration towards the steady flow, its dt only a label.
  bool steady = false;
  OversetCoupling overset_coupling = OversetCoupling::lagged;
  MassBalance mass_balance = MassBalance::bordered;
};

struct StepReport {
  int step = 0;
  double time = 0;
  double dt = 0;  // the step's time step (s)
  double max_courant = 0;
  double max_speed = 0;          // m/s, the largest |U| over the cells in the flow after the step
  double momentum_residual = 0;  // initial normalised residual, first outer iteration (max comp)
  double pressure_residual = 0;  // initial normalised residual, first corrector
  double outer_residual = 0;     // initial momentum residual of the last outer iteration
  double continuity_error = 0;   // volume-weighted mean |div phi| * dt after the step (over
                                 // the active cells of an overset mesh)
  // Overset meshes: the largest |net flux| (m^3/s) a component's active cells pass to its fringe
  // and hole cells (fv::interface_flux), after the step.
  double interface_flux = 0;
  // Overset re-assembly at the start of the step (overset_transition.cpp): the cells whose
  // status changed since the last step and, of those, the cells that came out of a hole.
  int status_changes = 0, uncovered_cells = 0;
  int outer_iterations = 0;
  int pressure_iterations = 0;  // Krylov iterations summed over correctors (0 for CHOLMOD)
  int momentum_iterations = 0;  // sweep pairs or Krylov iterations summed over components
  double seconds_momentum = 0, seconds_pressure = 0, seconds_other = 0;
  // Parts of the above: momentum assembly (in seconds_momentum) and every cell-gradient
  // evaluation (deferred corrections, grad p; spread over all three).
  double seconds_assembly = 0, seconds_gradient = 0;
  // Overset meshes: the overset parts of the above (the status carry-over after a re-assembly,
  // the fringe rows: fixed values or their elimination into the active rows, the fringe
  // interpolations and HbyA, the mass balance with its extra pressure solves, the interface
  // flux; a turbulence model's own, TurbulenceReport::seconds_overset). Not in it: the
  // re-assembly itself (the driver's, before the step) and, with implicit
  // coupling, the larger solve of the coupled system.
  double seconds_overset = 0;
  // The turbulence model's equations (none: zero), summed over the outer iterations, and their
  // wall-clock time.
  TurbulenceReport turbulence;
  double seconds_turbulence = 0;
};

// Thrown when a step diverges (NaN, Courant number beyond the limit, a linear solve that no
// longer converges); the solver's fields are those of the last good step (also written to
// settings.divergence_directory when set). what() names the step, time, the equation where a
// solve failed, the cell and its centre, and the files written.
struct DivergenceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Pimple {
 public:
  Pimple(const Mesh& mesh, PimpleSettings settings);

  VectorField U;
  ScalarField p;
  std::vector<double> phi;  // volume flux through each face (m^3/s, out of the owner)
  // Body force per unit mass in each cell (m/s^2; empty: none), e.g. the mean pressure gradient
  // that drives a periodic channel or an actuator disk's thrust. An explicit momentum source,
  // so it also enters H(U) and the Rhie-Chow flux, as in OpenFOAM's fvOptions.
  std::vector<Eigen::Vector3d> body_force;

  // Marks a patch as slip (symmetry): zero normal velocity, zero tangential stress (lagged by
  // one outer iteration through the boundary values).
  void slip(const std::string& patch);
  // Attaches a turbulence model (turbulence_model.hpp; not owned, it must outlive this flow;
  // nullptr detaches): momentum then diffuses with its nu_eff, and its correct() runs after the
  // pressure correctors of every outer iteration. On an overset mesh the model rides on the
  // coupling (turbulence_model.hpp, hook 8). Before initialise().
  void set_turbulence(TurbulenceModel* model);
  [[nodiscard]] TurbulenceModel* turbulence() const { return turbulence_; }
  // Couples the components of a composite (overset) mesh explicitly (overset.hpp states the
  // algorithm; not owned, it must outlive this flow; nullptr detaches), a turbulence model's
  // transported fields with it. Before initialise().
  void set_overset(const Overset* overset);
  [[nodiscard]] const Overset* overset() const { return overset_; }
  // Overset re-assembly: when the grids move against each other, the driver re-assembles at the
  // new time level's placements and passes the result to the attached Overset (Overset::update,
  // with the components' orientations) before step(); the step's first stage then carries the
  // fields over (overset_transition.cpp states it): cells that came out of a hole take the mean
  // of their neighbours in every time level, faces that came alive a consistent flux, cells
  // that became active a predictor force. A restart re-assembles at the checkpoint's placements
  // before initialise().

  // Rigid motion of the grids (motion.hpp): the motion of each grid's axes at the new time
  // level, one per component of an overset mesh (one otherwise), set before every step (a
  // prescribed motion, or the 6-DOF solution) and before initialise() for the initial flux.
  // Throws std::invalid_argument naming the problem on a wrong count, a rotating periodic mesh,
  // slip patches on a moving grid, or a motion out of the plane of a 2D grid.
  void set_motion(std::vector<FrameMotion> motion);
  [[nodiscard]] const std::vector<FrameMotion>& motion() const { return motion_; }
  // Hook "motion_correct" (the 6-DOF coupling, DFBI: engine/dfbi.hpp): when set, called after
  // every outer iteration that another follows (its correctors and turbulence done) with that
  // iteration's number (1-based). It may read the loads (forces.hpp) and call set_motion, which
  // within a step takes effect at once (the grid flux, the wall velocities and the far field's
  // faces of the new motion) for the next outer iteration. A step that diverges restores the
  // fields, not the motion: the driver keeps its own body state.
  std::function<void(int outer)> motion_correct;
  // A no-slip wall on its moving grid: U = the grid velocity at every face (zero at rest), at
  // the new time level of every step.
  void wall(const std::string& patch);
  // A far field: per face and step, a face through which the stream relative to the grid,
  // (stream - w) . S, enters or runs along takes U = stream and zero-gradient p (inflow); one it
  // leaves takes p = 0 and zero-gradient U (outflow). Thus the faces of a box that turns with
  // the vehicle switch between the two as it turns.
  void far_field(const std::string& patch);
  // The grid's face flux phi_g (m^3/s; empty while every grid is at rest).
  [[nodiscard]] const std::vector<double>& grid_flux() const { return phi_grid_; }
  // Boundary values and face fluxes from the current U (call after setting U and its BCs).
  void initialise();
  StepReport step();

  // Exact restart: write_checkpoint stores every value the next step reads besides the settings
  // and boundary conditions (U, p, phi, both old time levels, time, step count, dt history) in a
  // versioned binary file, atomically. read_checkpoint restores them into a solver constructed
  // on the same grid with the same settings and conditions (after initialise()); the run then
  // continues bitwise as if uninterrupted, except with cholmod-pcg, whose preconditioner is
  // the factor of an earlier matrix (not stored). Throws std::runtime_error naming the file on a
  // foreign, other-version, other-grid or truncated file, leaving the solver unchanged.
  void write_checkpoint(const std::filesystem::path& file) const;
  void read_checkpoint(const std::filesystem::path& file);
  // The same record within a larger one (a plant's, the closed loop's checkpoint); the reader
  // stops after the flow's part (`whole`: the record must end there, checked before anything
  // changes).
  void write_checkpoint(StateWriter& out) const;
  void read_checkpoint(StateReader& in, bool whole = false);
  // Sets the time step of the following steps (prescribed sequences; the adaptive control
  // overrides it). Throws std::invalid_argument unless dt > 0.
  void set_time_step(double dt);
  [[nodiscard]] double time_step() const { return dt_; }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] int steps() const { return steps_; }
  [[nodiscard]] const PimpleSettings& settings() const { return settings_; }
  [[nodiscard]] const Mesh& mesh() const { return mesh_; }

 private:
  struct Momentum {
    std::array<Matrix, 3> eq;  // without the pressure gradient
    // Implicit overset coupling: each equation's entries beyond the face pattern
    // (Overset::couple), part of its H(U).
    std::array<ExtraEntries, 3> extra;
  };
  void assemble_momentum(bool final);
  // The cell gradients of U's three components, computed only when U (its cell and boundary
  // values) is not bit for bit the U of the last computation: the model's strain after the
  // correctors and the next momentum assembly see the same U (the grid's geometry is fixed).
  const std::array<std::vector<Eigen::Vector3d>, 3>& velocity_gradient();
  void transpose_stress();
  void solve_momentum(StepReport& r, bool first, bool final);
  // The linear solves' tolerance of an outer iteration: intermediate_tolerance in a transient
  // step's iterations but the last, else 0 (their own).
  [[nodiscard]] double loose_tolerance(bool final) const {
    return final || settings_.steady ? 0.0 : settings_.intermediate_tolerance;
  }
  void correct_pressure(StepReport& r, bool first, bool final);
  // The face flux phi = phiHbyA - Df (grad p)_f of the pressure cells `pc` (the corrector's
  // phiHbyA, Df and, when `corrected`, its explicit non-orthogonal part), faces masked.
  void pressure_flux(std::span<const double> pc, bool corrected, std::vector<double>& out) const;
  // The same flux on internal face f alone, before masking.
  [[nodiscard]] double internal_pressure_flux(int f, std::span<const double> pc,
                                              bool corrected) const;
  // Overset mass balance (overset_mass.cpp): the fringe-pressure shifts of the open components
  // that make their interface flux zero; `free` the pressure matrix before its rows were fixed.
  void balance_overset_mass(const Matrix& free, bool corrected, StepReport& r);
  // The same balance in one solve (overset_mass.cpp, "bordered"), with cg-amg and the explicit
  // coupling: each open component's fringe ring one more unknown of the pressure equation. The
  // border from the matrix `free` before its rows are fixed, with fixed_ holding the fixed
  // cells' values; after the solve, shift_fringe adds the shifts to the fringe values.
  [[nodiscard]] bool bordered_balance() const {
    return settings_.mass_balance == MassBalance::bordered && !implicit_overset() &&
           settings_.pressure_solver == SymmetricMethod::cg_amg;
  }
  void border_overset_mass(const Matrix& free, bool corrected, Border& border);
  void shift_fringe(std::span<const double> lambda);
  // The place of an overset component in open_components_, -1 if it is closed.
  [[nodiscard]] int open_index(int component) const;
  void store_predictor_force();
  void apply_slip();
  // The skewness-corrected face flux of a cell velocity u into `flux` (internal faces; boundary
  // faces zero).
  void face_flux(const std::array<std::vector<double>, 3>& u, std::vector<double>& flux) const;
  void check(const StepReport& r) const;
  // The largest |U| over the cells in the flow (an overset mesh's active cells) and its cell.
  [[nodiscard]] std::pair<double, int> max_speed() const;
  [[nodiscard]] std::string write_last_good() const;
  void adapt_time_step();
  [[nodiscard]] TimeScheme time_scheme() const {
    return {dt_, settings_.bdf2 && steps_ > 0, dt_old_};
  }

  const Mesh& mesh_;
  PimpleSettings settings_;
  LinearSolver solver_;
  // The arrays of a step, kept from step to step so that a step allocates nothing: the momentum
  // equations of the current outer iteration and the correctors' work.
  Momentum momentum_;
  struct Work {
    std::vector<double> D, Df, phiHbyA, net, rhs, h, source, p_prev;
    std::array<std::vector<double>, 3> HbyA;
    std::vector<Eigen::Vector3d> gp;
    // grad U per component (velocity_gradient()) and the U (cells, then boundary values) it is
    // of; grad_u_of empty when grad_u holds something else (a laminar assembly's components).
    std::array<std::vector<Eigen::Vector3d>, 3> grad_u;
    std::array<std::vector<double>, 3> grad_u_of;
    std::array<std::vector<double>, 3> transpose;
    Matrix p_eq;
    // Overset mass balance: the pressure matrix before fixing, a shifted copy, its solution and
    // flux, the shifted fixed values.
    Matrix p_free, p_shifted;
    std::vector<double> p_shift, phi_shift, fixed_shift, offsets;
    // The bordered form (cg-amg): the border, its unknowns (the fringe shifts), a probe pressure
    // (zero outside border_overset_mass), per column its (row, a_f) entries and its ring's
    // (face, active cell) pairs.
    Border border;
    std::vector<double> lambda, probe;
    std::vector<std::pair<int, double>> probe_flux;  // (face, its flux out of the component)
    std::vector<std::vector<std::pair<int, double>>> border_entries;
    std::vector<std::vector<std::pair<int, int>>> ring_faces;
    // The flux-specified ring: its faces' fluxes, per open component their sum.
    std::vector<double> ring_flux, ring_mismatch;
    // Overset re-assembly: the filled cells' values of one sweep, the cells that hold a value,
    // those still to fill and those filled in a sweep, the faces that came alive.
    std::vector<double> fill;
    std::vector<std::vector<double>*> levels;       // the fields carried, their old levels, p
    std::vector<TurbulenceModel::Carried> carried;  // the turbulence model's (hook 9)
    std::vector<double> mean;
    std::vector<char> holds;
    std::vector<int> pending, filled, rest, born;
  };
  Work work_;
  // The fields at the start of the step, restored when it diverges.
  struct Saved {
    VectorField U;
    ScalarField p;
    std::vector<double> phi;
    std::array<std::array<std::vector<double>, 3>, 2> U_old;
    std::array<std::vector<double>, 2> phi_old;
    std::array<std::vector<double>, 3> predictor_force;
  };
  Saved good_;
  std::array<bool, 3> active_{true, true, true};  // components not normal to empty patches
  std::vector<int> slip_patches_;
  // Some boundary face fixes p (apply_motion decides it every step, as a far field's faces
  // switch); otherwise the reference cell does.
  bool pressure_fixed_ = false;
  // Old time levels: [0] = n, [1] = n - 1.
  std::array<std::array<std::vector<double>, 3>, 2> U_old_;
  std::array<std::vector<double>, 2> phi_old_;
  // face_flux(U_old_[k]) for the Rhie-Chow time correction: derived from U_old_ at the start of
  // every step (the skewness-corrected interpolation costs gradients; once per step, not per
  // corrector).
  std::array<std::vector<double>, 2> U_old_flux_;
  // The force per unit volume that balances the last corrector's momentum equation at its
  // velocity U: (H(U) - A U) / V = grad(p) + N (U_before - U) / V, N the off-diagonal part, whose
  // H(U) lags one corrector (PISO's splitting residual). A step's first predictor applies it in
  // place of grad(p): with grad(p) alone the predictor answers that residual fully implicitly,
  // which on stretched cells amplifies a streamwise pressure wave every step (docs/cfd.md,
  // "Predictor force"). Empty before the first step (grad(p) then); per active component.
  std::array<std::vector<double>, 3> predictor_force_;
  double time_ = 0;
  int steps_ = 0;
  double dt_ = 0;      // this step's time step
  double dt_old_ = 0;  // the previous step's (0 before the first step)
  TurbulenceModel* turbulence_ = nullptr;
  const Overset* overset_ = nullptr;
  int reference_cell_ = 0;      // where p = 0 when no patch fixes it (the first active cell)
  std::vector<double> fixed_;   // overset: the fixed cells' values (scratch)
  double overset_seconds_ = 0;  // this step's StepReport::seconds_overset so far
  // Implicit overset coupling: the pressure equation's entries beyond the face pattern, and the
  // Overset generation the coupled multigrid was planned for (plan_implicit).
  ExtraEntries pressure_extra_;
  int planned_generation_ = -1;
  // The coupled pressure multigrid planned from the geometric Laplacian whenever the assembly
  // changed, so that its aggregates depend on the grid and the stencils alone (exact restart).
  void plan_implicit();
  [[nodiscard]] bool implicit_overset() const {
    return overset_ != nullptr && settings_.overset_coupling == OversetCoupling::implicit;
  }
  // Overset: the components whose active cells touch a fixed-pressure patch, so that their
  // interface flux is not closed by continuity (overset_mass.cpp), and per such component the
  // last pressure response to a unit shift of its fringe values (the next solve's first guess;
  // emptied at the start of a step, so that nothing of it needs a checkpoint).
  std::vector<int> open_components_;
  std::vector<std::vector<double>> shift_response_;
  // The interface fluxes' response to the shifts (M of overset_mass.cpp) and whether it is of
  // this outer iteration's pressure matrix (the correctors of one outer iteration share it).
  Eigen::MatrixXd shift_matrix_;
  bool shift_current_ = false;
  // Overset: zero flux on the faces that carry none (Overset::live).
  void mask_faces(std::vector<double>& flux) const;
  // Overset re-assembly (overset_transition.cpp): the statuses the fields are of, the stage that
  // follows a new assembly (false when nothing changed), and what depends on the statuses.
  std::vector<mesher::CellStatus> status_;
  void snapshot_status();
  // The number of cells whose status changed and of those that came out of a hole (0, 0 when
  // nothing changed).
  std::pair<int, int> follow_assembly();
  void find_open_components();
  // MassBalance::flux (overset_ring.cpp): the faces between an open component's active cells
  // and its fringe ring (face order), per open component the ring's area, and the stage that
  // sets their phiHbyA (and D_f = 0) in a corrector.
  struct RingFace {
    int face;
    int column;   // the component's place in open_components_
    double sign;  // +1 when the face's owner is the active cell (phi out of the active cells)
  };
  std::vector<RingFace> ring_faces_;
  std::vector<double> ring_area_;
  void find_ring_faces();
  void specify_ring_flux();
  void find_reference_cell();  // an active cell: the last one while it stays active
  // Rigid motion (motion.cpp): at the start of initialise() and of every step, the grid flux,
  // the wall velocities, the far field's faces and whether any face fixes p.
  void apply_motion();
  // Overset: U component i of the hole cells = the grid velocity there (zero at rest): the
  // solid moves with its grid, and the gradients of the fringe cells next to a hole see the
  // same values in every frame.
  void set_hole_velocity(std::size_t i);
  // The convecting flux phi - phi_g (phi itself while at rest), into work storage.
  std::span<const double> relative_flux();
  // -(Omega x U)_i per unit volume for component i's momentum equation, into `out` (false when
  // no grid rotates).
  bool rotation_source(std::size_t i, std::vector<double>& out) const;
  [[nodiscard]] int component_of_cell(int c) const {
    return overset_ == nullptr ? 0 : overset_->component_of(c);
  }
  std::vector<FrameMotion> motion_{FrameMotion{}};
  bool moving_ = false;   // some grid has moved since construction: the grid flux is kept
  bool in_step_ = false;  // within step(): set_motion applies the motion at once
  std::vector<Eigen::Vector3d> face_moment_;  // m_f of motion.hpp (m^3), built on first motion
  std::vector<double> phi_grid_, phi_rel_;
  std::vector<int> wall_patches_, far_field_patches_;
};

// Maximum Courant number dt * sum |phi| / (2 V) over the cells, with the cell where it occurs.
std::pair<double, int> courant(const Mesh& mesh, std::span<const double> phi, double dt);

}  // namespace auvloop::engine::fv
