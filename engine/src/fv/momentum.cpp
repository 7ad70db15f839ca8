// SPDX-License-Identifier: GPL-3.0-or-later
// PIMPLE step 2 (docs/cfd.md): the momentum equation per velocity component,
//     ddt(U) + div(phi - phi_g, U) + Omega x U - laplacian(nu, U) == -grad(p),
// (phi_g and Omega of a moving grid, motion.hpp; zero at rest)
// with the face flux phi and the pressure of the previous outer iteration (lagged), deferred
// convection and non-orthogonal corrections from the current U, and Patankar under-relaxation in
// all but the final outer iteration. The predictor solves it with -grad(p) of the previous outer
// iteration, except in a step's first outer iteration: there with the force that balanced the
// previous step's final corrector (grad(p) plus that corrector's splitting residual, pimple.hpp).
#include "auvloop/engine/fv/pimple.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "diagnosis.hpp"
#include "parallel.hpp"
#include "stopwatch.hpp"

namespace auvloop::engine::fv {

void Pimple::assemble_momentum(bool final) {
  const TimeScheme ts = time_scheme();
  // grad U once, for the convection scheme, the non-orthogonal correction and the transpose
  // stress alike (each would otherwise compute it again from the same values); with a model,
  // that of its strain when U has not changed since.
  std::array<std::span<const Eigen::Vector3d>, 3> g;  // empty: not needed
  if (turbulence_) {
    const auto& all = velocity_gradient();
    for (std::size_t i = 0; i < 3; ++i) g[i] = all[i];
    transpose_stress();
  } else if (settings_.convection != Convection::upwind || !mesh_.orthogonal()) {
    for (auto& of : work_.grad_u_of) of.clear();  // only the active components, below
    for (std::size_t i = 0; i < 3; ++i) {
      if (!active_[i]) continue;
      work_.grad_u[i].resize(static_cast<std::size_t>(mesh_.cells()));
      mesh_.gradient(U.c[i].cells, U.c[i].boundary, work_.grad_u[i]);
      g[i] = work_.grad_u[i];
    }
  }
  const auto flux = relative_flux();  // convection relative to the moving grid (motion.hpp)
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    Matrix& eq = momentum_.eq[i];
    // div(nu_eff grad U) implicit and div(nu_eff dev2(grad U^T)) explicit with a turbulence
    // model, else laplacian(nu, U); no time derivative when steady.
    const auto convection = div(mesh_, flux, U.c[i], settings_.convection, g[i]);
    const auto diffusion = turbulence_ ? laplacian(mesh_, turbulence_->nu_eff(), U.c[i], g[i])
                                       : laplacian(mesh_, settings_.nu, U.c[i], g[i]);
    if (settings_.steady) {
      eq = convection - diffusion;
    } else {
      eq = ddt(mesh_, ts, U_old_[0][i], U_old_[1][i]) + convection - diffusion;
    }
    if (turbulence_) eq.add_rhs(mesh_, work_.transpose[i]);
    if (!body_force.empty()) {
      auto& f = work_.rhs;
      f.resize(body_force.size());
      for (std::size_t c = 0; c < f.size(); ++c) f[c] = body_force[c][static_cast<Eigen::Index>(i)];
      eq.add_rhs(mesh_, f);
    }
    if (rotation_source(i, work_.rhs)) eq.add_rhs(mesh_, work_.rhs);  // -Omega x U, motion.hpp
    if (!final && settings_.relax_u < 1) eq.relax(U.c[i].cells, settings_.relax_u);
    // Overset (overset.hpp, step 1): fringe rows the donors' interpolation of U, hole rows their
    // value, the grid velocity (set_hole_velocity).
    if (implicit_overset()) {  // overset_implicit.cpp
      const ScopedSeconds clock(overset_seconds_);
      overset_->couple(eq, {U.c[0].cells, U.c[1].cells, U.c[2].cells}, i, momentum_.extra[i],
                       fixed_);
    } else if (overset_ != nullptr) {
      const ScopedSeconds clock(overset_seconds_);
      overset_->fixed_values({U.c[0].cells, U.c[1].cells, U.c[2].cells}, i, fixed_);
      eq.fix_values(mesh_, overset_->fixed_cells(), fixed_);
    }
  }
}

const std::array<std::vector<Eigen::Vector3d>, 3>& Pimple::velocity_gradient() {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  const auto nb = static_cast<std::size_t>(mesh_.boundary_faces());
  auto& of = work_.grad_u_of;
  const auto same = [&](std::size_t i) {
    const auto& u = U.c[i];
    return of[i].size() == n + nb &&
           std::memcmp(of[i].data(), u.cells.data(), n * sizeof(double)) == 0 &&
           std::memcmp(of[i].data() + n, u.boundary.data(), nb * sizeof(double)) == 0;
  };
  if (same(0) && same(1) && same(2)) return work_.grad_u;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& u = U.c[i];
    work_.grad_u[i].resize(n);
    mesh_.gradient(u.cells, u.boundary, work_.grad_u[i]);
    of[i].resize(n + nb);
    std::copy(u.cells.begin(), u.cells.end(), of[i].begin());
    std::copy(u.boundary.begin(), u.boundary.end(), of[i].begin() + static_cast<std::ptrdiff_t>(n));
  }
  return work_.grad_u;
}

