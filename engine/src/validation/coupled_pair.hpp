// SPDX-License-Identifier: GPL-3.0-or-later
// A cylinder pair (O-grid over a background, mesher::CylinderOverset) assembled, merged and
// coupled: the grids of the moving-grid cases. Private to engine/src/validation.
#pragma once

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/fv/overset.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"

namespace auvloop::engine::validation {

struct CoupledPair {
  mesher::CompositeSystem system;
  fv::Mesh mesh;
  fv::Overset overset;
  explicit CoupledPair(const mesher::CylinderOverset& pair)
      : system(mesher::composite_system(
            {{&pair.cylinder, 1, pair.solid.get()}, {&pair.background, 0, nullptr}})),
        mesh(system.composite.grid),
        overset(mesh, system.stencils, system.composite.cell_offset) {}
};

}  // namespace auvloop::engine::validation
