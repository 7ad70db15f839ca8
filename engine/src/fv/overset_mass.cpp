// SPDX-License-Identifier: GPL-3.0-or-later
// Overset mass balance (docs/overset-flow.md), the last stage of a pressure corrector on an
// overset mesh. With the fringe pressures fixed, continuity holds in every active cell, so a
// component whose active cells are closed by walls and fringe (an O-grid) passes no net flux to
// its fringe. A component that also touches a fixed-pressure patch (the background with its
// outlet) is not closed: its fringe ring encloses fluid it does not solve, and the flux into the
// ring is the interpolation's mismatch between the grids (0.3 % of the inflow on the coarse
// Schaefer-Turek pair), mass that leaves the flow. Per such open component k (the response form):
//   1. Q_0 = its interface flux with the pressure p_0 just solved (fv::interface_flux);
//   2. once per pressure matrix (an outer iteration: its correctors share the matrix): the
//      response r_k to k's fringe values shifted by one pascal, solved from the right side the
//      shift adds (first guess the last response; with the implicit coupling, the difference of
//      the shifted equation's solution and p_0), and M_jk = Q_j(p_0 + r_k) - Q_j(p_0); both
//      depend on the matrix only (the flux is affine in p);
//   3. delta = -M^-1 Q_0; p = p_0 + sum_k delta_k r_k and phi from p: every open component's
//      interface flux is zero and every active cell's continuity holds, both to the solver's
//      tolerance. The shift is a pressure offset of the fringe ring against the donor grid, the
//      Lagrange multiplier of the constraint (the ring as one extra cell of the equation).
// Cost: one more pressure solve per open component and outer iteration, with the factorisation
// or the hierarchy of the first (same matrix) and a close first guess.
//
// Bordered (cg-amg with the explicit coupling, where that solve costs as much as the pressure
// solve itself): the shift delta_k is the Lagrange multiplier, so it is solved for with p. With
// the fringe values p_j = p_fix,j + lambda_k in component k's fringe ring, the interface flux
// Q_k = Q_k(p_active = 0, lambda = 0) + sum_f a_f (p_i - lambda_k) over the faces f between an
// active cell i and the ring, where a_f is the pressure matrix's coefficient of that face (the
// flux is phiHbyA - D_f (grad p)_f . S, whose p_j coefficient is the matrix's: continuity of
// every active cell is its row). Q_k = 0 is then one more row of the Laplacian: the ring as one
// cell, off-diagonals a_f to the active cells beside it, diagonal -sum_f a_f. The bordered
// matrix stays symmetric and negative definite; LinearSolver::solve_bordered solves it by cg-amg
// with the ring as a row of its own on every level of the multigrid (105-109 iterations a step
// against 91 for the plain solve on the REMUS coarse system):
//   B1. column k: per active cell i beside the ring of k, the sum of its rows' a_f to the ring;
//       diag_k = -sum a_f; rhs_k = -Q_k of the probe pressure (the fixed values in the fixed
//       cells, zero elsewhere), from the flux of the probe (fv::interface_flux);
//   B2. solve for p and lambda; the fringe cells of k shifted by lambda_k.
// Both forms give the same p to the solver's tolerance (test_fv_overset).
#include <algorithm>
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
      const auto in_ring = [&](int cell) {
        return overset_->status(cell) == mesher::CellStatus::fringe &&
               overset_->component_of(cell) == comp;
      };
      auto& response = shift_response_[k];
      W.p_shifted = free;
      const auto fringe = overset_->fringe_cells();
      W.p_shift.resize(n);
      // The explicit coupling solves for the response itself: the right side that a unit shift
      // adds (fix_values is linear in the source and the values together, so the matrix with no
      // source and the shift as its fixed values gives it), from the last response. Solved as
      // the difference of two full solutions, its error would scale with the step's own right
      // side, and an impulsive start's shift (the ring then acts as an outlet) multiplies it:
      // continuity 4e-8 against 1e-11 (schaefer-turek-2d2-overset, its first steps).
      if (implicit_overset()) {  // p_a = sum_k w_k p_k + 1 in k's fringe cells
        W.fixed_shift = fixed_;
        for (std::size_t i = 0; i < fixed.size(); ++i)
          if (in_ring(fixed[i])) W.fixed_shift[i] += 1.0;
        W.offsets.resize(fringe.size());
        for (std::size_t j = 0; j < fringe.size(); ++j)
          W.offsets[j] = overset_->component_of(fringe[j]) == comp ? 1.0 : 0.0;
        overset_->couple(W.p_shifted, p.cells, std::numeric_limits<double>::quiet_NaN(), W.offsets,
                         pressure_extra_, W.fixed_shift);
        parallel_for(mesh_.cells(), [&](int c) {
          const auto s = static_cast<std::size_t>(c);
          W.p_shift[s] = p.cells[s] + (response.empty() ? 0.0 : response[s]);
        });
      } else {
        W.fixed_shift.assign(fixed.size(), 0.0);
        for (std::size_t i = 0; i < fixed.size(); ++i)
          if (in_ring(fixed[i])) W.fixed_shift[i] = 1.0;
        std::fill(W.p_shifted.source.begin(), W.p_shifted.source.end(), 0.0);
        W.p_shifted.fix_values(mesh_, fixed, W.fixed_shift);
        if (response.empty()) {
          std::fill(W.p_shift.begin(), W.p_shift.end(), 0.0);
        } else {
          std::copy(response.begin(), response.end(), W.p_shift.begin());
        }
      }
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
        response.resize(n);
        parallel_for(mesh_.cells(), [&](int c) {
          const auto s = static_cast<std::size_t>(c);
          response[s] = W.p_shift[s] - p.cells[s];
        });
      } else {  // the response itself: p_0 plus it for the flux
        response.assign(W.p_shift.begin(), W.p_shift.end());
        parallel_for(mesh_.cells(), [&](int c) {
          const auto s = static_cast<std::size_t>(c);
          W.p_shift[s] += p.cells[s];
        });
      }
      W.phi_shift.resize(phi.size());
      pressure_flux(W.p_shift, corrected, W.phi_shift);
      const auto qk = interface_flux(*overset_, mesh_, W.phi_shift);
      for (std::size_t j = 0; j < K; ++j) {
        const auto cj = static_cast<std::size_t>(open_components_[j]);
        shift_matrix_(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k)) = qk[cj] - q0[cj];
      }
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

