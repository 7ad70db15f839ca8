// SPDX-License-Identifier: GPL-3.0-or-later
// Overset re-assembly (pimple.hpp, follow_assembly): when the grids moved and the driver passed a
// new assembly to the Overset, the first stage of the next step carries the fields over to the
// new statuses. Nothing happens when no status changed. With `was` the statuses of the last
// step and `is` the new ones:
//   1. cells that came out of a hole (was hole, is fringe or active) hold no flow: U, the old
//      level of U that the step keeps (U_old_[0]: the BDF2 level n-1 once the step shifts the
//      levels) and p become the mean of their face neighbours that hold one (not a hole
//      before, or filled in an earlier sweep), sweep by sweep outward from the flow, as
//      OpenFOAM's overset does for such cells; a cell no sweep reaches keeps its hole values
//      (U the grid velocity); a turbulence model's transported fields and their old levels
//      (TurbulenceModel::carried) are carried with U in steps 1 and 2;
//   2. of those, the fringe cells take their donors' interpolations of U, its old level and p
//      (the donors' old level at the new placement: displaced by one step's motion, closer than
//      a neighbour mean); every other fringe cell keeps the values of the last step, the flow
//      at its place at time level n, which the step keeps as its old level;
//   3. faces that came alive (were masked, are live) take the face flux of U, and for the
//      Rhie-Chow time correction the old flux of the old level, so that their old flux and old
//      velocity agree; faces that died carry no flux from now on;
//   4. cells that became active start their predictor force from grad(p) (a fixed row left
//      none), as every cell does on the first step;
//   5. the open components (overset_mass.cpp) and the reference cell from the new statuses.
// Returns the number of cells whose status changed and of those that came out of a hole.
// The old time levels of BDF2 in the cells that keep their status are untouched: every
// component's cells are at rest in its own axes, so their history stays the same cell's.

#include "auvloop/engine/fv/pimple.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

using mesher::CellStatus;

namespace {
constexpr int fill_sweeps = 8;  // cells beyond this many layers from the flow keep hole values
}

void Pimple::snapshot_status() {
  status_.clear();
  if (overset_ == nullptr) return;
  status_.resize(static_cast<std::size_t>(mesh_.cells()));
  for (int c = 0; c < mesh_.cells(); ++c)
    status_[static_cast<std::size_t>(c)] = overset_->status(c);
}

void Pimple::find_open_components() {
  open_components_.clear();
  shift_response_.clear();
  if (overset_ == nullptr) return;
  std::vector<char> open(static_cast<std::size_t>(overset_->components()), 0);
  for (int b = 0; b < mesh_.boundary_faces(); ++b) {
    const int c = mesh_.owner(mesh_.internal_faces() + b);
    const auto kind = p.bcs[static_cast<std::size_t>(mesh_.patch_of(b))].kind;
    if ((kind == BcKind::fixed_value || kind == BcKind::mixed) && overset_->active(c))
      open[static_cast<std::size_t>(overset_->component_of(c))] = 1;
  }
  std::vector<char> fringe(open.size(), 0);
  for (int c : overset_->fringe_cells())
    fringe[static_cast<std::size_t>(overset_->component_of(c))] = 1;
  for (std::size_t k = 0; k < open.size(); ++k)
    if (open[k] != 0 && fringe[k] != 0) open_components_.push_back(static_cast<int>(k));
  find_ring_faces();
}

void Pimple::find_reference_cell() {
  if (overset_ == nullptr || overset_->active_cells().empty()) {
    reference_cell_ = 0;
  } else if (!overset_->active(reference_cell_)) {
    reference_cell_ = overset_->active_cells().front();
  }
}

