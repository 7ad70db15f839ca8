// SPDX-License-Identifier: GPL-3.0-or-later
// Checks shared by the component-grid tests: invariants, boundary orientation, patch measures.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::test {

inline const mesher::Patch& patch_named(const mesher::Grid& g, const std::string& name) {
  for (const auto& p : g.patches)
    if (p.name == name) return p;
  throw std::runtime_error("no patch " + name);
}

// Every boundary face's area vector points away from its owner cell: patches are oriented
// outward from the fluid, as the solver and OpenFOAM expect.
inline int inward_boundary_faces(const mesher::Grid& g, const mesher::GridGeometry& geo) {
  int bad = 0;
  for (int f = g.internal_faces(); f < g.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const auto c = static_cast<std::size_t>(g.owner[fs]);
    if (!(geo.face_area[fs].dot(geo.face_centre[fs] - geo.cell_centre[c]) > 0)) ++bad;
  }
  return bad;
}

inline double patch_area(const mesher::GridGeometry& geo, const mesher::Patch& p) {
  double a = 0;
  for (int f = p.start; f < p.start + p.size; ++f)
    a += geo.face_area[static_cast<std::size_t>(f)].norm();
  return a;
}

// Volume enclosed by a closed wall patch whose normals point into the body (out of the fluid):
// divergence theorem, V = -(1/3) sum S . x_f, exact for planar faces.
inline double enclosed_volume(const mesher::GridGeometry& geo, const mesher::Patch& p) {
  double v = 0;
  for (int f = p.start; f < p.start + p.size; ++f) {
    const auto fs = static_cast<std::size_t>(f);
    v -= geo.face_area[fs].dot(geo.face_centre[fs]) / 3;
  }
  return v;
}

// Sum of the area vectors of a patch: zero for a closed surface (to round-off).
inline Eigen::Vector3d patch_area_vector(const mesher::GridGeometry& geo, const mesher::Patch& p) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (int f = p.start; f < p.start + p.size; ++f) s += geo.face_area[static_cast<std::size_t>(f)];
  return s;
}

}  // namespace auvloop::test
