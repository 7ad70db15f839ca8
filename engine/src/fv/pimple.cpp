// SPDX-License-Identifier: GPL-3.0-or-later
// The PIMPLE time step (docs/cfd.md, "Algorithm"):
//   1. shift the time levels (U, phi); BDF2 from the second step, Euler on the first;
//   2. for each outer iteration: refresh slip values, assemble momentum with the lagged flux
//      and pressure, solve the predictor (momentum.cpp);
//   3. then the pressure correctors (pressure.cpp), the last outer iteration unrelaxed, and the
//      force that balances the corrected velocity, for the next step's predictor; a turbulence
//      model's correct() (in the last outer iteration only with turbulence_final_only, the
//      eddy viscosity then the last step's in the others); when another outer iteration follows,
//      the motion_correct hook (the 6-DOF coupling), whose new motion applies at once (motion.cpp);
//   4. Courant number, continuity error, divergence checks; on failure restore the last good
//      fields and throw DivergenceError naming where and when.
#include "auvloop/engine/fv/pimple.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "auvloop/engine/fv/output.hpp"
#include "diagnosis.hpp"
#include "parallel.hpp"
#include "scratch.hpp"
#include "stopwatch.hpp"

namespace auvloop::engine::fv {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

std::pair<double, int> courant(const Mesh& mesh, std::span<const double> phi, double dt) {
  Scratch<double> sum(static_cast<std::size_t>(mesh.cells()));
  sum_faces(
      mesh, *sum, [&](int f) { return std::abs(phi[static_cast<std::size_t>(f)]); }, 1.0);
  std::pair<double, int> worst{0.0, 0};
  for (int c = 0; c < mesh.cells(); ++c) {
    const double co = 0.5 * dt * sum[static_cast<std::size_t>(c)] / mesh.volume(c);
    if (co > worst.first) worst = {co, c};
  }
  return worst;
}

const char* to_string(OversetCoupling c) {
  return c == OversetCoupling::lagged ? "explicit" : "implicit";
}

OversetCoupling overset_coupling_from_string(const std::string& s) {
  for (auto c : {OversetCoupling::lagged, OversetCoupling::implicit})
    if (s == to_string(c)) return c;
  throw std::invalid_argument("unknown overset coupling '" + s + "' (explicit, implicit)");
}

const char* to_string(MassBalance b) {
  switch (b) {
    case MassBalance::flux:
      return "flux";
    case MassBalance::bordered:
      return "bordered";
    case MassBalance::response:
      return "response";
    case MassBalance::off:
      return "off";
  }
  return "?";
}

MassBalance mass_balance_from_string(const std::string& s) {
  for (auto b : {MassBalance::flux, MassBalance::bordered, MassBalance::response, MassBalance::off})
    if (s == to_string(b)) return b;
  throw std::invalid_argument("unknown overset mass balance '" + s +
                              "' (flux, bordered, response, off)");
}

Pimple::Pimple(const Mesh& mesh, PimpleSettings settings)
    : U(mesh, "U"),
      p(mesh, "p"),
      phi(static_cast<std::size_t>(mesh.faces()), 0.0),
      mesh_(mesh),
      settings_(settings),
      solver_(mesh, Tolerance(settings.tolerance, settings.residual_norm)) {
  // A direction normal to an empty patch carries no velocity component (2D grids).
  for (const auto& patch : mesh.grid().patches) {
    if (patch.type != mesher::PatchType::empty || patch.size == 0) continue;
    const Eigen::Vector3d n = mesh.area(patch.start).normalized();
    for (int i = 0; i < 3; ++i)
      if (std::abs(n[i]) > 0.999) active_[static_cast<std::size_t>(i)] = false;
  }
  if (!(settings_.dt > 0))
    throw std::invalid_argument(fmt::format("Pimple: dt must be positive, got {}", settings_.dt));
  if (settings_.target_courant > 0 &&
      !(settings_.max_dt_growth > 1 && settings_.max_dt_growth < 1 + std::numbers::sqrt2))
    throw std::invalid_argument(fmt::format(
        "Pimple: max_dt_growth must be in (1, 1 + sqrt 2) for stable variable-step BDF2, got {}",
        settings_.max_dt_growth));
  dt_ = settings_.dt;
  if (!settings_.pressure_solver) {
    const bool two_d = !(active_[0] && active_[1] && active_[2]);
    settings_.pressure_solver = two_d ? SymmetricMethod::cholmod_pcg : SymmetricMethod::cg_amg;
  }
}

void Pimple::plan_implicit() {
  if (!implicit_overset() || planned_generation_ == overset_->generation()) return;
  Matrix m = laplacian(mesh_, 1.0, p);
  overset_->couple(m, p.cells, std::numeric_limits<double>::quiet_NaN(), {}, pressure_extra_,
                   fixed_);
  solver_.plan_coupled(m, pressure_extra_);
  planned_generation_ = overset_->generation();
}

void Pimple::set_overset(const Overset* overset) {
  overset_ = overset;
  if (turbulence_ != nullptr) turbulence_->set_overset(overset_);
}

void Pimple::set_turbulence(TurbulenceModel* model) {
  if (turbulence_ != nullptr && turbulence_ != model) turbulence_->set_overset(nullptr);
  turbulence_ = model;
  if (turbulence_ != nullptr) turbulence_->set_overset(overset_);
}

void Pimple::mask_faces(std::vector<double>& flux) const {
  if (overset_ == nullptr) return;
  parallel_for(mesh_.faces(), [&](int f) {
    if (!overset_->live(f)) flux[static_cast<std::size_t>(f)] = 0.0;
  });
}

void Pimple::slip(const std::string& patch) {
  slip_patches_.push_back(patch_index(mesh_, patch));
  U.fix(mesh_, patch, Eigen::Vector3d::Zero());
}

void Pimple::apply_slip() {
  for (int pi : slip_patches_) {
    const auto& patch = mesh_.grid().patches[static_cast<std::size_t>(pi)];
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const Eigen::Vector3d n = mesh_.area(f).normalized();
      const Eigen::Vector3d u = U.cell(mesh_.owner(f));
      // No flux relative to the grid: the normal component is the grid's (zero at rest).
      const auto& m = motion_[static_cast<std::size_t>(component_of_cell(mesh_.owner(f)))];
      const Eigen::Vector3d t = u - (u - m.at(mesh_.face_centre(f))).dot(n) * n;
      for (std::size_t c = 0; c < 3; ++c)
        U.c[c].bcs[static_cast<std::size_t>(pi)].value[static_cast<std::size_t>(i)] =
            t[static_cast<Eigen::Index>(c)];
    }
  }
  U.update_boundary(mesh_);
}

