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
#include "auvloop/mesher/overset.hpp"

namespace auvloop::mesher {

struct CompositeGrid {
  Grid grid;
  std::vector<int> cell_offset;           // per component (step 1)
  std::vector<int> internal_face_offset;  // per component: its first internal face
  std::vector<std::vector<int>> patch;    // per component and its patch: the composite patch
  [[nodiscard]] int cells_of(std::size_t component) const {
    const std::size_t next = component + 1;
    return (next < cell_offset.size() ? cell_offset[next] : grid.cells) - cell_offset[component];
  }
};

// Throws std::invalid_argument when `components` is empty or two components share a name.
CompositeGrid composite_grid(std::span<const Grid* const> components);

// An overset assembly in the composite grid's cell numbers: per cell its status, and per fringe
// cell its stencil (CSR over the cells, empty for the others) of composite donor cells and
// weights, a donor of component grid h cell k being cell cell_offset[h] + k. The weights are the
// assembly's, so a field linear in the body frame is reproduced at every fringe centre.
struct CompositeStencils {
  std::vector<CellStatus> status;
  std::vector<int> offsets{0};  // cells + 1
  std::vector<int> donors;
  std::vector<double> weights;
};

// Throws std::invalid_argument when the assembly's grids do not match the composite's
// components (count or cells).
CompositeStencils composite_stencils(const CompositeGrid& composite, const Assembly& assembly);

// A static overset system in one call: the components assembled at their present placements
// (OversetAssembler), merged into one grid in the given order, the assembly in its numbers.
struct CompositeSystem {
  CompositeGrid composite;
  CompositeStencils stencils;
};
CompositeSystem composite_system(const std::vector<OversetComponent>& components,
                                 OversetSettings settings = {});

}  // namespace auvloop::mesher
