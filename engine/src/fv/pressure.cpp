// SPDX-License-Identifier: GPL-3.0-or-later
// PIMPLE step 3 (docs/cfd.md): one pressure corrector.
//   a. A = the diagonal of the momentum matrix, D = V / A, HbyA = H(U) / A with H(U) the
//      off-diagonal part and sources (old time levels, deferred corrections): U = HbyA - D grad p.
//   b. Rhie-Chow face flux phiHbyA = (HbyA)_f . S + (D / dt)_f sum_k (-c_k) (phi_k - (U_k)_f . S)
//      over the old time levels k: the old-time part of H is taken from the old face fluxes,
//      not from interpolated velocities, so the converged flux does not depend on dt.
//   c. laplacian(D_f, p) == div(phiHbyA), with non-orthogonal correctors.
//   d. phi = phiHbyA - the pressure equation's face flux (conservative to the solver tolerance);
//      p relaxed in all but the final outer iteration; U = HbyA - D grad(p).
#include "auvloop/engine/fv/pimple.hpp"

#include <limits>
#include <optional>

#include <Eigen/LU>

#include "diagnosis.hpp"
#include "parallel.hpp"
#include "scratch.hpp"
#include "stopwatch.hpp"

namespace auvloop::engine::fv {

namespace {
Eigen::Vector3d cell_vector(const std::array<std::vector<double>, 3>& u, std::size_t c) {
  return {u[0][c], u[1][c], u[2][c]};
}

// The value the cell gradients see on zero-gradient pressure patches (walls, inlets). p_b = p_P
// there means dp/dn = 0 to the least-squares fit, which is wrong wherever the wall-normal pressure
// gradient is not zero (mu d2u_n/dn2 at a no-slip wall, the stagnation region of a cylinder): the
// wall cells' grad(p), and through U = HbyA - D grad(p) their velocity, then carry an O(1) error.
// Instead p_b = p_P + g_P . (x_b - x_P) with g_P the least-squares gradient of the cell's other
// points (neighbours, fixed and empty faces): consistent with the fit, so every later grad(p)
// returns g_P there. The pressure equation still sees the flux condition only.
bool free_pressure_face(const Mesh& mesh, const ScalarField& p, int f) {
  if (f < mesh.internal_faces()) return false;
  const int b = f - mesh.internal_faces();
  return !p.is_empty(mesh, b) && p.value_coeffs(mesh, b)[0] == 1.0;  // zero gradient here
}

void extrapolate_zero_gradient(const Mesh& mesh, ScalarField& p) {
  const auto cells = mesh.boundary_cells();
  parallel_for(static_cast<int>(cells.size()), [&](int i) {  // a cell writes its own faces only
    const int c = cells[static_cast<std::size_t>(i)];
    const auto cell_faces = mesh.cell_faces(c);
    bool any = false;
    for (int f : cell_faces) any = any || free_pressure_face(mesh, p, f);
    if (!any) return;
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    const auto P = static_cast<std::size_t>(c);
    for (int f : cell_faces) {
      if (free_pressure_face(mesh, p, f)) continue;
      double other;
      Eigen::Vector3d d;
      if (f < mesh.internal_faces()) {
        const int n = mesh.owner(f) == c ? mesh.neighbour(f) : mesh.owner(f);
        d = mesh.centre(n) - mesh.centre(c);
        other = p.cells[static_cast<std::size_t>(n)];
      } else {
        d = mesh.face_centre(f) - mesh.centre(c);
        other = p.boundary[static_cast<std::size_t>(f - mesh.internal_faces())];
      }
      M += d * d.transpose() / d.squaredNorm();
      rhs += d * (other - p.cells[P]) / d.squaredNorm();
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
    if (!lu.isInvertible()) return;  // too few other points: keep p_b = p_P
    const Eigen::Vector3d g = lu.solve(rhs);
    for (int f : cell_faces) {
      if (!free_pressure_face(mesh, p, f)) continue;
      p.boundary[static_cast<std::size_t>(f - mesh.internal_faces())] =
          p.cells[P] + g.dot(mesh.face_centre(f) - mesh.centre(c));
    }
  });
}
}  // namespace

void Pimple::face_flux(const std::array<std::vector<double>, 3>& u, std::vector<double>& f) const {
  // Skewness-corrected interpolation (mesh.hpp, "skew") of each active component: with plain
  // w u_P + (1 - w) u_N the flux is first order wherever the skewness does not shrink under
  // refinement (an O-grid's corners), and the converged flow then depends on where they are.
  // The gradients see U's boundary values on fixed-velocity patches, the cell value elsewhere.
  f.resize(static_cast<std::size_t>(mesh_.faces()));
  const int internal = mesh_.internal_faces();
  parallel_for(mesh_.faces(), [&](int j) {
    const auto js = static_cast<std::size_t>(j);
    if (j >= internal || mesh_.skewed()) {
      f[js] = 0.0;
      return;
    }
    const double w = mesh_.weight(j);
    f[js] = (w * cell_vector(u, static_cast<std::size_t>(mesh_.owner(j))) +
             (1 - w) * cell_vector(u, static_cast<std::size_t>(mesh_.neighbour(j))))
                .dot(mesh_.area(j));
  });
  if (!mesh_.skewed()) return;
  Scratch<double> boundary(static_cast<std::size_t>(mesh_.boundary_faces()));
  Scratch<Eigen::Vector3d> g(static_cast<std::size_t>(mesh_.cells()));
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    parallel_for(mesh_.boundary_faces(), [&](int b) {
      const bool fixed = U.c[i].value_coeffs(mesh_, b)[0] == 0.0;
      boundary[static_cast<std::size_t>(b)] =
          fixed ? U.c[i].boundary[static_cast<std::size_t>(b)]
                : u[i][static_cast<std::size_t>(mesh_.owner(b + internal))];
    });
    mesh_.gradient(u[i], *boundary, *g);
    const auto e = static_cast<Eigen::Index>(i);
    parallel_for(internal, [&](int j) {
      f[static_cast<std::size_t>(j)] += interpolate(mesh_, u[i], *g, j) * mesh_.area(j)[e];
    });
  }
}

void Pimple::correct_pressure(StepReport& r, bool first, bool final) {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  const int internal = mesh_.internal_faces();
  const std::size_t a0 = active_[0] ? 0 : (active_[1] ? 1 : 2);
  const auto& eqs = momentum_.eq;
  const auto& A = eqs[a0].diag;
  auto& W = work_;
  auto& D = W.D;
  auto& HbyA = W.HbyA;
  D.resize(n);
  parallel_for(mesh_.cells(), [&](int c) {
    D[static_cast<std::size_t>(c)] = mesh_.volume(c) / A[static_cast<std::size_t>(c)];
  });
  for (std::size_t i = 0; i < 3; ++i) {
    HbyA[i].resize(n);
    if (!active_[i]) {
      std::fill(HbyA[i].begin(), HbyA[i].end(), 0.0);
      continue;
    }
    eqs[i].h_operator(mesh_, U.c[i].cells, HbyA[i]);
    // Implicit overset coupling: an active row's couplings to its fringe neighbours are entries
    // beyond the face pattern (overset_implicit.cpp, step 2), part of its H too (fringe rows'
    // HbyA is set below).
    if (implicit_overset()) momentum_.extra[i].multiply_add(U.c[i].cells, HbyA[i], -1.0);
    parallel_for(mesh_.cells(), [&](int c) {
      HbyA[i][static_cast<std::size_t>(c)] /= A[static_cast<std::size_t>(c)];
    });
  }
  // Overset (overset.hpp, step 3): a fringe cell's HbyA = U + D grad(p), so that the Rhie-Chow
  // flux at an active-fringe face treats it as an active cell whose U is the interpolated one;
  // hole cells (fixed to zero) keep HbyA = 0.
  // The gradient is the first non-orthogonal corrector's (below) on a mesh that is not
  // orthogonal, which that corrector would take anyway: overset work only on an orthogonal mesh.
  const bool corrected = !mesh_.orthogonal();
  if (overset_ != nullptr) {
    auto& gp = W.gp;
    gp.resize(n);
    {
      std::optional<ScopedSeconds> clock;
      if (!corrected) clock.emplace(overset_seconds_);
      mesh_.gradient(p.cells, p.boundary, gp);
    }
    const ScopedSeconds clock(overset_seconds_);
    for (int c : overset_->fringe_cells()) {
      const auto s = static_cast<std::size_t>(c);
      for (std::size_t i = 0; i < 3; ++i)
        if (active_[i]) HbyA[i][s] = U.c[i].cells[s] + D[s] * gp[s][static_cast<Eigen::Index>(i)];
    }
  }
  // b. Rhie-Chow flux with the time-consistent correction; the face D.
  auto& phiHbyA = W.phiHbyA;
  auto& Df = W.Df;
  face_flux(HbyA, phiHbyA);
  Df.resize(static_cast<std::size_t>(mesh_.faces()));
  auto coeffs = time_scheme().coeffs();
  if (settings_.steady) coeffs = {0.0, 0.0, 0.0};  // no time derivative, no time correction
  parallel_for(mesh_.faces(), [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    const auto P = static_cast<std::size_t>(mesh_.owner(f));
    if (f < internal) {
      const double w = mesh_.weight(f);
      Df[fs] = w * D[P] + (1 - w) * D[static_cast<std::size_t>(mesh_.neighbour(f))];
      for (std::size_t k = 0; k < 2; ++k) {
        if (coeffs[k + 1] == 0.0) continue;
        phiHbyA[fs] += Df[fs] / dt_ * -coeffs[k + 1] * (phi_old_[k][fs] - U_old_flux_[k][fs]);
      }
      return;
    }
    const int b = f - internal;
    Df[fs] = D[P];
    const bool fixed_u = U.c[a0].value_coeffs(mesh_, b)[0] == 0.0;
    phiHbyA[fs] = U.c[a0].is_empty(mesh_, b)
                      ? 0.0
                      : (fixed_u ? U.face(b) : cell_vector(HbyA, P)).dot(mesh_.area(f));
  });
  // Overset, the flux-specified ring of the open components (overset_ring.cpp).
  const bool ring =
      overset_ != nullptr && !ring_faces_.empty() && settings_.mass_balance == MassBalance::flux;
  if (ring) {
    const ScopedSeconds clock(overset_seconds_);
    specify_ring_flux();
  }
  // c. and d.
  W.p_prev = p.cells;
  auto& net = W.net;
  net.resize(n);
  div(mesh_, phiHbyA, net);
  auto& gp = W.gp;
  gp.resize(n);
  Matrix& eq = W.p_eq;
  for (int corr = 0; corr <= settings_.non_orthogonal_correctors; ++corr) {
    // (an overset mesh's fringe HbyA above took the first corrector's gradient of the same p)
    if (corrected && !(overset_ != nullptr && corr == 0)) mesh_.gradient(p.cells, p.boundary, gp);
    eq = laplacian(mesh_, Df, p);
    parallel_for(mesh_.cells(), [&](int c) {
      eq.source[static_cast<std::size_t>(c)] += net[static_cast<std::size_t>(c)] * mesh_.volume(c);
    });
    // Overset (step 2): fringe rows the interpolation of the current p, hole rows their value.
    // Every non-orthogonal corrector: the next one refreshes the fringe values from this one's
    // p, and an unbalanced p there made a closed grid's fringe read a pressure that the balance
    // then moved; the steady state kept the mismatch (4e-3 of the fringe pressure, p and U no
    // better than first order in mms-overset). Holding the fringe values through the loop
    // instead did not converge on mms-overset's finest level.
    const bool balance = overset_ != nullptr && !open_components_.empty() &&
                         settings_.mass_balance != MassBalance::off && !ring;
    const bool bordered = balance && bordered_balance();
    if (balance && !bordered && !shift_current_) W.p_free = eq;  // only the response reads it
    if (implicit_overset()) {                                    // overset_implicit.cpp
      const ScopedSeconds clock(overset_seconds_);
      overset_->couple(eq, p.cells, std::numeric_limits<double>::quiet_NaN(), {}, pressure_extra_,
                       fixed_);
    } else if (overset_ != nullptr) {
      const ScopedSeconds clock(overset_seconds_);
      overset_->fixed_values(p.cells, std::numeric_limits<double>::quiet_NaN(), fixed_);
      if (bordered) border_overset_mass(eq, corrected, W.border);
      eq.fix_values(mesh_, overset_->fixed_cells(), fixed_);
    }
    if (!pressure_fixed_) {  // reference value p = 0 in the reference cell
      const auto ref = static_cast<std::size_t>(reference_cell_);
      eq.diag[ref] += eq.diag[ref];
    }
    const double tol = loose_tolerance(final);  // 0: the solver's own
    const auto s = solve_named(mesh_, eq, p.cells, "pressure equation", [&] {
      if (bordered) {
        W.lambda.resize(open_components_.size(), 0.0);  // the last corrector's: a first guess
        return solver_.solve_bordered(eq, W.border, p.cells, W.lambda, *settings_.pressure_solver,
                                      tol);
      }
      if (implicit_overset())
        return solver_.solve_coupled(eq, pressure_extra_, p.cells, settings_.pressure_solver, tol);
      return solver_.solve_symmetric(eq, p.cells, *settings_.pressure_solver, tol);
    });
    if (first && corr == 0) r.pressure_residual = s.initial_residual;
    r.pressure_iterations += s.iterations;
    if (implicit_overset()) {
      const ScopedSeconds clock(overset_seconds_);
      overset_->apply(p.cells, std::numeric_limits<double>::quiet_NaN());
    }
    if (bordered) {
      const ScopedSeconds clock(overset_seconds_);
      shift_fringe(W.lambda);
    }
    pressure_flux(p.cells, corrected, phi);
    // Overset: the open components' interface flux to zero (overset_mass.cpp), every corrector:
    // a flux that keeps the interpolation's mismatch in an earlier outer iteration convects
    // momentum differently in a moving frame (balanced in the last iteration only, a towed
    // cylinder differed from the fixed one in a stream by 1.2e-4 of the speed, not 1e-7).
    if (balance && !bordered) {
      const ScopedSeconds clock(overset_seconds_);
      balance_overset_mass(W.p_free, corrected, r);
    }
  }
  if (!final && settings_.relax_p < 1) {
    parallel_for(mesh_.cells(), [&](int c) {
      const auto s = static_cast<std::size_t>(c);
      p.cells[s] = W.p_prev[s] + settings_.relax_p * (p.cells[s] - W.p_prev[s]);
    });
  }
  p.update_boundary(mesh_);
  extrapolate_zero_gradient(mesh_, p);
  mesh_.gradient(p.cells, p.boundary, gp);
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    const auto e = static_cast<Eigen::Index>(i);
    parallel_for(mesh_.cells(), [&](int c) {
      const auto s = static_cast<std::size_t>(c);
      U.c[i].cells[s] = HbyA[i][s] - D[s] * gp[s][e];
    });
  }
  if (overset_ != nullptr) {  // overset, step 4 (a turned donor's vector needs all components)
    const ScopedSeconds clock(overset_seconds_);
    overset_->apply(std::array<std::span<double>, 3>{U.c[0].cells, U.c[1].cells, U.c[2].cells});
    for (std::size_t i = 0; i < 3; ++i) set_hole_velocity(i);
  }
  U.update_boundary(mesh_);
}

