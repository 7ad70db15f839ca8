// SPDX-License-Identifier: GPL-3.0-or-later
// Implicit overset coupling (overset.hpp; docs/overset-flow.md): the interpolation joins the
// linear system instead of being applied between solves, by elimination of the fringe values.
//   1. a fringe cell a of component h takes phi_a = sum_k w_k phi_{d_k} + o_a, the donors'
//      values unknowns of the same solve. For component i of a vector whose donors lie in a
//      component g with turned axes, phi_a = sum_k w_k (R_hg u_{d_k})_i: the unknown part is
//      w_k (R_hg)_ii u_{d_k, i}, and the donors' other components, o_a = sum_k w_k
//      sum_{j != i} (R_hg)_ij u_{d_k, j}, are taken at their current values (lagged, as the
//      segregated components are); o_a = 0 for a scalar (the mass balance's shift: 1);
//   2. an active cell r with a fringe face neighbour a: its coefficient a_ra of phi_a becomes
//      a_ra w_k (R_hg)_ii on each donor d_k (entries beyond the face pattern, equal donors of
//      several neighbours summed), and -a_ra o_a joins its source (Matrix::fix_values with the
//      fringe value o_a zeroes the face coefficient and moves it there);
//   3. fringe and hole rows are fixed rows, decoupled (a hole its value, a fringe cell its
//      current value: no residual); after the solve the fringe cells take phi_a from their
//      donors (Overset::apply, + o_a).
// The system left is the active cells' alone: no constraint rows, each active row's
// off-diagonal sum unchanged by the elimination (the weights sum to one), so the smoothers and
// the multigrid's pairing see a matrix like a single grid's, with entries reaching into the
// other grids (LinearSolver::solve_coupled: FGMRES with the multigrid of the whole system).
// It is not symmetric. H(U) of an active row must add its entries of step 2 (pressure.cpp).
#include <algorithm>
#include <limits>

#include "auvloop/engine/fv/overset.hpp"

namespace auvloop::engine::fv {

using mesher::CellStatus;

void Overset::list_coupled_rows() {
  const auto& mesh = mesh_;
  std::vector<int> rows;
  for (int a : fringe_)
    for (int f : mesh.cell_faces(a)) {
      if (f >= mesh.internal_faces()) continue;
      const int other = mesh.owner(f) == a ? mesh.neighbour(f) : mesh.owner(f);
      if (active(other)) rows.push_back(other);
    }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  active_rows_ = std::move(rows);
  coupled_start_.assign(1, 0);
  coupled_faces_.clear();
  for (int r : active_rows_) {
    for (int f : mesh.cell_faces(r)) {
      if (f >= mesh.internal_faces()) continue;
      const int other = mesh.owner(f) == r ? mesh.neighbour(f) : mesh.owner(f);
      if (status(other) == CellStatus::fringe) coupled_faces_.push_back(f);
    }
    coupled_start_.push_back(static_cast<int>(coupled_faces_.size()));
  }
  fringe_slot_.resize(fringe_.size());
  std::size_t j = 0;
  for (std::size_t k = 0; k < fixed_.size(); ++k)
    if (status(fixed_[k]) == CellStatus::fringe) fringe_slot_[j++] = static_cast<int>(k);
}

void Overset::implicit_entries(const Matrix& eq, int i, ExtraEntries& extra) const {
  const auto& mesh = mesh_;
  extra.clear();
  std::vector<std::pair<int, double>> row;  // (donor, coefficient), merged per donor
  for (std::size_t k = 0; k < active_rows_.size(); ++k) {
    const int r = active_rows_[k];
    row.clear();
    for (int e = coupled_start_[k]; e < coupled_start_[k + 1]; ++e) {
      const int f = coupled_faces_[static_cast<std::size_t>(e)];
      const auto fu = static_cast<std::size_t>(f);
      const bool owner = mesh.owner(f) == r;
      const int a = owner ? mesh.neighbour(f) : mesh.owner(f);
      const double c = owner ? eq.upper[fu] : eq.lower[fu];  // r's coefficient of a
      const auto au = static_cast<std::size_t>(a);
      const int h = component_of(a);
      for (int s = stencils_.offsets[au]; s < stencils_.offsets[au + 1]; ++s) {
        const auto su = static_cast<std::size_t>(s);
        const int d = stencils_.donors[su];
        const int g = component_of(d);
        const double turn = i < 0 || g == h ? 1.0 : rotation(h, g)(static_cast<Eigen::Index>(i), i);
        row.emplace_back(d, c * stencils_.weights[su] * turn);
      }
    }
    std::stable_sort(row.begin(), row.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    extra.begin_row(r);
    for (std::size_t j = 0; j < row.size();) {  // equal donors summed in a fixed order
      double v = 0;
      const int d = row[j].first;
      for (; j < row.size() && row[j].first == d; ++j) v += row[j].second;
      extra.add(d, v);
    }
    extra.end_row();
  }
}

void Overset::couple(Matrix& eq, std::span<const double> field, double hole,
                     std::span<const double> offsets, ExtraEntries& extra,
                     std::vector<double>& values) const {
  implicit_entries(eq, -1, extra);
  fixed_values(field, hole, values);
  for (std::size_t j = 0; j < fringe_slot_.size(); ++j)
    values[static_cast<std::size_t>(fringe_slot_[j])] = offsets.empty() ? 0.0 : offsets[j];
  eq.fix_values(mesh_, fixed_, values);  // 3. (and the offsets into the active rows' sources)
  hold_fringe_rows(eq, field);
}

// A fringe row, decoupled, returns whatever its source says; the current value makes its
// residual zero, so that the solve's residuals are the active rows' (apply() sets it after).
void Overset::hold_fringe_rows(Matrix& eq, std::span<const double> field) const {
  for (int a : fringe_) {
    const auto au = static_cast<std::size_t>(a);
    eq.source[au] = eq.diag[au] * field[au];
  }
}

void Overset::couple(Matrix& eq, const Vector& u, std::size_t i, ExtraEntries& extra,
                     std::vector<double>& values) const {
  implicit_entries(eq, static_cast<int>(i), extra);
  fixed_values(u[i], std::numeric_limits<double>::quiet_NaN(), values);
  const auto e = static_cast<Eigen::Index>(i);
  for (std::size_t j = 0; j < fringe_.size(); ++j) {  // 1., the donors' other components
    const int a = fringe_[j];
    const auto au = static_cast<std::size_t>(a);
    const int h = component_of(a);
    double cross = 0;
    for (int s = stencils_.offsets[au]; turned_ && s < stencils_.offsets[au + 1]; ++s) {
      const auto su = static_cast<std::size_t>(s);
      const int d = stencils_.donors[su];
      const int g = component_of(d);
      if (g == h) continue;
      const auto du = static_cast<std::size_t>(d);
      const Eigen::Vector3d ud(u[0][du], u[1][du], u[2][du]);
      cross +=
          stencils_.weights[su] * (rotation(h, g).row(e).dot(ud) - rotation(h, g)(e, e) * ud[e]);
    }
    values[static_cast<std::size_t>(fringe_slot_[j])] = cross;
  }
  eq.fix_values(mesh_, fixed_, values);
  hold_fringe_rows(eq, u[i]);
}

}  // namespace auvloop::engine::fv
