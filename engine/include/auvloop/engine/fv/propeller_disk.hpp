// SPDX-License-Identifier: GPL-3.0-or-later
// The propeller's body-force disk on a finite-volume mesh (issue 18, item 2; the force law is
// engine/propeller.hpp's Hough-Ordway distribution):
//   1. construction: the disk's cells are those whose centre lies in the disk (axial distance
//      at most half the thickness, hub radius <= r <= tip radius) among the candidates (on an
//      overset mesh the active cells of the grid that carries the disk: a fringe or hole cell's
//      force would never reach the flow), in ascending cell order; per disk cell its volume V_c,
//      radius r_c, the axial shape a_c = r* sqrt(1 - r*) and the tangential shape
//      t_c = a_c / r'_c and the swirl direction s_c = n_hat x r_hat_c less the swirl's net
//      side force per unit load, sum V_c t_c s_c / sum V_c t_c (zero where the cells sample the
//      disk symmetrically, as a grid revolved about the axis does; a grid whose cell centres
//      sit on the disk's faces may take one side's cells and not the other's); the sums
//      W_x = sum V_c a_c and W_t = sum V_c t_c ((x_c - centre) x s_c) . n_hat;
//   2. apply(T, Q): each disk cell's force per unit mass, -T a_c / W_x n_hat +
//      sense Q t_c / W_t s_c, so that the fluid receives exactly the force -T n_hat and the
//      torque +sense Q about the axis whatever the grid (the sampled shape renormalised: on a
//      coarse grid the continuous A_x, A_theta of propeller.hpp would miss T by the sampling's
//      error, and the vehicle's reaction would not match what the fluid gets). Not made exact:
//      the moment normal to the axis of a disk sampled asymmetrically;
//   3. disk_speed(U): the volume-weighted mean of n_hat . U over the disk cells (OpenFOAM's
//      propellerDisk; the inflow the advance ratio is taken from, before its own induction is
//      removed by the caller).
// Sums in ascending cell order: the same bits for any number of threads.
#pragma once

#include <span>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "auvloop/engine/fv/field.hpp"
#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/propeller.hpp"

namespace auvloop::engine::fv {

class DiskForce {
 public:
  // candidates: one flag per cell (empty: every cell). Throws std::invalid_argument on a bad
  // disk (propeller.hpp's invariants) or when no candidate cell centre lies in the disk (the
  // disk thinner than the grid's cells there, or not where the grid is).
  DiskForce(const Mesh& mesh, const PropellerDisk& disk, std::span<const char> candidates = {});

  // Step 2: sets the disk cells' entries of body_force (sized to the cells, others untouched)
  // for thrust T (m^4/s^2) and torque Q (m^5/s^2) per unit density.
  void apply(double T, double Q, std::vector<Eigen::Vector3d>& body_force) const;
  // Step 3 (m/s).
  [[nodiscard]] double disk_speed(const VectorField& U) const;

  [[nodiscard]] const std::vector<int>& cells() const { return cells_; }
  [[nodiscard]] double volume() const { return volume_; }  // of the disk cells (m^3)
  [[nodiscard]] const PropellerDisk& disk() const { return disk_; }

 private:
  PropellerDisk disk_;
  std::vector<int> cells_;
  std::vector<double> axial_, tangential_;  // a_c / W_x, t_c / W_t (1/m^3, 1/m^4)
  std::vector<Eigen::Vector3d> swirl_;      // n_hat x r_hat_c
  std::vector<double> cell_volume_;
  double volume_ = 0;
};

}  // namespace auvloop::engine::fv
