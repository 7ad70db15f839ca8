// SPDX-License-Identifier: GPL-3.0-or-later
// The grids of an overset system as one grid (docs/overset-flow.md, "One mesh, one frame"): the
// composite grid the flow solver runs on, as OpenFOAM merges an overset case's components into
// one mesh.
//   1. cells: component g's cells are cells cell_offset[g] .. cell_offset[g] + cells_g, in the
//      order given; each component a zone named after its grid, its own zones "<grid>/<zone>";
//   2. points: every component's points in the body frame (its placement applied); the composite
//      placement is the identity;
//   3. faces: the internal faces of every component in turn (owner < neighbour kept: the offsets
//      preserve it, and the upper-triangular order with it), then the boundary faces patch by
//      patch, component by component; patch "<grid>/<patch>" of the same type (periodic partners
//      renumbered); a component's faces keep their point order, so their normals point out of the
//      same owners.
// No face joins two components: the components meet only through their overset patches and the
// assembly's donor stencils, which the solver adds.
#pragma once

#include <span>
#include <vector>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

struct CompositeGrid {
  Grid grid;
  std::vector<int> cell_offset;           // per component (step 1)
  std::vector<int> internal_face_offset;  // per component: its first internal face
  std::vector<std::vector<int>> patch;    // per component and its patch: the composite patch
};

// Throws std::invalid_argument when `components` is empty or two components share a name.
CompositeGrid composite_grid(std::span<const Grid* const> components);

}  // namespace auvloop::mesher