// The predictor force (pimple.hpp): (H(U) - A U) / V per active component with the equation of
// the last corrector. With U_k = HbyA(U_{k-1}) - D grad(p) this is grad(p) + N (U_{k-1} - U_k) / V:
// the pressure gradient plus the part of H that lagged one corrector behind.
void Pimple::store_predictor_force() {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  auto& h = work_.h;
  h.resize(n);
  for (std::size_t i = 0; i < 3; ++i) {
    auto& force = predictor_force_[i];
    if (!active_[i]) {
      force.clear();
      continue;
    }
    const Matrix& eq = momentum_.eq[i];
    eq.h_operator(mesh_, U.c[i].cells, h);
    if (implicit_overset()) momentum_.extra[i].multiply_add(U.c[i].cells, h, -1.0);
    force.resize(n);
    parallel_for(mesh_.cells(), [&](int c) {
      const auto s = static_cast<std::size_t>(c);
      force[s] = (h[s] - eq.diag[s] * U.c[i].cells[s]) / mesh_.volume(c);
    });
  }
}

// Face flux of the pressure equation with the same explicit part as its source.
void Pimple::pressure_flux(std::span<const double> pc, bool corrected,
                           std::vector<double>& out) const {
  const auto& W = work_;
  const int internal = mesh_.internal_faces();
  parallel_for(mesh_.faces(), [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    const auto P = static_cast<std::size_t>(mesh_.owner(f));
    double pf;
    double correction = 0;
    if (f < internal) {
      out[fs] = internal_pressure_flux(f, pc, corrected);
      return;
    } else {
      const int b = f - internal;
      const auto [ca, cb] = p.value_coeffs(mesh_, b);
      if (p.is_empty(mesh_, b) || ca == 1.0) {
        out[fs] = W.phiHbyA[fs];
        return;
      }
      pf = ca == 0.0 ? cb : ca * pc[P] + cb;  // fixed, or mixed with a value fraction below 1
      if (corrected) correction = mesh_.k(f).dot(W.gp[P]);
    }
    out[fs] = W.phiHbyA[fs] - W.Df[fs] * (mesh_.alpha(f) * (pf - pc[P]) + correction);
  });
  mask_faces(out);  // overset, step 5
}

double Pimple::internal_pressure_flux(int f, std::span<const double> pc, bool corrected) const {
  const auto& W = work_;
  const auto fs = static_cast<std::size_t>(f);
  const auto P = static_cast<std::size_t>(mesh_.owner(f));
  const double pf = pc[static_cast<std::size_t>(mesh_.neighbour(f))];
  const double correction = corrected ? mesh_.k(f).dot(interpolate(mesh_, W.gp, f)) : 0.0;
  return W.phiHbyA[fs] - W.Df[fs] * (mesh_.alpha(f) * (pf - pc[P]) + correction);
}

}  // namespace auvloop::engine::fv
