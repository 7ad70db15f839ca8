// SPDX-License-Identifier: GPL-3.0-or-later
// The propeller's body-force disk on the mesh: steps 1-3 of fv/propeller_disk.hpp.
#include "auvloop/engine/fv/propeller_disk.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace auvloop::engine::fv {

DiskForce::DiskForce(const Mesh& mesh, const PropellerDisk& disk, std::span<const char> candidates,
                     double inflow_offset)
    : disk_(disk), inflow_offset_(inflow_offset) {
  // The disk's invariants, checked where they are defined (a point at the centre is outside).
  (void)hough_ordway(disk_, 0, 0, disk_.centre);
  if (!candidates.empty() && candidates.size() != static_cast<std::size_t>(mesh.cells()))
    throw std::invalid_argument(fmt::format("propeller disk: {} candidate flags for {} cells",
                                            candidates.size(), mesh.cells()));
  if (!(inflow_offset >= 0) || !std::isfinite(inflow_offset))
    throw std::invalid_argument(fmt::format(
        "propeller disk: the inflow plane's offset must be >= 0 m ahead of the disk, got {}",
        inflow_offset));
  // 1.
  const double RP = disk_.radius, RH = disk_.hub_radius, rh = RH / RP;
  double Wx = 0, Wt = 0;
  for (int c = 0; c < mesh.cells(); ++c) {
    if (!candidates.empty() && candidates[static_cast<std::size_t>(c)] == 0) continue;
    const Eigen::Vector3d d = mesh.centre(c) - disk_.centre;
    const double axial = d.dot(disk_.axis);
    const Eigen::Vector3d radial = d - axial * disk_.axis;
    const double r = radial.norm();
    if (std::abs(axial) > 0.5 * disk_.thickness || r < RH || r > RP || r == 0) continue;
    const double rs = std::min((r / RP - rh) / (1 - rh), 1.0);
    const double a = rs * std::sqrt(1 - rs);
    const double t = a / (r / RP);
    const double V = mesh.volume(c);
    cells_.push_back(c);
    axial_.push_back(a);
    tangential_.push_back(t);
    swirl_.push_back(disk_.axis.cross(radial / r));
    cell_volume_.push_back(V);
    Wx += V * a;
    volume_ += V;
  }
  // The swirl's net side force taken off (a uniform vector, normal to the axis like every
  // swirl_c), then W_t from the corrected directions.
  Eigen::Vector3d side = Eigen::Vector3d::Zero();
  double Vt = 0;
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    side += cell_volume_[k] * tangential_[k] * swirl_[k];
    Vt += cell_volume_[k] * tangential_[k];
  }
  if (Vt > 0)
    for (auto& w : swirl_) w -= side / Vt;
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    const Eigen::Vector3d d = mesh.centre(cells_[k]) - disk_.centre;
    Wt += cell_volume_[k] * tangential_[k] * d.cross(swirl_[k]).dot(disk_.axis);
  }
  if (cells_.empty() || !(Wx > 0) || !(Wt > 0))
    throw std::invalid_argument(fmt::format(
        "propeller disk at ({:.4g}, {:.4g}, {:.4g}) m, radius {:.4g} m, thickness {:.4g} m: {} "
        "cell centres in it carry load (a disk thinner than the cells there, or off the grid)",
        disk_.centre.x(), disk_.centre.y(), disk_.centre.z(), RP, disk_.thickness, cells_.size()));
  for (auto& a : axial_) a /= Wx;
  for (auto& t : tangential_) t /= Wt;
  // 4.
  if (inflow_offset == 0) {
    inflow_cells_ = cells_;
    inflow_volume_ = cell_volume_;
    for (int c : cells_) inflow_centre_.push_back(mesh.centre(c));
  } else {
    const Eigen::Vector3d plane = disk_.centre + inflow_offset * disk_.axis;
    for (int c = 0; c < mesh.cells(); ++c) {
      if (!candidates.empty() && candidates[static_cast<std::size_t>(c)] == 0) continue;
      const Eigen::Vector3d d = mesh.centre(c) - plane;
      const double axial = d.dot(disk_.axis);
      if (std::abs(axial) > 0.5 * disk_.thickness || (d - axial * disk_.axis).norm() > RP) continue;
      inflow_cells_.push_back(c);
      inflow_volume_.push_back(mesh.volume(c));
      inflow_centre_.push_back(mesh.centre(c));
    }
    if (inflow_cells_.empty())
      throw std::invalid_argument(fmt::format(
          "propeller disk: no cell centre lies on its inflow plane {:.4g} m ahead of it, within "
          "{:.4g} m of the plane (half the disk's thickness) and {:.4g} m of the axis",
          inflow_offset, 0.5 * disk_.thickness, RP));
  }
  for (double V : inflow_volume_) inflow_total_ += V;
}

void DiskForce::apply(double T, double Q, std::vector<Eigen::Vector3d>& body_force) const {
  for (std::size_t k = 0; k < cells_.size(); ++k)  // 2.
    body_force[static_cast<std::size_t>(cells_[k])] =
        -T * axial_[k] * disk_.axis + disk_.sense * Q * tangential_[k] * swirl_[k];
}

double DiskForce::disk_speed(const VectorField& U) const {
  double sum = 0;  // 3.
  for (std::size_t k = 0; k < cells_.size(); ++k)
    sum += cell_volume_[k] * U.cell(cells_[k]).dot(disk_.axis);
  return sum / volume_;
}

double DiskForce::inflow_speed(const VectorField& U, const FrameMotion& motion) const {
  double sum = 0;  // 4.
  for (std::size_t k = 0; k < inflow_cells_.size(); ++k)
    sum += inflow_volume_[k] *
           (motion.at(inflow_centre_[k]) - U.cell(inflow_cells_[k])).dot(disk_.axis);
  return sum / inflow_total_;
}

}  // namespace auvloop::engine::fv