// The explicit part of the effective stress, per unit volume and component j (OpenFOAM's
// divDevReff): (1 / V) sum_f nu_eff,f [sum_i S_f,i (du_i/dx_j)_f - 2/3 (div U)_f S_f,j], with the
// face gradients linearly interpolated from the cell gradients (the owner's on boundary faces:
// those assemble_momentum computed).
// Zero for uniform nu_eff and divergence-free U in the continuum; it carries grad(nu_t) . grad U^T.
void Pimple::transpose_stress() {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  const auto& g = work_.grad_u;  // assemble_momentum's
  const auto nu_eff = turbulence_->nu_eff();
  const int internal = mesh_.internal_faces();
  for (auto& t : work_.transpose) t.resize(n);
  scatter_faces(
      mesh_,
      [&](int b, int e) {
        for (auto& t : work_.transpose)
          for (auto c = static_cast<std::size_t>(b); c < static_cast<std::size_t>(e); ++c) t[c] = 0;
      },
      [&](int f, bool own, bool nei) {
        const auto fs = static_cast<std::size_t>(f);
        const auto P = static_cast<std::size_t>(mesh_.owner(f));
        Eigen::Matrix3d G;  // G(i, j) = du_i/dx_j on the face
        if (f < internal) {
          const auto N = static_cast<std::size_t>(mesh_.neighbour(f));
          const double w = mesh_.weight(f);
          for (std::size_t i = 0; i < 3; ++i)
            G.row(static_cast<Eigen::Index>(i)) = (w * g[i][P] + (1 - w) * g[i][N]).transpose();
        } else {
          if (U.c[0].is_empty(mesh_, f - internal)) return;
          for (std::size_t i = 0; i < 3; ++i)
            G.row(static_cast<Eigen::Index>(i)) = g[i][P].transpose();
        }
        const Eigen::Vector3d& S = mesh_.area(f);
        const Eigen::Vector3d t = nu_eff[fs] * (G.transpose() * S - (2.0 / 3.0) * G.trace() * S);
        for (std::size_t j = 0; j < 3; ++j) {
          const double v = t[static_cast<Eigen::Index>(j)];
          if (own) work_.transpose[j][P] += v;
          if (nei && f < internal)
            work_.transpose[j][static_cast<std::size_t>(mesh_.neighbour(f))] -= v;
        }
      });
  for (auto& t : work_.transpose)
    parallel_for(mesh_.cells(), [&](int c) { t[static_cast<std::size_t>(c)] /= mesh_.volume(c); });
}

void Pimple::solve_momentum(StepReport& r, bool first, bool final) {
  // The first outer iteration of a step applies the force that balanced the last step's final
  // corrector (pimple.hpp, predictor_force_); later ones grad(p) of the previous iteration.
  const bool use_force = first && std::any_of(predictor_force_.begin(), predictor_force_.end(),
                                              [](const auto& f) { return !f.empty(); });
  auto& gp = work_.gp;
  if (!use_force) {
    gp.resize(static_cast<std::size_t>(mesh_.cells()));
    mesh_.gradient(p.cells, p.boundary, gp);
  }
  auto& rhs = work_.rhs;
  rhs.resize(static_cast<std::size_t>(mesh_.cells()));
  r.outer_residual = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    const auto& force = predictor_force_[i];
    const auto e = static_cast<Eigen::Index>(i);
    parallel_for(mesh_.cells(), [&](int c) {
      const auto s = static_cast<std::size_t>(c);
      rhs[s] = overset_ != nullptr && !overset_->active(c) ? 0.0  // fixed rows stay fixed
               : use_force                                 ? -force[s]
                                                           : -gp[s][e];
    });
    // The pressure force joins the source for the solve only: the correctors need the equation
    // without it, so its source is kept aside and swapped back after (bit for bit).
    Matrix& eq = momentum_.eq[i];
    work_.source = eq.source;
    eq.add_rhs(mesh_, rhs);
    const auto s =
        solve_named(mesh_, eq, U.c[i].cells, fmt::format("momentum equation U{}", "xyz"[i]), [&] {
          const double loose = loose_tolerance(final);
          const double tol = loose > 0 ? loose : settings_.momentum_tolerance;  // 0: its own
          if (implicit_overset())
            return solver_.solve_coupled(eq, momentum_.extra[i], U.c[i].cells, std::nullopt, tol);
          return solver_.solve_asymmetric(eq, U.c[i].cells, settings_.momentum_solver, tol);
        });
    eq.source.swap(work_.source);
    r.momentum_iterations += s.iterations;
    if (first) r.momentum_residual = std::max(r.momentum_residual, s.initial_residual);
    r.outer_residual = std::max(r.outer_residual, s.initial_residual);
    U.c[i].update_boundary(mesh_);
  }
  if (implicit_overset()) {  // the fringe cells from their donors (overset_implicit.cpp, 3.)
    const ScopedSeconds clock(overset_seconds_);
    overset_->apply(std::array<std::span<double>, 3>{U.c[0].cells, U.c[1].cells, U.c[2].cells});
    for (std::size_t i = 0; i < 3; ++i)
      if (active_[i]) U.c[i].update_boundary(mesh_);
  }
}

}  // namespace auvloop::engine::fv
