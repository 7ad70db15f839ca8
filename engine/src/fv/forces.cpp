// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/forces.hpp"

#include <array>

namespace auvloop::engine::fv {

PatchForce& PatchForce::operator+=(const PatchForce& o) {
  pressure += o.pressure;
  viscous += o.viscous;
  pressure_moment += o.pressure_moment;
  viscous_moment += o.viscous_moment;
  return *this;
}

FaceForces face_forces(const Pimple& flow, const std::string& patch) {
  const Mesh& mesh = flow.mesh();
  const auto& p = mesh.grid().patches[static_cast<std::size_t>(patch_index(mesh, patch))];
  // The wall cells' gradients of the velocity components, for the transposed part of the
  // stress: only the owners of the patch's faces (the same bits as a whole-field gradient's
  // entries; a whole field for every wall patch in every outer iteration cost about 5 % of a
  // coarse step).
  const auto velocity_gradient = [&](int cell) {
    std::array<Eigen::Vector3d, 3> g;
    for (std::size_t c = 0; c < 3; ++c)
      g[c] = mesh.gradient_at(cell, flow.U.c[c].cells, flow.U.c[c].boundary);
    return g;
  };
  const Overset* overset = flow.overset();
  const TurbulenceModel* model = flow.turbulence();
  FaceForces out;
  out.start = p.start;
  const auto n = static_cast<std::size_t>(p.size);
  out.pressure.assign(n, Eigen::Vector3d::Zero());
  out.viscous.assign(n, Eigen::Vector3d::Zero());
  out.counted.assign(n, 0);
  for (int i = 0; i < p.size; ++i) {
    const int f = p.start + i;
    const int b = f - mesh.internal_faces();
    if (overset != nullptr && !overset->in_flow(mesh.owner(f))) continue;
    const double nu =
        model != nullptr ? model->nu_eff()[static_cast<std::size_t>(f)] : flow.settings().nu;
    const Eigen::Vector3d& S = mesh.area(f);
    const double dn = S.dot(mesh.d(f)) / S.norm();
    const auto g = velocity_gradient(mesh.owner(f));
    Eigen::Vector3d transposed;  // (grad U)^T . S
    for (int k = 0; k < 3; ++k) transposed[k] = g[0][k] * S.x() + g[1][k] * S.y() + g[2][k] * S.z();
    const auto is = static_cast<std::size_t>(i);
    out.pressure[is] = flow.p.boundary[static_cast<std::size_t>(b)] * S;
    out.viscous[is] =
        nu * ((flow.U.cell(mesh.owner(f)) - flow.U.face(b)) * S.norm() / dn - transposed);
    out.counted[is] = 1;
  }
  return out;
}

PatchForce patch_force(const Pimple& flow, const std::string& patch,
                       const Eigen::Vector3d& moment_point) {
  const Mesh& mesh = flow.mesh();
  const auto faces = face_forces(flow, patch);
  PatchForce force;
  for (std::size_t i = 0; i < faces.counted.size(); ++i) {
    if (!faces.counted[i]) continue;
    const Eigen::Vector3d arm = mesh.face_centre(faces.start + static_cast<int>(i)) - moment_point;
    force.pressure += faces.pressure[i];
    force.viscous += faces.viscous[i];
    force.pressure_moment += arm.cross(faces.pressure[i]);
    force.viscous_moment += arm.cross(faces.viscous[i]);
  }
  return force;
}

std::vector<std::pair<std::string, PatchForce>> wall_forces(const Pimple& flow,
                                                            const Eigen::Vector3d& moment_point) {
  std::vector<std::pair<std::string, PatchForce>> out;
  for (const auto& patch : flow.mesh().grid().patches)
    if (patch.type == mesher::PatchType::wall)
      out.emplace_back(patch.name, patch_force(flow, patch.name, moment_point));
  return out;
}

PatchForce total_wall_force(const Pimple& flow, const Eigen::Vector3d& moment_point) {
  PatchForce sum;
  for (const auto& [name, force] : wall_forces(flow, moment_point)) sum += force;
  return sum;
}

}  // namespace auvloop::engine::fv
