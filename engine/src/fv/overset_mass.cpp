// SPDX-License-Identifier: GPL-3.0-or-later
// Overset mass balance (docs/overset-flow.md), the last stage of a pressure corrector in the
// step's last outer iteration on an overset mesh. With the fringe pressures fixed, continuity holds
// in every active cell, so a component whose active cells are closed by walls and fringe (an
// O-grid) passes no net flux to its fringe. A component that also touches a fixed-pressure patch
// (the background with its outlet) is not closed: its fringe ring encloses fluid it does not solve,
// and the flux into the ring is the interpolation's mismatch between the grids (0.3 % of the inflow
// on the coarse Schaefer-Turek pair), mass that leaves the flow. Per such open component k:
//   1. Q_0 = its interface flux with the pressure p_0 just solved (fv::interface_flux);
//   2. once per pressure matrix (an outer iteration: its correctors share the matrix): p_k = the
//      solution of the same equation with k's fringe values shifted by one pascal (first guess
//      p_0 plus the last response), Q_k its interface flux; the response r_k = p_k - p_0 and
//      M_jk = Q_j(p_k) - Q_j(p_0) depend on the matrix only (the flux is affine in p);
//   3. delta = -M^-1 Q_0; p = p_0 + sum_k delta_k r_k and phi from p: every open component's
//      interface flux is zero and every active cell's continuity holds, both to the solver's
//      tolerance. The shift is a pressure offset of the fringe ring against the donor grid, the
//      Lagrange multiplier of the constraint (the ring as one extra cell of the equation).
// Cost: one more pressure solve per open component and step, with the factorisation or the
// hierarchy of the first (same matrix) and a close first guess.
#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "auvloop/engine/fv/pimple.hpp"
#include "diagnosis.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

void Pimple::balance_overset_mass(const Matrix& free, bool corrected, StepReport& r) {
  auto& W = work_;
  const auto K = open_components_.size();
  const auto Ki = static_cast<Eigen::Index>(K);
  const auto n = static_cast<std::size_t>(mesh_.cells());
  const auto q0 = interface_flux(*overset_, mesh_, phi);  // 1.
  Eigen::VectorXd rhs(Ki);
  for (std::size_t k = 0; k < K; ++k)
    rhs[static_cast<Eigen::Index>(k)] = -q0[static_cast<std::size_t>(open_components_[k])];
  // 2. once per pressure matrix (the correctors of an outer iteration share it)
  if (!shift_current_) {
    const auto fixed = overset_->fixed_cells();
    shift_response_.resize(K);
    shift_matrix_.resize(Ki, Ki);
    for (std::size_t k = 0; k < K; ++k) {
      const int comp = open_components_[k];
      W.fixed_shift = fixed_;
      for (std::size_t i = 0; i < fixed.size(); ++i)
        if (overset_->status(fixed[i]) == mesher::CellStatus::fringe &&
            overset_->component_of(fixed[i]) == comp)
          W.fixed_shift[i] += 1.0;
      W.p_shifted = free;
      const auto fringe = overset_->fringe_cells();
      if (implicit_overset()) {  // p_a = sum_k w_k p_k + 1 in k's fringe cells
        W.offsets.resize(fringe.size());
        for (std::size_t j = 0; j < fringe.size(); ++j)
          W.offsets[j] = overset_->component_of(fringe[j]) == comp ? 1.0 : 0.0;
        overset_->couple(W.p_shifted, p.cells, std::numeric_limits<double>::quiet_NaN(), W.offsets,
                         pressure_extra_, W.fixed_shift);
      } else {
        W.p_shifted.fix_values(mesh_, fixed, W.fixed_shift);
      }
      auto& response = shift_response_[k];
      W.p_shift.resize(n);
      parallel_for(mesh_.cells(), [&](int c) {
        const auto s = static_cast<std::size_t>(c);
        W.p_shift[s] = p.cells[s] + (response.empty() ? 0.0 : response[s]);
      });
      const auto stats =
          solve_named(mesh_, W.p_shifted, W.p_shift, "pressure equation (mass balance)", [&] {
            if (implicit_overset())
              return solver_.solve_coupled(W.p_shifted, pressure_extra_, W.p_shift,
                                           settings_.pressure_solver);
            return solver_.solve_symmetric(W.p_shifted, W.p_shift, *settings_.pressure_solver);
          });
      r.pressure_iterations += stats.iterations;
      if (implicit_overset()) {
        overset_->apply(W.p_shift, std::numeric_limits<double>::quiet_NaN());
        for (std::size_t j = 0; j < fringe.size(); ++j)
          W.p_shift[static_cast<std::size_t>(fringe[j])] += W.offsets[j];
      }
      W.phi_shift.resize(phi.size());
      pressure_flux(W.p_shift, corrected, W.phi_shift);
      const auto qk = interface_flux(*overset_, mesh_, W.phi_shift);
      for (std::size_t j = 0; j < K; ++j) {
        const auto cj = static_cast<std::size_t>(open_components_[j]);
        shift_matrix_(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k)) = qk[cj] - q0[cj];
      }
      response.resize(n);
      parallel_for(mesh_.cells(), [&](int c) {
        const auto s = static_cast<std::size_t>(c);
        response[s] = W.p_shift[s] - p.cells[s];
      });
    }
    shift_current_ = true;
  }
  // 3. the shifts; a component whose flux does not answer to its shift (M singular) keeps p_0.
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(shift_matrix_);
  if (!lu.isInvertible()) return;
  const Eigen::VectorXd delta = lu.solve(rhs);
  if (!delta.allFinite()) return;
  parallel_for(mesh_.cells(), [&](int c) {
    const auto s = static_cast<std::size_t>(c);
    for (std::size_t k = 0; k < K; ++k)
      p.cells[s] += delta[static_cast<Eigen::Index>(k)] * shift_response_[k][s];
  });
  pressure_flux(p.cells, corrected, phi);
}

}  // namespace auvloop::engine::fv