int Pimple::open_index(int component) const {
  const auto it = std::find(open_components_.begin(), open_components_.end(), component);
  return it == open_components_.end() ? -1 : static_cast<int>(it - open_components_.begin());
}

// B1.
void Pimple::border_overset_mass(const Matrix& free, bool corrected, Border& border) {
  auto& W = work_;
  const auto K = open_components_.size();
  border.columns.resize(K);
  for (auto& column : border.columns) {
    column.rows.clear();
    column.values.clear();
    column.diag = 0;
  }
  const int internal = mesh_.internal_faces();
  // (row, a_f) per face between an active cell and an open component's fringe cell, by fringe
  // cell and face: a deterministic order, sorted by row below.
  auto& entries = W.border_entries;
  auto& ring_faces = W.ring_faces;  // (face, its active cell)
  entries.resize(K);
  ring_faces.resize(K);
  for (std::size_t k = 0; k < K; ++k) {
    entries[k].clear();
    ring_faces[k].clear();
  }
  int last_comp = -1, last_column = -1;
  for (int c : overset_->fringe_cells()) {
    const int comp = overset_->component_of(c);
    if (comp != last_comp) {
      last_comp = comp;
      last_column = open_index(comp);
    }
    if (last_column < 0) continue;
    for (int f : mesh_.cell_faces(c)) {
      if (f >= internal) continue;
      const bool owner = mesh_.owner(f) == c;
      const int i = owner ? mesh_.neighbour(f) : mesh_.owner(f);
      if (!overset_->active(i)) continue;
      // row i's coefficient of column c: upper when i owns the face
      const double a =
          owner ? free.lower[static_cast<std::size_t>(f)] : free.upper[static_cast<std::size_t>(f)];
      entries[static_cast<std::size_t>(last_column)].emplace_back(i, a);
      ring_faces[static_cast<std::size_t>(last_column)].emplace_back(f, i);
    }
  }
  for (std::size_t k = 0; k < K; ++k) {
    auto& e = entries[k];
    std::stable_sort(e.begin(), e.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    auto& column = border.columns[k];
    for (const auto& [row, a] : e) {
      if (column.rows.empty() || column.rows.back() != row) {
        column.rows.push_back(row);
        column.values.push_back(0.0);
      }
      column.values.back() += a;
      column.diag -= a;
    }
  }
  // rhs_k = -Q_k(probe): the probe's flux on the ring's faces only (those between an active cell
  // and the fringe of an open component; fringe layers keep holes from active cells), summed in
  // face order as fv::interface_flux sums a whole field's.
  const auto n = static_cast<std::size_t>(mesh_.cells());
  if (W.probe.size() != n) W.probe.assign(n, 0.0);
  const auto fixed = overset_->fixed_cells();
  for (std::size_t i = 0; i < fixed.size(); ++i)
    W.probe[static_cast<std::size_t>(fixed[i])] = fixed_[i];
  for (std::size_t k = 0; k < K; ++k) {
    auto& faces = W.probe_flux;
    faces.clear();
    for (const auto& [f, i] : ring_faces[k]) {
      const double flux = overset_->live(f) ? internal_pressure_flux(f, W.probe, corrected) : 0.0;
      faces.emplace_back(f, mesh_.owner(f) == i ? flux : -flux);
    }
    std::sort(faces.begin(), faces.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    double q = 0;
    for (const auto& [f, out] : faces) q += out;
    border.columns[k].rhs = -q;
  }
  for (int c : fixed) W.probe[static_cast<std::size_t>(c)] = 0.0;  // zero again for the next call
}

// B2. (after the solve)
void Pimple::shift_fringe(std::span<const double> lambda) {
  int last_comp = -1;
  double shift = 0;
  for (int c : overset_->fringe_cells()) {
    const int comp = overset_->component_of(c);
    if (comp != last_comp) {
      last_comp = comp;
      const int k = open_index(comp);
      shift = k < 0 ? 0.0 : lambda[static_cast<std::size_t>(k)];
    }
    p.cells[static_cast<std::size_t>(c)] += shift;
  }
}

}  // namespace auvloop::engine::fv
