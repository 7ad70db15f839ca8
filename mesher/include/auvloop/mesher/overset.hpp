// SPDX-License-Identifier: GPL-3.0-or-later
// Overset assembly of a grid system (docs/mesher.md): which cells solve (active), which take
// their values from another grid (fringe, with donor cells and weights), which are out of the
// fluid or covered by a better grid (hole), and which found no donor (orphan).
//
// Algorithm, grids in priority order (a vehicle: fins, then hull, then background; the finest,
// nearest-wall grid wins):
//   1. wall holes: cells whose centre lies inside the solid of another grid (hull, fins; CGAL
//      inside tests, geometry::SurfaceQuery, on the solids placed with their grids);
//   2. covered holes: a cell whose centre lies in an active cell of another component grid whose
//      wall is nearer (by the fringe layers plus one and a half of the cell's sizes; the
//      background has no wall), at least `overlap_cells` of its own sizes plus fringe_layers + 1.5
//      diameters of the covering cell deep inside that grid's active region (so that the cell's
//      fringe finds covering-grid cells that are not fringe themselves);
//   3. fringe: `fringe_layers` layers of cells next to holes and, for component grids, next to the
//      outer (overset) boundary;
//   4. donors: the cell of another grid (priority order) that contains the fringe cell's centre
//      and is active, found by a walk through the cells from the nearest cell centre (a k-d tree),
//      or from the previous donor in an incremental update; the stencil is it and its active
//      neighbours. Failing that in every grid (where the fringes of two grids overlap: beside a
//      fin near the hull, and at a fin grid's outer boundary over the hull grid's fringe round
//      its cells inside the fin; docs/mesher.md), a fallback donor: the active cells nearest to
//      the containing cell (or, just outside a grid, to its nearest cell) in the grid where they
//      lie nearest to the centre, in their cell sizes. Weights: the minimum (inverse-distance
//      weighted) norm solution of sum w = 1, sum w x = x_fringe, so linear fields are interpolated
//      exactly, inside or outside the stencil's hull.
//   5. chains: a fallback receiver whose centre lies in a fringe cell of another grid that has
//      donors of its own takes the containing stencil there with that cell's stencil composed in
//      (GridAssembly::chained; its donors, all active, may lie in several grids). The fallback
//      stencils of step 4 are searched only for the receivers left unchained.
// Invariants of a result: no donor cell is anything but active; weights sum to one.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "auvloop/geometry/surface_fwd.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/grid_system.hpp"

namespace auvloop::mesher {

enum class CellStatus : std::uint8_t { active = 0, fringe = 1, hole = 2, orphan = 3 };
const char* to_string(CellStatus s);

struct GridAssembly {
  std::vector<CellStatus> status;
  // Per fringe cell (CSR over cells; empty for the others): donor grid, donor cells, weights.
  std::vector<int> donor_grid;  // per cell, -1 if none
  std::vector<int> donor_cell;  // per cell: the cell containing the centre, -1 if none
  // Per cell: 1 when the donors are a fallback (the containing cell was not active; donor_cell is
  // then the stencil's first active cell).
  std::vector<char> fallback;
  // Per cell: 1 when the stencil is chained: the containing cell of donor_grid is a fringe cell
  // whose own stencil is composed in, so the donors (all active) may lie in several grids.
  std::vector<char> chained;
  std::vector<int> stencil_offsets;  // cells + 1
  std::vector<int> stencil_grids;    // per stencil entry: the donor's grid
  std::vector<int> stencil_cells;
  std::vector<double> stencil_weights;
  [[nodiscard]] int count(CellStatus s) const;
  [[nodiscard]] int fallbacks() const;
  [[nodiscard]] int chains() const;
};

struct Assembly {
  std::vector<double> fin_deflections;  // rad
  std::vector<GridAssembly> grids;      // GridSystem::grids() order
  double seconds = 0;                   // wall time of the assembly
  int cells_visited = 0;                // cells whose status was (re)computed
  // What is legal but almost surely not meant, one sentence each: a grid that another grid's
  // solid cuts while no grid covers any of its cells (its cells are too coarse for the cover
  // rule, so it resolves the body on its own staircase of cells).
  std::vector<std::string> warnings;
};

struct OversetSettings {
  int fringe_layers = 2;  // second-order stencils reach two cells
  // A cell is covered only this many of its own sizes inside the better grid's active region:
  // its two fringe layers (2 sizes) then find active donors there, and the better grid's fringe
  // finds active donors among this grid's cells (the 0.87 of a size to the farthest corner).
  double overlap_cells = 3.5;
  double surface_edge = 0.004;  // m, triangulation of hull and fins for the inside tests
  // When the cell of another grid containing a fringe centre is not active (a fringe or hole cell
  // of that grid), the donors are the active cells within this many face steps of it.
  int fallback_rings = 5;
  // Fallback receivers inside a fringe cell of another grid that has donors of its own take that
  // cell's stencil composed in (a chained stencil); each pass reaches one cell further.
  int chain_passes = 4;
};

// One grid of a general overset system (a cylinder's O-grid over a channel, a foil's grid over a
// background): the grid (not owned; its placement, read at every assembly, maps its frame to the
// system's), its priority (where grids overlap the higher wins; 0 is a background, which has no
// wall and covers nothing) and the closed body it fits, in the grid's frame (null: none), whose
// inside is a hole in every other grid. Grids whose patches include a non-empty `empty` patch are
// one cell thick; when all are, the system is planar (2D): stencils reproduce linear fields in
// the plane, and cell sizes are measured in it.
struct OversetComponent {
  const Grid* grid = nullptr;
  int priority = 0;
  const geometry::SurfaceMesh* solid = nullptr;  // copied by the assembler
};

class OversetAssembler {
 public:
  // A vehicle's system: hull (priority 1, the hull's solid), fins (priority 2, each its fin's
  // solid, turned with its grid), background (0); GridSystem::grids() order.
  OversetAssembler(GridSystem& system, const geometry::Vehicle& vehicle,
                   OversetSettings settings = {});
  // A general system, in the order given (the Assembly's grid order). Throws
  // std::invalid_argument for fewer than two grids or a grid without cells.
  explicit OversetAssembler(const std::vector<OversetComponent>& components,
                            OversetSettings settings = {});
  OversetAssembler(OversetAssembler&&) noexcept;
  ~OversetAssembler();

  // Full assembly with the fins at `deflections` (rad, one per fin); moves the fin grids'
  // placements of the system given to the constructor.
  // A vehicle's system only (std::logic_error otherwise).
  Assembly assemble(const std::vector<double>& deflections);
  // Full assembly at the grids' present placements (any system).
  Assembly assemble();
  // After a small fin rotation: only cells near the fins whose deflection changed are
  // re-examined; stencils between grids that did not move are kept, the others refitted (new
  // weights on the previous cells) while their donor still contains the centre and nothing outranks
  // it, or else searched from the previous donor. Gives the same statuses as a full assembly
  // (tested). A vehicle's system only (std::logic_error otherwise).
  Assembly update(const Assembly& previous, const std::vector<double>& deflections);

  // Body-frame centre of a cell (placement applied).
  [[nodiscard]] Eigen::Vector3d centre(int grid, int cell) const;
  // The cell of a grid (GridSystem::grids() order) containing a body-frame point, -1 if none.
  [[nodiscard]] int locate(int grid, const Eigen::Vector3d& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace auvloop::mesher
