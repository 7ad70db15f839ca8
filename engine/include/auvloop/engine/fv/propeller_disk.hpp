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
//      removed by the caller);
//   4. the inflow plane (the paper's way to J; STAR-CCM+'s "inflow velocity plane"): with
//      inflow_offset > 0, the candidate cells whose centre lies within half the disk's thickness
//      of the plane inflow_offset ahead of the disk's centre along n_hat, and within the tip
//      radius of the axis (the hub's radius included: the plane is a whole disk, and cells
//      exist only in the fluid); inflow_speed(U, motion) the volume-weighted mean of
//      n_hat . (w(x_c) - U_c) over them, the speed at which the water meets the propeller, with
//      w the grid velocity of the axes the mesh is at rest in (motion.hpp; zero at rest). With
//      inflow_offset 0 the same mean over the disk cells (the induction then included).
// Sums in ascending cell order: the same bits for any number of threads.
#pragma once

#include <span>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "auvloop/engine/fv/field.hpp"
#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/fv/motion.hpp"
#include "auvloop/engine/propeller.hpp"

namespace auvloop::engine::fv {

class DiskForce {
 public:
  // candidates: one flag per cell (empty: every cell); inflow_offset (m, >= 0) as in step 4.
  // Throws std::invalid_argument on a bad disk (propeller.hpp's invariants), a negative offset,
  // or when no candidate cell centre lies in the disk or on the inflow plane (the disk thinner
  // than the grid's cells there, or not where the grid is).
  DiskForce(const Mesh& mesh, const PropellerDisk& disk, std::span<const char> candidates = {},
            double inflow_offset = 0);

  // Step 2: sets the disk cells' entries of body_force (sized to the cells, others untouched)
  // for thrust T (m^4/s^2) and torque Q (m^5/s^2) per unit density.
  void apply(double T, double Q, std::vector<Eigen::Vector3d>& body_force) const;
  // Step 3 (m/s).
  [[nodiscard]] double disk_speed(const VectorField& U) const;
  // Step 4 (m/s).
  [[nodiscard]] double inflow_speed(const VectorField& U, const FrameMotion& motion = {}) const;
  [[nodiscard]] const std::vector<int>& inflow_cells() const { return inflow_cells_; }
  [[nodiscard]] double inflow_offset() const { return inflow_offset_; }

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
  double inflow_offset_ = 0;
  std::vector<int> inflow_cells_;  // the plane's cells (step 4), the disk's with offset 0
  std::vector<double> inflow_volume_;
  std::vector<Eigen::Vector3d> inflow_centre_;
  double inflow_total_ = 0;
};

}  // namespace auvloop::engine::fv
