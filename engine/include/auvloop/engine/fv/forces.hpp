// SPDX-License-Identifier: GPL-3.0-or-later
// Force and moment of the fluid on wall patches, per unit density (the solver's p is kinematic):
//   pressure  dF_f = p_f S_f                         (S_f points out of the fluid, into the wall)
//   viscous   dF_f = nu_f [(U_P - U_wall) |S_f| / dn - (grad U)_P^T . S_f]
//                                                    (dn: normal distance of the cell centre;
//                                                    nu_f the turbulence model's nu_eff of the
//                                                    face, nu + nu_t,w: the law of the wall's
//                                                    shear at any y+; nu when laminar)
//   moment    M = sum_f (x_f - x_ref) x dF_f         about a reference point x_ref
// The viscous part is -nu (grad U + grad U^T) . S with the normal derivative one-sided (as
// OpenFOAM's wallShearStress): exact for velocity linear in the wall distance, first order
// otherwise. The transposed part vanishes on a wall at rest (U = 0 along it, and du_n/dn = 0 by
// continuity) but not on a rotating one (Taylor-Couette: without it the torque is 5/8 of the
// exact value for R2 = 2 R1). p_f is the boundary value.
// On an overset mesh the wall faces whose cell is a hole are not in the flow (a wall inside
// another grid's body) and are left out. Every other wall face counts once: in the systems
// auvloop builds each wall surface belongs to one grid and every wall face to an active cell (a
// fin stands a gap off the hull, its root a wall of its own grid: test_fv_vehicle_overset); a
// surface covered by the walls of two grids (a collar grid) would be counted twice.
// Multiply by the density for newtons and newton-metres.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "auvloop/engine/fv/pimple.hpp"

namespace auvloop::engine::fv {

struct PatchForce {
  Eigen::Vector3d pressure = Eigen::Vector3d::Zero();  // m^4/s^2 (times rho: N)
  Eigen::Vector3d viscous = Eigen::Vector3d::Zero();
  Eigen::Vector3d pressure_moment = Eigen::Vector3d::Zero();  // m^5/s^2 (times rho: N m)
  Eigen::Vector3d viscous_moment = Eigen::Vector3d::Zero();
  [[nodiscard]] Eigen::Vector3d total() const { return pressure + viscous; }
  [[nodiscard]] Eigen::Vector3d total_moment() const { return pressure_moment + viscous_moment; }
  PatchForce& operator+=(const PatchForce& o);
};

// Per face of one patch (by name, as patch_force), in face order: its pressure and viscous force
// (m^4/s^2) and whether it counts (false: its cell is an overset hole; both forces zero).
struct FaceForces {
  int start = 0;  // the patch's first face
  std::vector<Eigen::Vector3d> pressure, viscous;
  std::vector<char> counted;
};
FaceForces face_forces(const Pimple& flow, const std::string& patch);

// One patch (by name; throws std::invalid_argument naming the grid's patches if unknown): the
// sums of face_forces in face order.
PatchForce patch_force(const Pimple& flow, const std::string& patch,
                       const Eigen::Vector3d& moment_point = Eigen::Vector3d::Zero());

// Every wall patch of the grid with its force and moment, in patch order.
std::vector<std::pair<std::string, PatchForce>> wall_forces(
    const Pimple& flow, const Eigen::Vector3d& moment_point = Eigen::Vector3d::Zero());
// Their sum.
PatchForce total_wall_force(const Pimple& flow,
                            const Eigen::Vector3d& moment_point = Eigen::Vector3d::Zero());

}  // namespace auvloop::engine::fv