std::pair<int, int> Pimple::follow_assembly() {
  if (overset_ == nullptr || status_.empty()) return {0, 0};
  const auto n = static_cast<std::size_t>(mesh_.cells());
  int changed = 0;
  for (std::size_t c = 0; c < n; ++c)
    changed += status_[c] != overset_->status(static_cast<int>(c));
  if (changed == 0) return {0, 0};
  // 1. fill the cells that came out of a hole, sweep by sweep
  auto& pending = work_.pending;
  auto& holds = work_.holds;
  pending.clear();
  holds.assign(n, 0);
  for (std::size_t c = 0; c < n; ++c) {
    const bool was_hole = status_[c] == CellStatus::hole;
    holds[c] = was_hole ? 0 : 1;
    if (was_hole && overset_->status(static_cast<int>(c)) != CellStatus::hole)
      pending.push_back(static_cast<int>(c));
  }
  const auto uncovered = static_cast<int>(pending.size());
  // U_old_[1] is not among them: the step's shift of the levels drops it. A turbulence model's
  // transported fields and their old levels likewise (turbulence_model.hpp, hook 9).
  auto& levels = work_.levels;
  levels = {&U.c[0].cells, &U.c[1].cells, &U.c[2].cells, &U_old_[0][0],
            &U_old_[0][1], &U_old_[0][2], &p.cells};
  auto& carried = work_.carried;
  carried.clear();
  if (turbulence_ != nullptr) turbulence_->carried(carried);
  for (const auto& field : carried) {
    levels.push_back(field.cells);
    levels.push_back(field.old);
  }
  const int internal = mesh_.internal_faces();
  auto& filled = work_.filled;
  auto& rest = work_.rest;
  auto& mean = work_.mean;
  mean.resize(levels.size());
  for (int sweep = 0; sweep < fill_sweeps && !pending.empty(); ++sweep) {
    filled.clear();
    rest.clear();
    for (int c : pending) {
      std::fill(mean.begin(), mean.end(), 0.0);
      int count = 0;
      for (int f : mesh_.cell_faces(c)) {
        if (f >= internal) continue;
        const int o = mesh_.owner(f) == c ? mesh_.neighbour(f) : mesh_.owner(f);
        const auto os = static_cast<std::size_t>(o);
        if (holds[os] == 0) continue;
        for (std::size_t l = 0; l < levels.size(); ++l) mean[l] += (*levels[l])[os];
        ++count;
      }
      if (count == 0) {
        rest.push_back(c);
        continue;
      }
      // Values written after the sweep: a cell filled in this sweep feeds the next one only.
      filled.push_back(c);
      for (std::size_t l = 0; l < levels.size(); ++l) mean[l] /= count;
      work_.fill.insert(work_.fill.end(), mean.begin(), mean.end());
    }
    for (std::size_t j = 0; j < filled.size(); ++j) {
      const auto cs = static_cast<std::size_t>(filled[j]);
      for (std::size_t l = 0; l < levels.size(); ++l)
        (*levels[l])[cs] = work_.fill[j * levels.size() + l];
      holds[cs] = 1;
    }
    work_.fill.clear();
    pending.swap(rest);
  }
  // 2. the fringe cells out of a hole from their donors; the other fringe cells keep their
  //    values, which are the interpolations at the last step's placement: the flow at the
  //    cell at time level n, which the step keeps as its old level (re-interpolating them at
  //    the new placement would turn the old level into the donors' flow displaced by a step)
  for (std::size_t c = 0; c < n; ++c) {
    const int ci = static_cast<int>(c);
    if (status_[c] != CellStatus::hole || overset_->status(ci) != CellStatus::fringe) continue;
    const Eigen::Vector3d u = overset_->interpolate({U.c[0].cells, U.c[1].cells, U.c[2].cells}, ci);
    const Eigen::Vector3d u_old =
        overset_->interpolate({U_old_[0][0], U_old_[0][1], U_old_[0][2]}, ci);
    for (std::size_t i = 0; i < 3; ++i) {
      U.c[i].cells[c] = u[static_cast<Eigen::Index>(i)];
      U_old_[0][i][c] = u_old[static_cast<Eigen::Index>(i)];
    }
    p.cells[c] = overset_->interpolate(p.cells, ci);
    for (const auto& field : carried) {
      (*field.cells)[c] = overset_->interpolate(*field.cells, ci, Overset::Bound::donors);
      (*field.old)[c] = overset_->interpolate(*field.old, ci, Overset::Bound::donors);
    }
  }
  U.update_boundary(mesh_);
  p.update_boundary(mesh_);
  // 3. the faces that came alive: the flux of U, the old flux of the old level
  auto& born = work_.born;
  born.clear();
  for (int f = 0; f < mesh_.faces(); ++f) {
    const bool was = status_[static_cast<std::size_t>(mesh_.owner(f))] == CellStatus::active ||
                     (f < internal &&
                      status_[static_cast<std::size_t>(mesh_.neighbour(f))] == CellStatus::active);
    if (!was && overset_->live(f)) born.push_back(f);
  }
  if (!born.empty()) {
    std::array<std::vector<double>, 3> u{U.c[0].cells, U.c[1].cells, U.c[2].cells};
    auto& flux = work_.h;
    face_flux(u, flux);
    for (int f : born) {
      const auto fs = static_cast<std::size_t>(f);
      phi[fs] = f < internal ? flux[fs] : U.face(f - internal).dot(mesh_.area(f));
    }
    face_flux(U_old_[0], flux);
    for (int f : born) {
      const auto fs = static_cast<std::size_t>(f);
      phi_old_[0][fs] = f < internal ? flux[fs] : phi[fs];
    }
  }
  mask_faces(phi);
  // 4. the predictor force of the cells that became active
  if (!predictor_force_[0].empty() || !predictor_force_[1].empty() ||
      !predictor_force_[2].empty()) {
    auto& gp = work_.gp;
    gp.resize(n);
    mesh_.gradient(p.cells, p.boundary, gp);
    for (std::size_t c = 0; c < n; ++c) {
      if (status_[c] == CellStatus::active || !overset_->active(static_cast<int>(c))) continue;
      for (std::size_t i = 0; i < 3; ++i)
        if (!predictor_force_[i].empty())
          predictor_force_[i][c] = gp[c][static_cast<Eigen::Index>(i)];
    }
  }
  find_open_components();  // 5.
  find_reference_cell();
  snapshot_status();
  return {changed, uncovered};
}

}  // namespace auvloop::engine::fv
