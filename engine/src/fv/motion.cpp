// SPDX-License-Identifier: GPL-3.0-or-later
// Rigid motion of the grids (motion.hpp states the equations), at the start of initialise() and
// of every step, for the new time level:
//   1. the face moments m_f = sum_t x_t x S_t, once, on the first motion (the mesher's fan of
//      triangles about the face's point average: the closed surface of a cell then has
//      sum m_f = 0 exactly, as sum S_f = 0);
//   2. the grid flux phi_g,f = V_k . S_f + Omega_k . m_f, k the component of the face's owner
//      (zero through empty faces);
//   3. walls: U_b = w_k(x_f) per face;
//   4. far fields: per face q = (stream_k - w_k(x_f)) . S_f; q <= 0 (the stream enters, or runs
//      along the face) fixes U = stream_k with zero-gradient p, q > 0 fixes p = 0 with
//      zero-gradient U (the value fractions of two mixed conditions);
//   5. overset: the hole cells' U = w_k(x_c) (the solid moves with its grid);
//   6. whether any boundary face fixes p (else the reference cell does).
// The momentum equation then convects with phi - phi_g (relative_flux) and takes the rotation of
// the axes, -Omega_k x U, as an explicit source (rotation_source), lagged by an outer iteration.
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/engine/fv/pimple.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

void Pimple::set_motion(std::vector<FrameMotion> motion) {
  const int components = overset_ == nullptr ? 1 : overset_->components();
  if (static_cast<int>(motion.size()) != components)
    throw std::invalid_argument(
        fmt::format("Pimple::set_motion: {} motions for {} grid(s)", motion.size(), components));
  for (std::size_t k = 0; k < motion.size(); ++k) {
    const auto& m = motion[k];
    if (!(m.velocity.allFinite() && m.rate.allFinite() && m.stream.allFinite()))
      throw std::invalid_argument(
          fmt::format("Pimple::set_motion: grid {}: a motion that is not finite", k));
    if (mesh_.periodic() && !m.rate.isZero(0))
      throw std::invalid_argument(
          "Pimple::set_motion: a periodic mesh can translate, not rotate (its coupling is a "
          "translation)");
    for (std::size_t i = 0; i < 3; ++i) {
      if (active_[i]) continue;  // a 2D grid: nothing may move out of its plane
      const auto e = static_cast<Eigen::Index>(i);
      bool in_plane = m.velocity[e] == 0.0 && m.stream[e] == 0.0;
      for (std::size_t j = 0; j < 3; ++j)
        if (j != i) in_plane = in_plane && m.rate[static_cast<Eigen::Index>(j)] == 0.0;
      if (!in_plane)
        throw std::invalid_argument(fmt::format(
            "Pimple::set_motion: grid {} is two-dimensional (no {} direction): its motion must "
            "stay in its plane and turn about its normal",
            k, "xyz"[i]));
    }
  }
  motion_ = std::move(motion);
  if (in_step_) apply_motion();  // the motion_correct hook: for the next outer iteration
}

FrameMotion placed_motion(const FrameMotion& body, const Eigen::Isometry3d& placement,
                          const Eigen::Vector3d& rate, const Eigen::Vector3d& pivot) {
  const Eigen::Matrix3d Rt = placement.linear().transpose();
  const Eigen::Vector3d t = placement.translation();
  FrameMotion m;
  m.velocity = Rt * (body.velocity + body.rate.cross(t) + rate.cross(t - pivot));
  m.rate = Rt * (body.rate + rate);
  m.stream = Rt * body.stream;
  return m;
}

void Pimple::wall(const std::string& patch) {
  const int pi = patch_index(mesh_, patch);
  U.fix(mesh_, patch, {0, 0, 0});
  wall_patches_.push_back(pi);
}

void Pimple::far_field(const std::string& patch) {
  const int pi = patch_index(mesh_, patch);
  for (auto& c : U.c) c.mix(mesh_, patch, 0.0);
  p.mix(mesh_, patch, 0.0);
  far_field_patches_.push_back(pi);
}