void Pimple::initialise() {
  reference_cell_ = 0;
  find_reference_cell();
  if (overset_ != nullptr) {
    overset_->apply(std::array<std::span<double>, 3>{U.c[0].cells, U.c[1].cells, U.c[2].cells});
    overset_->apply(p.cells, std::numeric_limits<double>::quiet_NaN());
  }
  // The pressure solver's structure (cg-amg's aggregates) from the geometric Laplacian, a
  // function of the grid alone, not from the first step's matrix: a restart continues bitwise.
  solver_.plan_symmetric(Matrix(laplacian(mesh_, 1.0, p)), *settings_.pressure_solver);
  planned_generation_ = -1;
  plan_implicit();
  // Overset: the open components (overset_mass.cpp), those with fringe cells and an active cell
  // on a fixed-pressure patch; the statuses the fields are now of.
  find_open_components();
  snapshot_status();
  apply_motion();
  apply_slip();
  p.update_boundary(mesh_);
  std::array<std::vector<double>, 3> u{U.c[0].cells, U.c[1].cells, U.c[2].cells};
  face_flux(u, phi);
  for (int b = 0; b < mesh_.boundary_faces(); ++b) {
    const int f = b + mesh_.internal_faces();
    phi[static_cast<std::size_t>(f)] =
        U.c[0].is_empty(mesh_, b) ? 0.0 : U.face(b).dot(mesh_.area(f));
  }
  mask_faces(phi);
  for (auto& level : U_old_) level = u;
  for (auto& level : phi_old_) level = phi;
  for (auto& force : predictor_force_) force.clear();
  steps_ = 0;
  dt_old_ = 0;
  if (turbulence_) turbulence_->initialise(U, relative_flux());
}

void Pimple::set_time_step(double dt) {
  if (!(dt > 0 && std::isfinite(dt)))
    throw std::invalid_argument(fmt::format("Pimple: time step must be positive, got {}", dt));
  dt_ = dt;
}

// dt for the target Courant number of the current flux (which the step will carry), limited in
// growth (a flow at rest or slowing down would otherwise jump to large steps at once).
void Pimple::adapt_time_step() {
  const double co = courant(mesh_, relative_flux(), dt_).first;
  double dt = dt_ * settings_.max_dt_growth;
  if (co > 0) dt = std::min(dt, dt_ * settings_.target_courant / co);
  if (settings_.max_dt > 0) dt = std::min(dt, settings_.max_dt);
  dt_ = dt;
}

