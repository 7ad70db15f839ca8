// SPDX-License-Identifier: GPL-3.0-or-later
// The overset coupling of a composite mesh (docs/overset-flow.md): which cells the flow solves
// (active), which take their values from donor cells of another component (fringe), which are out
// of the flow (hole), and which faces carry flux.
//
// Explicit coupling, as Pimple applies it (pimple.hpp, set_overset):
//   1. momentum: fringe rows fixed to the donors' interpolation of the current U, hole rows to 0
//      (Matrix::fix_values: active neighbours take the coupling into their sources);
//   2. pressure, each corrector: fringe rows fixed to the interpolation of the current p, hole rows
//      to their own value; the matrix stays symmetric (the fixed rows decouple);
//   3. Rhie-Chow flux at an active-fringe face with the fringe cell's HbyA = U + D grad(p), so
//      that its U = HbyA - D grad(p) is the interpolated velocity, as in an active cell;
//   4. after each corrector: fringe U from the donors again, hole U = 0;
//   5. face mask: a face carries flux only if one of its cells is active (`live`); others zero.
// Invariants (checked by the constructor): the stencils match the mesh; every fringe cell has a
// stencil whose donors are all active and whose weights sum to one; no cell is an orphan.
#pragma once

#include <span>
#include <vector>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/mesher/composite_grid.hpp"

namespace auvloop::engine::fv {

class Overset {
 public:
  // `stencils` in the mesh's (the composite grid's) cell numbers; `cell_offset` the composite's
  // first cell of each component. Throws std::invalid_argument naming the first violated
  // invariant.
  Overset(const Mesh& mesh, mesher::CompositeStencils stencils, std::vector<int> cell_offset);

  [[nodiscard]] mesher::CellStatus status(int c) const {
    return stencils_.status[static_cast<std::size_t>(c)];
  }
  [[nodiscard]] bool active(int c) const { return status(c) == mesher::CellStatus::active; }
  // Fringe and hole cells, ascending: the rows the coupling fixes.
  [[nodiscard]] std::span<const int> fixed_cells() const { return fixed_; }
  [[nodiscard]] std::span<const int> fringe_cells() const { return fringe_; }
  [[nodiscard]] std::span<const int> active_cells() const { return active_cells_; }
  // Whether face f carries flux: one of its cells (the owner of a boundary face) is active.
  [[nodiscard]] bool live(int f) const { return live_[static_cast<std::size_t>(f)] != 0; }
  // The value of `field` interpolated at fringe cell c from its donors.
  [[nodiscard]] double interpolate(std::span<const double> field, int c) const;
  // Per fixed cell (fixed_cells() order): the interpolation for a fringe cell, `hole` (or the
  // field's own value if `hole` is NaN) for a hole cell.
  void fixed_values(std::span<const double> field, double hole, std::vector<double>& out) const;
  // Sets the fringe cells of `field` to their interpolations (the donors are active: one pass),
  // and the hole cells to `hole` unless it is NaN.
  void apply(std::span<double> field, double hole) const;
  [[nodiscard]] int components() const { return static_cast<int>(cell_offset_.size()); }
  [[nodiscard]] int component_of(int c) const;
  [[nodiscard]] double active_volume() const { return active_volume_; }

 private:
  const Mesh& mesh_;
  mesher::CompositeStencils stencils_;
  std::vector<int> cell_offset_;
  std::vector<int> fixed_, fringe_, active_cells_;
  std::vector<char> live_;
  double active_volume_ = 0;
};

// Net volume flux (m^3/s) out of each component's active cells through the faces they share
// with its fringe and hole cells: the flux the overset interface passes. Zero for a component
// whose active region is closed by walls and fringe (an O-grid) once continuity holds; for a
// background, the flux into the region it does not solve, which continuity across the overlap
// would make zero.
std::vector<double> interface_flux(const Overset& overset, const Mesh& mesh,
                                   std::span<const double> phi);

}  // namespace auvloop::engine::fv
