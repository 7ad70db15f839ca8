// SPDX-License-Identifier: GPL-3.0-or-later
// The single-grid hull flow the benchmarks time: a preset's REMUS 100 hull grid (no fins, no
// overset) in a free stream, and one PIMPLE time step on it.
#pragma once

#include <string>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/grid_system.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

namespace auvloop::bench {

inline  // The hull grid with its outer (overset) patch split into "inflow" (faces facing the
        // oncoming
    // stream, U_inf . S < 0) and "outflow" (the rest), as a single-grid freestream case needs.
    mesher::Grid
    hull_freestream_grid(const std::string& preset, const Eigen::Vector3d& u_inf) {
  const auto vehicle = geometry::preset_vehicle("remus100");
  const auto settings = mesher::mesh_preset(preset, vehicle);
  const mesher::Grid hull = mesher::build_grid_system(vehicle, settings).hull;
  mesher::Grid g = hull;
  g.face_offsets = {0};
  g.face_points.clear();
  g.owner.clear();
  g.patches.clear();
  const auto geo = mesher::compute_geometry(hull);
  auto copy = [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    g.add_face(std::vector<int>(hull.face_points.begin() + hull.face_offsets[fs],
                                hull.face_points.begin() + hull.face_offsets[fs + 1]),
               hull.owner[fs]);
  };
  for (int f = 0; f < hull.internal_faces(); ++f) copy(f);
  for (const auto& patch : hull.patches) {
    if (patch.type != mesher::PatchType::overset) {
      mesher::Patch p = patch;
      p.start = g.faces();
      for (int i = 0; i < patch.size; ++i) copy(patch.start + i);
      g.patches.push_back(p);
      continue;
    }
    for (const bool inflow : {true, false}) {
      mesher::Patch p{inflow ? "inflow" : "outflow",
                      inflow ? mesher::PatchType::inlet : mesher::PatchType::outlet, g.faces(), 0};
      for (int i = 0; i < patch.size; ++i) {
        const int f = patch.start + i;
        if ((u_inf.dot(geo.face_area[static_cast<std::size_t>(f)]) < 0) == inflow) copy(f);
      }
      p.size = g.faces() - p.start;
      g.patches.push_back(p);
    }
  }
  return g;
}

// The time step for Courant number `co` of the free stream in the smallest cell of the grid.
inline double freestream_dt(const engine::fv::Mesh& mesh, const Eigen::Vector3d& u_inf, double co) {
  std::vector<double> flux(static_cast<std::size_t>(mesh.faces()));
  for (int f = 0; f < mesh.faces(); ++f)
    flux[static_cast<std::size_t>(f)] = u_inf.dot(mesh.area(f));
  return co / engine::fv::courant(mesh, flux, 1.0).first;
}

// Boundary and initial conditions on that grid: U_inf fixed on the inflow part of the outer
// boundary, p = 0 on the outflow part, no slip on the hull, U_inf everywhere at the start.
inline void set_freestream(engine::fv::Pimple& flow, const engine::fv::Mesh& mesh,
                           const Eigen::Vector3d& u_inf) {
  flow.U.fix(mesh, "hull", {0, 0, 0});
  flow.U.fix(mesh, "inflow", u_inf);
  flow.p.fix(mesh, "outflow", 0.0);
  for (int k = 0; k < 3; ++k)
    flow.U.c[static_cast<std::size_t>(k)].cells.assign(
        flow.U.c[static_cast<std::size_t>(k)].cells.size(), u_inf(k));
}

}  // namespace auvloop::bench
