// SPDX-License-Identifier: GPL-3.0-or-later
// Rigid motion of the grids (docs/cfd.md, "Moving grids"). Every grid (the single mesh, or each
// component of an overset mesh) stays at rest in its own axes, which move rigidly: the solver
// works in those axes with the absolute velocity u (the fluid's velocity in the Earth frame,
// resolved in the grid's axes) as its unknown. For a cell at rest in moving axes, the finite-
// volume balance of the Earth-frame momentum, resolved in those axes, reads
//     d/dt (V u) + sum_f u_f (phi_f - phi_g,f) + V (Omega x u) = -sum_f p_f S_f + viscous terms,
//     sum_f phi_f = 0,
// with phi = u . S the absolute face flux (what continuity and Rhie-Chow see), phi_g the flux of
// the grid velocity w(x) = V + Omega x x through the face (what convection subtracts), and
// Omega x u the rotation of the axes under the vector (absolute-velocity formulation: no
// centrifugal or Coriolis term, and the pressure of fluid at rest stays uniform). It is the
// arbitrary Lagrangian-Eulerian form of the Earth-frame equations for a rigid grid motion, so
// the flow is the same as that of a grid moved through the fluid, and a Galilean or a rotating
// change of frame is exact (the grid's geometry, its multigrid hierarchy and its gradients never
// change).
//
// Geometric conservation, exact per cell: phi_g,f = V . S_f + Omega . m_f with the face moment
// m_f = sum_t x_t x S_t over the face's triangles (the same fan the mesher's geometry uses, x_t
// a triangle's centroid): over a cell's closed surface sum S_f = 0 and sum m_f = 0 (the
// integral of x x n over a closed polyhedron), so the grid flux adds no volume to any cell.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace auvloop::engine::fv {

// The motion of one grid's axes at the new time level, resolved in those axes.
struct FrameMotion {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // of the axes' origin (m/s): (u, v, w)
  Eigen::Vector3d rate = Eigen::Vector3d::Zero();      // angular velocity (rad/s): (p, q, r)
  // The far field's fluid velocity (m/s): zero for fluid at rest, a current otherwise, both in
  // these axes (Pimple::far_field).
  Eigen::Vector3d stream = Eigen::Vector3d::Zero();
  // The grid velocity at the point x of these axes (m/s).
  [[nodiscard]] Eigen::Vector3d at(const Eigen::Vector3d& x) const {
    return velocity + rate.cross(x);
  }
  [[nodiscard]] bool at_rest() const { return velocity.isZero(0) && rate.isZero(0); }
};

// The motion of a grid's axes that turn within a moving body (a fin on its post, a foil pitching
// over a background at rest): `body` the motion of the body's axes (its stream the far field's,
// all resolved in the body's axes), `placement` the grid's axes in the body's (x_body =
// placement * x_grid; for a grid that was merged into a composite mesh at placement P0 and now
// stands at P, placement = P * P0^-1), and the grid turning relative to the body at `rate`
// (rad/s, body axes) about the point `pivot` (body axes). With R and t the placement's rotation
// and translation, the grid velocity w(y) = V + Omega x y + rate x (y - pivot) at y = R x + t,
// resolved in the grid's axes, is R^T w(R x + t) = velocity + rate_g x x with
//     velocity = R^T (V + Omega x t + rate x (t - pivot)),  rate_g = R^T (Omega + rate),
// and stream = R^T stream_body.
FrameMotion placed_motion(const FrameMotion& body, const Eigen::Isometry3d& placement,
                          const Eigen::Vector3d& rate, const Eigen::Vector3d& pivot);

}  // namespace auvloop::engine::fv
