// SPDX-License-Identifier: GPL-3.0-or-later
// PIMPLE step 2 (docs/cfd.md): the momentum equation per velocity component,
//     ddt(U) + div(phi, U) - laplacian(nu, U) == -grad(p),
// with the face flux phi and the pressure of the previous outer iteration (lagged), deferred
// convection and non-orthogonal corrections from the current U, and Patankar under-relaxation in
// all but the final outer iteration. The predictor solves it with -grad(p) of the previous outer
// iteration, except in a step's first outer iteration: there with the force that balanced the
// previous step's final corrector (grad(p) plus that corrector's splitting residual, pimple.hpp).
#include "auvloop/engine/fv/pimple.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "diagnosis.hpp"

namespace auvloop::engine::fv {

Pimple::Momentum Pimple::assemble_momentum(bool final) {
  const TimeScheme ts = time_scheme();
  Momentum m;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    m.eq[i] = ddt(mesh_, ts, U_old_[0][i], U_old_[1][i]) +
              div(mesh_, phi, U.c[i], settings_.convection) -
              laplacian(mesh_, settings_.nu, U.c[i]);
    if (!body_force.empty()) {
      std::vector<double> f(body_force.size());
      for (std::size_t c = 0; c < f.size(); ++c) f[c] = body_force[c][static_cast<Eigen::Index>(i)];
      m.eq[i].add_rhs(mesh_, f);
    }
    if (!final && settings_.relax_u < 1) m.eq[i].relax(U.c[i].cells, settings_.relax_u);
  }
  return m;
}

void Pimple::solve_momentum(Momentum& m, StepReport& r, bool first) {
  // The first outer iteration of a step applies the force that balanced the last step's final
  // corrector (pimple.hpp, predictor_force_); later ones grad(p) of the previous iteration.
  const bool use_force = first && std::any_of(predictor_force_.begin(), predictor_force_.end(),
                                              [](const auto& f) { return !f.empty(); });
  std::vector<Eigen::Vector3d> gp;
  if (!use_force) gp = grad(mesh_, p);
  std::vector<double> rhs(static_cast<std::size_t>(mesh_.cells()));
  r.outer_residual = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    const auto& force = predictor_force_[i];
    for (std::size_t c = 0; c < rhs.size(); ++c)
      rhs[c] = use_force ? -force[c] : -gp[c][static_cast<Eigen::Index>(i)];
    Matrix eq = m.eq[i];
    eq.add_rhs(mesh_, rhs);
    const auto s =
        solve_named(mesh_, eq, U.c[i].cells, fmt::format("momentum equation U{}", "xyz"[i]), [&] {
          return solver_.solve_asymmetric(eq, U.c[i].cells, AsymmetricMethod::bicgstab_jacobi);
        });
    if (first) r.momentum_residual = std::max(r.momentum_residual, s.initial_residual);
    r.outer_residual = std::max(r.outer_residual, s.initial_residual);
    U.c[i].update_boundary(mesh_);
  }
}

}  // namespace auvloop::engine::fv