StepReport Pimple::step() {
  const Team::Region team(threads());  // every loop of the step on one team (team.hpp)
  if (settings_.target_courant > 0 && steps_ > 0) adapt_time_step();
  if (!body_force.empty() && body_force.size() != static_cast<std::size_t>(mesh_.cells()))
    throw std::invalid_argument(fmt::format("Pimple: body_force has {} entries for {} cells",
                                            body_force.size(), mesh_.cells()));
  overset_seconds_ = 0;
  int status_changes = 0, uncovered_cells = 0;
  {
    const ScopedSeconds clock(overset_seconds_);
    std::tie(status_changes, uncovered_cells) = follow_assembly();  // overset re-assembly
    plan_implicit();
  }
  // Copy assignments into kept storage: no allocation after the first step.
  good_.U = U;
  good_.p = p;
  good_.phi = phi;
  good_.U_old = U_old_;
  good_.phi_old = phi_old_;
  good_.predictor_force = predictor_force_;
  apply_motion();  // the grids' motion at the new time level: grid flux and boundary values
  struct InStep {  // set_motion within the step applies the motion at once
    bool& flag;
    explicit InStep(bool& f) : flag(f) { flag = true; }
    ~InStep() { flag = false; }
    InStep(const InStep&) = delete;
    InStep& operator=(const InStep&) = delete;
  } in_step(in_step_);
  if (turbulence_) {
    turbulence_->save();
    turbulence_->begin_step();
  }
  U_old_[1].swap(U_old_[0]);
  for (std::size_t i = 0; i < 3; ++i) U_old_[0][i] = U.c[i].cells;
  // The mass balance's warm start lives within a step: a restart from a checkpoint (written
  // between steps) then continues bitwise.
  for (auto& response : shift_response_) response.clear();
  work_.lambda.clear();  // the bordered balance's shifts: from zero (nothing to checkpoint)
  phi_old_[1].swap(phi_old_[0]);
  phi_old_[0] = phi;
  const auto coeffs = TimeScheme{settings_.dt, settings_.bdf2 && steps_ > 0}.coeffs();
  for (std::size_t k = 0; k < 2; ++k)
    if (coeffs[k + 1] != 0.0) face_flux(U_old_[k], U_old_flux_[k]);
  StepReport r;
  const double gradient_seconds = mesh_.gradient_seconds();
  r.step = steps_ + 1;
  r.status_changes = status_changes;
  r.uncovered_cells = uncovered_cells;
  r.dt = dt_;
  r.time = time_ + dt_;
  try {
    for (int outer = 1; outer <= settings_.outer_iterations; ++outer) {
      // The final outer iteration is unrelaxed, unless the solve is steady (SIMPLE).
      const bool final = outer == settings_.outer_iterations && !settings_.steady;
      auto t0 = std::chrono::steady_clock::now();
      apply_slip();
      assemble_momentum(final);
      r.seconds_assembly += seconds_since(t0);
      solve_momentum(r, outer == 1, final);
      r.seconds_momentum += seconds_since(t0);
      t0 = std::chrono::steady_clock::now();
      shift_current_ = false;  // a new momentum matrix: a new pressure matrix
      for (int corr = 0; corr < settings_.pressure_correctors; ++corr)
        correct_pressure(r, outer == 1 && corr == 0, final);
      store_predictor_force();
      r.seconds_pressure += seconds_since(t0);
      // Converged outer loop: momentum's initial residual of this iteration is small enough.
      const bool converged = outer > 1 && r.outer_residual < settings_.outer_tolerance;
      if (turbulence_ &&
          (final || converged || settings_.steady || !settings_.turbulence_final_only)) {
        t0 = std::chrono::steady_clock::now();
        TurbulenceInput in;
        in.U = &U;
        in.grad_U = &velocity_gradient();
        in.phi = relative_flux();
        in.time = time_scheme();
        in.steady = settings_.steady;
        in.final = final;
        in.intermediate_tolerance = loose_tolerance(false);
        in.solver = &solver_;
        r.turbulence.add(turbulence_->correct(in));
        r.seconds_turbulence += seconds_since(t0);
      }
      r.outer_iterations = outer;
      if (converged) break;
      if (motion_correct && outer < settings_.outer_iterations) motion_correct(outer);
    }
    const auto t0 = std::chrono::steady_clock::now();
    const auto [co, cell] = courant(mesh_, relative_flux(), dt_);
    r.max_courant = co;
    r.max_speed = max_speed().first;
    Scratch<double> d(static_cast<std::size_t>(mesh_.cells()));
    div(mesh_, phi, *d);
    // Over the active cells of an overset mesh: the others solve no continuity equation.
    r.continuity_error =
        parallel_sum<1>(mesh_.cells(),
                        [&](int lo, int hi, std::array<double, 1>& s) {
                          for (int c = lo; c < hi; ++c)
                            if (overset_ == nullptr || overset_->active(c))
                              s[0] += std::abs(d[static_cast<std::size_t>(c)]) * mesh_.volume(c);
                        })[0] *
        dt_ / (overset_ == nullptr ? mesh_.total_volume() : overset_->active_volume());
    if (overset_ != nullptr) {
      const ScopedSeconds clock(overset_seconds_);
      for (double q : interface_flux(*overset_, mesh_, phi))
        r.interface_flux = std::max(r.interface_flux, std::abs(q));
    }
    r.seconds_overset = overset_seconds_ + r.turbulence.seconds_overset;
    r.seconds_other = seconds_since(t0);
    r.seconds_gradient = mesh_.gradient_seconds() - gradient_seconds;
    check(r);
  } catch (const std::exception& e) {
    U = good_.U;
    p = good_.p;
    phi = good_.phi;
    U_old_ = good_.U_old;
    phi_old_ = good_.phi_old;
    predictor_force_ = good_.predictor_force;
    if (turbulence_) turbulence_->restore();
    throw DivergenceError(
        fmt::format("the flow's step {} (flow time {:.6g} s) diverged: {}; the fields of flow "
                    "time {:.6g} s are kept{}",
                    r.step, r.time, e.what(), time_, write_last_good()));
  }
  time_ = r.time;
  ++steps_;
  dt_old_ = dt_;
  return r;
}

