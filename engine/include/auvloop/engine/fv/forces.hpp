// SPDX-License-Identifier: GPL-3.0-or-later
// Force of the fluid on a wall patch, per unit density (the solver's p is kinematic):
//   pressure  sum_f p_f S_f                       (S_f points out of the fluid, into the wall)
//   viscous   sum_f nu (U_P - U_wall) |S_f| / dn  (dn: normal distance of the cell centre)
// The viscous part is the one-sided normal derivative (as OpenFOAM's wall shear stress): exact
// for velocity linear in the wall distance, first order otherwise; p_f is the boundary value.
#pragma once

#include <string>

#include <Eigen/Core>

#include "auvloop/engine/fv/pimple.hpp"

namespace auvloop::engine::fv {

struct PatchForce {
  Eigen::Vector3d pressure = Eigen::Vector3d::Zero();  // m^4/s^2 (times rho: N)
  Eigen::Vector3d viscous = Eigen::Vector3d::Zero();
  [[nodiscard]] Eigen::Vector3d total() const { return pressure + viscous; }
};

PatchForce patch_force(const Pimple& flow, const std::string& patch);

}  // namespace auvloop::engine::fv
