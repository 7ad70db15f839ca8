// SPDX-License-Identifier: GPL-3.0-or-later
// Wall pressure for the validation cases' pressure differences on a wall.
//
// A wall face f sees two cells along its normal: its owner P and the cell Q across P's face
// opposite the wall (the O-grid's next radial cell). With the wall-normal distances s_P < s_Q of
// their centres (after moving each value along the wall with its cell gradient, so that both lie
// on the normal through the face centre), p at the wall by linear extrapolation of p_P and p_Q
// (error O(s_P s_Q)). Not for forces: a wall derivative from the same stencil (a parabola through
// U_wall, U_P, U_Q) converged at first order from above, where the solver's own one-sided wall
// flux converges to the reference (schaefer_turek.cpp).
#pragma once

#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "auvloop/engine/fv/mesh.hpp"

namespace auvloop::engine::validation {

struct WallStencil {
  int face = 0;
  int P = 0, Q = 0;        // the wall cell and the next cell along the normal
  double sP = 0, sQ = 0;   // their wall-normal distances (m)
  Eigen::Vector3d n;       // unit normal into the fluid
  Eigen::Vector3d tP, tQ;  // tangential offsets of the centres from the normal through the face
};

// Value of a cell field on the wall normal at the cell's distance: phi_c - grad(phi)_c . t.
inline double on_normal(const std::vector<double>& phi, const std::vector<Eigen::Vector3d>& grad,
                        int c, const Eigen::Vector3d& t) {
  const auto s = static_cast<std::size_t>(c);
  return phi[s] - grad[s].dot(t);
}

// One stencil per face of the patch (by index into the grid's patches).
inline std::vector<WallStencil> wall_stencils(const engine::fv::Mesh& mesh, int patch) {
  const auto& pa = mesh.grid().patches[static_cast<std::size_t>(patch)];
  std::vector<WallStencil> out;
  for (int i = 0; i < pa.size; ++i) {
    WallStencil w;
    w.face = pa.start + i;
    w.P = mesh.owner(w.face);
    w.n = -mesh.area(w.face).normalized();
    const Eigen::Vector3d& xf = mesh.face_centre(w.face);
    // Q: the neighbour of P whose centre lies furthest along the normal.
    double best = -1e300;
    for (int g : mesh.cell_faces(w.P)) {
      if (g >= mesh.internal_faces()) continue;
      const int other = mesh.owner(g) == w.P ? mesh.neighbour(g) : mesh.owner(g);
      const double s = w.n.dot(mesh.centre(other) - xf);
      if (s > best) {
        best = s;
        w.Q = other;
      }
    }
    const Eigen::Vector3d rP = mesh.centre(w.P) - xf, rQ = mesh.centre(w.Q) - xf;
    w.sP = w.n.dot(rP);
    w.sQ = w.n.dot(rQ);
    if (!(w.sP > 0 && w.sQ > 1.5 * w.sP))
      throw std::runtime_error("wall_stencils: no cell beyond the wall cell along the normal");
    w.tP = rP - w.sP * w.n;
    w.tQ = rQ - w.sQ * w.n;
    out.push_back(w);
  }
  return out;
}

// Wall value of a field by linear extrapolation from the two cells.
inline double wall_extrapolation(const WallStencil& w, double phiP, double phiQ) {
  return (w.sQ * phiP - w.sP * phiQ) / (w.sQ - w.sP);
}

}  // namespace auvloop::engine::validation