std::pair<double, int> Pimple::max_speed() const {
  std::pair<double, int> worst{0.0, 0};
  for (int c = 0; c < mesh_.cells(); ++c) {
    if (overset_ != nullptr && !overset_->active(c)) continue;
    const double speed = U.cell(c).norm();
    if (speed > worst.first) worst = {speed, c};
  }
  return worst;
}

void Pimple::check(const StepReport& r) const {
  const double bad = parallel_sum<1>(mesh_.cells(), [&](int lo, int hi, std::array<double, 1>& s) {
    for (int c = lo; c < hi; ++c)
      if (!std::isfinite(p.cells[static_cast<std::size_t>(c)]) || !U.cell(c).allFinite()) s[0] += 1;
  })[0];
  if (turbulence_) turbulence_->check();
  for (int c = 0; bad > 0 && c < mesh_.cells(); ++c) {  // the first such cell, named
    const auto s = static_cast<std::size_t>(c);
    if (!std::isfinite(p.cells[s]) || !U.cell(c).allFinite())
      throw std::runtime_error("non-finite velocity or pressure in " + cell_at(mesh_, c));
  }
  if (settings_.max_speed > 0 && r.max_speed > settings_.max_speed) {
    const auto [speed, cell] = max_speed();
    throw std::runtime_error(fmt::format("|U| {:.3g} m/s beyond the limit {:.3g} m/s in {}", speed,
                                         settings_.max_speed, cell_at(mesh_, cell)));
  }
  if (r.max_courant > settings_.max_courant) {
    const auto [co, cell] = courant(mesh_, phi_grid_.empty() ? phi : phi_rel_, dt_);
    throw std::runtime_error(fmt::format("Courant number {:.3g} beyond the limit {:.3g} in {}", co,
                                         settings_.max_courant, cell_at(mesh_, cell)));
  }
}

// The restored fields to settings.divergence_directory; the clause for the message. A failure to
// write is reported in the message, not thrown: the divergence is the error to report.
std::string Pimple::write_last_good() const {
  const auto& dir = settings_.divergence_directory;
  if (dir.empty()) return "";
  try {
    std::filesystem::create_directories(dir);
    VtkSeries vtk(dir, "last-good");
    vtk.write(*this);
    write_checkpoint(dir / "last-good.checkpoint");
    return fmt::format(" and written to {} and {}", vtk.pvd().string(),
                       (dir / "last-good.checkpoint").string());
  } catch (const std::exception& e) {
    return fmt::format(" (writing them to {} failed: {})", dir.string(), e.what());
  }
}

}  // namespace auvloop::engine::fv
