// SPDX-License-Identifier: GPL-3.0-or-later
// The overset coupling of a composite mesh (docs/overset-flow.md): which cells the flow solves
// (active), which take their values from donor cells of another component (fringe), which are out
// of the flow (hole), and which faces carry flux.
//
// Explicit coupling (PimpleSettings::overset_coupling = lagged), as Pimple applies it:
//   1. momentum: fringe rows fixed to the donors' interpolation of the current U, hole rows to 0
//      (Matrix::fix_values: active neighbours take the coupling into their sources);
//   2. pressure, each corrector: fringe rows fixed to the interpolation of the current p, hole rows
//      to their own value; the matrix stays symmetric (the fixed rows decouple);
//   3. Rhie-Chow flux at an active-fringe face with the fringe cell's HbyA = U + D grad(p), so
//      that its U = HbyA - D grad(p) is the interpolated velocity, as in an active cell;
//   4. after each corrector: fringe U from the donors again, hole U = 0;
//   5. face mask: a face carries flux only if one of its cells is active (`live`); others zero.
// Implicit coupling (overset_coupling = implicit; overset_implicit.cpp states it): in steps 1 and
// 2 the fringe values are eliminated, phi_a = sum_k w_k phi_k with the donors' values unknowns
// of the same solve, so an active row next to a fringe cell couples to that cell's donors
// (couple(): the entries beyond the face pattern go to an ExtraEntries, solved by
// LinearSolver::solve_coupled); after each solve the fringe cells take their interpolation.
// Grids that turn against each other (a fin on its post, a pitching foil): every component keeps
// its cells at rest in its own axes (motion.hpp), so a vector interpolated from a donor of
// component g into a fringe cell of component h is turned from g's axes into h's:
// u_h = R_h^T R_g u_g, R_k the orientation of component k's axes in the system's (identity at
// construction). The stencils' weights are scalars, the same in every frame.
// When the grids move, the driver re-assembles at the new placements before each step and
// passes the result to update(); Pimple then carries the cells that came out of a hole
// (pimple.hpp, "Overset re-assembly").
// Invariants (checked by the constructor and update): the stencils match the mesh; every fringe
// cell has a stencil whose donors are all active and whose weights sum to one; no cell is an
// orphan.
#pragma once

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "auvloop/engine/fv/matrix.hpp"
#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/mesher/composite_grid.hpp"

namespace auvloop::engine::fv {

class Overset {
 public:
  // `stencils` in the mesh's (the composite grid's) cell numbers; `cell_offset` the composite's
  // first cell of each component. Throws std::invalid_argument naming the first violated
  // invariant.
  Overset(const Mesh& mesh, mesher::CompositeStencils stencils, std::vector<int> cell_offset);

  // A new assembly of the same composite mesh (the grids moved). Throws std::invalid_argument
  // naming the first violated invariant, leaving this coupling unchanged.
  void update(mesher::CompositeStencils stencils);
  // The orientation of each component's axes in the system's (rotation matrices, one per
  // component). Throws std::invalid_argument on a wrong count or a matrix that is not a rotation.
  void set_orientation(std::vector<Eigen::Matrix3d> orientation);
  // Whether some component's axes are turned against another's.
  [[nodiscard]] bool turned() const { return turned_; }
  // Counts the assemblies this coupling has held (construction 1, each update one more): a
  // solver keeping anything built from the stencils rebuilds it when this changes.
  [[nodiscard]] int generation() const { return generation_; }
  // Rotation from component g's axes into component h's: R_h^T R_g.
  [[nodiscard]] const Eigen::Matrix3d& rotation(int h, int g) const {
    return rotation_[static_cast<std::size_t>(h * components() + g)];
  }

