// SPDX-License-Identifier: GPL-3.0-or-later
// Plane Couette flow u = U y / H between a wall at rest (y = 0) and one moving at U (y = H),
// entering with that profile, on cells graded in y, run to its steady state: every operator
// reproduces a velocity linear in y exactly, so the flow and its wall shear nu U / H per area are
// exact to the solver tolerance. Shared by the PIMPLE and the wall-force tests.
#pragma once

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::test {

struct CouetteFlow {
  static constexpr double U = 0.5, H = 0.2, L = 1.0, nu = 0.01, dz = 0.05;  // m/s, m, m^2/s

  mesher::Grid grid = make_grid();
  engine::fv::Mesh mesh{grid};
  engine::fv::Pimple flow{mesh, settings()};

  CouetteFlow() {
    flow.U.fix(mesh, "bottom", {0, 0, 0});
    flow.U.fix(mesh, "top", {U, 0, 0});
    flow.U.fix(mesh, "inlet", {0, 0, 0});
    const auto& inlet = grid.patches[0];
    for (int i = 0; i < inlet.size; ++i)
      flow.U.c[0].bcs[0].value[static_cast<std::size_t>(i)] =
          U * mesh.face_centre(inlet.start + i).y() / H;
    flow.p.fix(mesh, "outlet", 0.0);
    flow.initialise();
    for (int k = 0; k < 60; ++k) flow.step();
  }
  CouetteFlow(const CouetteFlow&) = delete;
  CouetteFlow& operator=(const CouetteFlow&) = delete;

  // The exact force on each wall (N per unit density), along x.
  static constexpr double shear() { return nu * U / H * L * dz; }

 private:
  static mesher::Grid make_grid() {
    mesher::BoxPatches patches;
    patches.names = {"inlet", "outlet", "bottom", "top", "front", "back"};
    patches.types = {mesher::PatchType::inlet, mesher::PatchType::outlet, mesher::PatchType::wall,
                     mesher::PatchType::wall,  mesher::PatchType::empty,  mesher::PatchType::empty};
    return mesher::cartesian_box(mesher::graded_nodes(0, L, 10), mesher::graded_nodes(0, H, 8, 1.3),
                                 {0, dz}, patches, "couette");
  }
  static engine::fv::PimpleSettings settings() {
    engine::fv::PimpleSettings s;
    s.nu = nu;
    s.dt = 0.5;
    s.bdf2 = false;
    s.tolerance = 1e-12;
    return s;
  }
};

}  // namespace auvloop::test
