// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/forces.hpp"

namespace auvloop::engine::fv {

PatchForce patch_force(const Pimple& flow, const std::string& patch) {
  const Mesh& mesh = flow.mesh();
  const auto& p = mesh.grid().patches[static_cast<std::size_t>(patch_index(mesh, patch))];
  PatchForce force;
  for (int i = 0; i < p.size; ++i) {
    const int f = p.start + i;
    const int b = f - mesh.internal_faces();
    const Eigen::Vector3d& S = mesh.area(f);
    const double dn = S.dot(mesh.d(f)) / S.norm();
    force.pressure += flow.p.boundary[static_cast<std::size_t>(b)] * S;
    force.viscous +=
        flow.settings().nu * (flow.U.cell(mesh.owner(f)) - flow.U.face(b)) * S.norm() / dn;
  }
  return force;
}

}  // namespace auvloop::engine::fv