  [[nodiscard]] mesher::CellStatus status(int c) const {
    return stencils_.status[static_cast<std::size_t>(c)];
  }
  [[nodiscard]] bool active(int c) const { return status(c) == mesher::CellStatus::active; }
  // Whether cell c is in the flow (active or fringe, not a hole): a wall face of a hole cell lies
  // inside another grid's body and counts for no force and no wall treatment.
  [[nodiscard]] bool in_flow(int c) const { return status(c) != mesher::CellStatus::hole; }
  // Fringe and hole cells, ascending: the rows the coupling fixes.
  [[nodiscard]] std::span<const int> fixed_cells() const { return fixed_; }
  [[nodiscard]] std::span<const int> fringe_cells() const { return fringe_; }
  [[nodiscard]] std::span<const int> active_cells() const { return active_cells_; }
  // Whether face f carries flux: one of its cells (the owner of a boundary face) is active.
  [[nodiscard]] bool live(int f) const { return live_[static_cast<std::size_t>(f)] != 0; }
  // How a scalar is interpolated: `linear` the stencil's weights as they are (exact for a linear
  // field; a weight may be negative); `donors` the same value clipped to the range of the
  // donors' values, so that a positive field (k, omega) stays positive where it is steep (at a
  // wall) and the stencil's negative weights would overshoot.
  enum class Bound { linear, donors };
  // The value of `field` interpolated at fringe cell c from its donors.
  [[nodiscard]] double interpolate(std::span<const double> field, int c,
                                   Bound bound = Bound::linear) const;
  // The vector (u[0], u[1], u[2]) interpolated at fringe cell c, each donor's value turned into
  // c's axes.
  using Vector = std::array<std::span<const double>, 3>;
  [[nodiscard]] Eigen::Vector3d interpolate(const Vector& u, int c) const;
  // The gradient of u at fringe cell c (row i: grad u_i, in c's axes) interpolated from its
  // donors' least-squares gradients (Mesh::gradient_at, with u's boundary values `boundary`),
  // each turned into c's axes (R G R^T). Reproduces a gradient that is the same everywhere.
  [[nodiscard]] Eigen::Matrix3d interpolate_gradient(const Vector& u, const Vector& boundary,
                                                     int c) const;
  // Per fixed cell (fixed_cells() order): the interpolation for a fringe cell, `hole` (or the
  // field's own value if `hole` is NaN) for a hole cell.
  void fixed_values(std::span<const double> field, double hole, std::vector<double>& out,
                    Bound bound = Bound::linear) const;
  // The same for component i of a vector field (a hole cell keeps its own value).
  void fixed_values(const Vector& u, std::size_t i, std::vector<double>& out) const;
  // Sets the fringe cells of `field` to their interpolations (the donors are active: one pass),
  // and the hole cells to `hole` unless it is NaN.
  void apply(std::span<double> field, double hole, Bound bound = Bound::linear) const;
  // Sets the fringe cells of a vector field to their interpolations (hole cells unchanged).
  void apply(const std::array<std::span<double>, 3>& u) const;
  // The implicit coupling of `eq` (overset_implicit.cpp) for a scalar field: the fringe values
  // eliminated, phi_a = sum_k w_k phi_{d_k} + offsets[j] for fringe_cells()[j] (empty: 0), into
  // the active rows (`extra`: the entries on the donors); fringe and hole rows fixed (a hole
  // to `hole`, or the field's own value if NaN). After the solve, apply() the interpolation
  // (and add the offsets). `values`: scratch.
  void couple(Matrix& eq, std::span<const double> field, double hole,
              std::span<const double> offsets, ExtraEntries& extra,
              std::vector<double>& values) const;
  // The same for component i of a vector field (hole rows keep their own value); with turned
  // axes the donors' other components are the offsets, at their current values.
  void couple(Matrix& eq, const Vector& u, std::size_t i, ExtraEntries& extra,
              std::vector<double>& values) const;
  [[nodiscard]] int components() const { return static_cast<int>(cell_offset_.size()); }
  [[nodiscard]] int component_of(int c) const;
  [[nodiscard]] double active_volume() const { return active_volume_; }

 private:
  // Validates `stencils` and builds the lists from them (all or nothing).
  void assign(mesher::CompositeStencils stencils);
  // The implicit coupling's lists (overset_implicit.cpp), from the statuses.
  void list_coupled_rows();
  // `extra` for eq (component i of a vector, or -1 for a scalar).
  void implicit_entries(const Matrix& eq, int i, ExtraEntries& extra) const;
  void hold_fringe_rows(Matrix& eq, std::span<const double> field) const;

  const Mesh& mesh_;
  mesher::CompositeStencils stencils_;
  std::vector<int> cell_offset_;
  std::vector<int> fixed_, fringe_, active_cells_;
  std::vector<char> live_;
  // Implicit coupling: the active cells with a fringe face neighbour, ascending, and per such
  // cell the faces to its fringe neighbours at [coupled_start_[k], coupled_start_[k + 1]);
  // fringe_slot_[j]: the place of fringe_[j] in fixed_.
  std::vector<int> active_rows_, coupled_start_, coupled_faces_, fringe_slot_;
  double active_volume_ = 0;
  std::vector<Eigen::Matrix3d> orientation_, rotation_;
  bool turned_ = false;
  int generation_ = 0;
  mutable std::vector<Eigen::Vector3d> scratch_;  // apply()'s interpolated vectors
  // Per stencil entry: the donor's component (the rotation into the receiver's axes).
  std::vector<int> donor_component_;
  // Component i of the vector interpolated at fringe cell c (interpolate(u, c)[i]).
  [[nodiscard]] double interpolate(const Vector& u, int c, std::size_t i) const;
};

// Net volume flux (m^3/s) out of each component's active cells through the faces they share
// with its fringe and hole cells: the flux the overset interface passes. Zero for a component
// whose active region is closed by walls and fringe (an O-grid) once continuity holds; for a
// background, the flux into the region it does not solve, which continuity across the overlap
// would make zero.
std::vector<double> interface_flux(const Overset& overset, const Mesh& mesh,
                                   std::span<const double> phi);

}  // namespace auvloop::engine::fv