void Pimple::apply_motion() {
  // One motion per component: a flow that never called set_motion is at rest in every grid.
  const int components = overset_ == nullptr ? 1 : overset_->components();
  if (static_cast<int>(motion_.size()) != components) {
    for (const auto& m : motion_)
      if (!m.at_rest())
        throw std::invalid_argument(
            fmt::format("Pimple: {} motions set for {} grid(s) (set_overset after set_motion?)",
                        motion_.size(), components));
    motion_.assign(static_cast<std::size_t>(components), FrameMotion{});
  }
  bool at_rest = true;
  for (const auto& m : motion_) at_rest = at_rest && m.at_rest();
  moving_ = moving_ || !at_rest;
  const int internal = mesh_.internal_faces();
  const auto& grid = mesh_.grid();
  if (moving_) {
    if (face_moment_.empty()) {  // 1.
      face_moment_.resize(static_cast<std::size_t>(mesh_.faces()));
      parallel_for(mesh_.faces(), [&](int f) {
        const int n = grid.face_size(f);
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (int k = 0; k < n; ++k)
          mean += grid.points[static_cast<std::size_t>(grid.face_point(f, k))];
        mean /= n;
        Eigen::Vector3d m = Eigen::Vector3d::Zero();
        for (int k = 0; k < n; ++k) {
          const Eigen::Vector3d& a = grid.points[static_cast<std::size_t>(grid.face_point(f, k))];
          const Eigen::Vector3d& b =
              grid.points[static_cast<std::size_t>(grid.face_point(f, (k + 1) % n))];
          const Eigen::Vector3d S = 0.5 * (b - a).cross(mean - a);
          m += ((a + b + mean) / 3).cross(S);
        }
        face_moment_[static_cast<std::size_t>(f)] = m;
      });
    }
    phi_grid_.resize(static_cast<std::size_t>(mesh_.faces()));  // 2.
    parallel_for(mesh_.faces(), [&](int f) {
      const auto fs = static_cast<std::size_t>(f);
      if (f >= internal && U.c[0].is_empty(mesh_, f - internal)) {
        phi_grid_[fs] = 0.0;
        return;
      }
      const auto& m = motion_[static_cast<std::size_t>(component_of_cell(mesh_.owner(f)))];
      phi_grid_[fs] = m.velocity.dot(mesh_.area(f)) + m.rate.dot(face_moment_[fs]);
    });
  }
  for (int pi : wall_patches_) {  // 3.
    const auto& patch = grid.patches[static_cast<std::size_t>(pi)];
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const auto& m = motion_[static_cast<std::size_t>(component_of_cell(mesh_.owner(f)))];
      const Eigen::Vector3d w = m.at(mesh_.face_centre(f));
      for (std::size_t c = 0; c < 3; ++c)
        U.c[c].bcs[static_cast<std::size_t>(pi)].value[static_cast<std::size_t>(i)] =
            active_[c] ? w[static_cast<Eigen::Index>(c)] : 0.0;
    }
  }
  for (int pi : far_field_patches_) {  // 4.
    const auto& patch = grid.patches[static_cast<std::size_t>(pi)];
    const auto ps = static_cast<std::size_t>(pi);
    const auto faces = static_cast<std::size_t>(patch.size);
    for (const auto* bc : {&U.c[0].bcs[ps], &U.c[1].bcs[ps], &U.c[2].bcs[ps], &p.bcs[ps]})
      if (bc->kind != BcKind::mixed || bc->fraction.size() != faces || bc->value.size() != faces)
        throw std::logic_error("Pimple: patch '" + patch.name +
                               "' is a far field, but a condition of U or p on it was changed");
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const auto is = static_cast<std::size_t>(i);
      const auto& m = motion_[static_cast<std::size_t>(component_of_cell(mesh_.owner(f)))];
      const Eigen::Vector3d relative = m.stream - m.at(mesh_.face_centre(f));
      const bool inflow = relative.dot(mesh_.area(f)) <= 0;
      const double fu = inflow ? 1.0 : 0.0;
      for (std::size_t c = 0; c < 3; ++c) {
        auto& bc = U.c[c].bcs[ps];
        bc.value[is] = active_[c] ? m.stream[static_cast<Eigen::Index>(c)] : 0.0;
        bc.fraction[is] = fu;
      }
      p.bcs[ps].value[is] = 0.0;
      p.bcs[ps].fraction[is] = 1.0 - fu;
    }
  }
  if (overset_ != nullptr)  // 5.
    for (std::size_t i = 0; i < 3; ++i) set_hole_velocity(i);
  pressure_fixed_ = false;  // 6.
  for (int b = 0; b < mesh_.boundary_faces(); ++b)
    pressure_fixed_ = pressure_fixed_ || (!p.is_empty(mesh_, b) && p.fixes(mesh_, b));
  U.update_boundary(mesh_);
}

void Pimple::set_hole_velocity(std::size_t i) {
  const auto e = static_cast<Eigen::Index>(i);
  for (int c : overset_->fixed_cells()) {
    if (overset_->status(c) != mesher::CellStatus::hole) continue;
    const auto& m = motion_[static_cast<std::size_t>(component_of_cell(c))];
    U.c[i].cells[static_cast<std::size_t>(c)] = active_[i] ? m.at(mesh_.centre(c))[e] : 0.0;
  }
}

std::span<const double> Pimple::relative_flux() {
  if (phi_grid_.empty()) return phi;
  phi_rel_.resize(phi.size());
  parallel_for(static_cast<int>(phi.size()), [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    phi_rel_[fs] = phi[fs] - phi_grid_[fs];
  });
  mask_faces(phi_rel_);
  return phi_rel_;
}

bool Pimple::rotation_source(std::size_t i, std::vector<double>& out) const {
  bool rotating = false;
  for (const auto& m : motion_) rotating = rotating || !m.rate.isZero(0);
  if (!rotating) return false;
  out.resize(static_cast<std::size_t>(mesh_.cells()));
  const auto e = static_cast<Eigen::Index>(i);
  parallel_for(mesh_.cells(), [&](int c) {
    const auto& m = motion_[static_cast<std::size_t>(component_of_cell(c))];
    out[static_cast<std::size_t>(c)] = -m.rate.cross(U.cell(c))[e];
  });
  return true;
}

}  // namespace auvloop::engine::fv
