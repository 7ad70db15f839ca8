// SPDX-License-Identifier: GPL-3.0-or-later
// A turbulence model as the PIMPLE step sees it: the hook points where it plugs into the step
// (pimple.cpp), in the order the step calls them:
//   1. initialise(U, phi)    Pimple::initialise, after the flow's own initial fields;
//   2. begin_step()          after the flow's time levels shift: the model shifts its own;
//   3. nu_eff()              read by every momentum assembly: the effective viscosity per face
//                            (m^2/s), nu + nu_t, wall faces from the model's wall treatment;
//   4. correct(input)        after the pressure correctors of every outer iteration: the
//                            model's own equations with the corrected U and phi, then nu_eff;
//   5. save() / restore()    with the step's last good fields (a diverged step restores both);
//   6. check()               after the step: throws std::runtime_error naming the first cell
//                            with a non-finite or non-physical value;
//   7. state()               the arrays a checkpoint stores;
//   8. set_overset(o)        Pimple::set_overset / set_turbulence on an overset mesh (o null:
//                            none): the model's transported fields ride on the coupling as a
//                            scalar does (overset.hpp): explicitly, fringe rows fixed to the
//                            donors' interpolation of the current values (bounded by the donors'
//                            range, Overset::Bound::donors: k and omega stay positive where they
//                            are steep) and hole rows to their
//                            own, after any under-relaxation, and the fringe cells set to their
//                            interpolation again after each solve;
//   9. carried(out)          the transported fields' cells and their old time level (n - 1 when
//                            the step's re-assembly stage runs, before begin_step), which Pimple's
//                            re-assembly carries onto new cell statuses with U
//                            (overset_transition.cpp; interpolated bounded, as in hook 8).
// The flow never owns the model; the model must outlive the Pimple it is attached to.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "auvloop/engine/fv/field.hpp"
#include "auvloop/engine/fv/linear_solver.hpp"
#include "auvloop/engine/fv/operators.hpp"

namespace auvloop::engine::fv {

class Overset;

// What correct() is given: the flow after its pressure correctors.
struct TurbulenceInput {
  const VectorField* U = nullptr;
  // The cell gradients of U's components (Mesh::gradient of U's current values), which the next
  // momentum assembly reuses while U stays as it is.
  const std::array<std::vector<Eigen::Vector3d>, 3>* grad_U = nullptr;
  std::span<const double> phi;  // face volume fluxes (m^3/s)
  TimeScheme time;              // this step's scheme (Euler on the first step)
  bool steady = false;          // no time derivative (PimpleSettings::steady)
  bool final = false;           // the step's final outer iteration: no under-relaxation
  // > 0: the relative tolerance of the solves when not final (PimpleSettings).
  double intermediate_tolerance = 0;
  LinearSolver* solver = nullptr;
};

// What correct() did, for the step report: per equation, its initial normalised residual and
// linear-solver iterations; how many cells the positivity bound and the production limiter
// changed.
struct TurbulenceReport {
  double k_residual = 0, omega_residual = 0;
  int k_iterations = 0, omega_iterations = 0;
  long bounded_cells = 0;  // cells whose k or omega fell below its floor and were raised to it
  long limited_cells = 0;  // cells where the production limiter acted
  // Wall-clock time of the model's overset work (fixed fringe rows, interpolations: hook 8),
  // also counted in StepReport::seconds_overset.
  double seconds_overset = 0;
  void add(const TurbulenceReport& o) {
    k_residual = std::max(k_residual, o.k_residual);
    omega_residual = std::max(omega_residual, o.omega_residual);
    k_iterations += o.k_iterations;
    omega_iterations += o.omega_iterations;
    bounded_cells += o.bounded_cells;
    limited_cells += o.limited_cells;
    seconds_overset += o.seconds_overset;
  }
};

class TurbulenceModel {
 public:
  virtual ~TurbulenceModel() = default;
  virtual void initialise(const VectorField& U, std::span<const double> phi) = 0;
  virtual void begin_step() = 0;
  [[nodiscard]] virtual std::span<const double> nu_eff() const = 0;
  virtual TurbulenceReport correct(const TurbulenceInput& input) = 0;
  virtual void save() = 0;
  virtual void restore() = 0;
  virtual void check() const = 0;
  // The model's cell fields, for output (k, omega, nu_t, ...).
  [[nodiscard]] virtual std::vector<const ScalarField*> fields() const = 0;
  [[nodiscard]] virtual std::vector<ScalarField*> fields() = 0;
  // Every array a step reads besides the flow's and the settings (fields with their boundary
  // values, old time levels, nu_eff), in a fixed order and of sizes fixed by the grid: what
  // Pimple's checkpoint stores so that a restart continues bitwise.
  [[nodiscard]] virtual std::vector<std::vector<double>*> state() = 0;
  virtual void set_overset(const Overset* overset) = 0;
  struct Carried {
    std::vector<double>* cells = nullptr;  // one per cell
    std::vector<double>* old = nullptr;    // the time level the next step keeps as n - 1
  };
  // Replaces `out`'s contents (a vector the caller keeps: nothing allocated once it has held as
  // many).
  virtual void carried(std::vector<Carried>& out) = 0;
};

}  // namespace auvloop::engine::fv
