// SPDX-License-Identifier: GPL-3.0-or-later
// Grids of a 2D foil (one cell thick, empty sides) for issue 17's pitching-foil case: a NACA
// section's O-grid over a background, and the same O-grid continued to a far field as a single
// body-fitted grid, so that both set-ups share every cell near the foil.
//   1. the O-grid: the section loop of the fin grids (a fan of lines at a sharp trailing edge,
//      prisms there), each line a cubic Hermite curve from its wall point w, leaving along the
//      wall normal n, to its point c on the circle of outer_radius about the pivot, meeting it
//      radially (both end tangents of length |c - w|), its points at s in [0, 1] graded from the
//      wall (first cell first_cell); c's angle advances half with the wall's arc length plus half
//      the turning of its normal (so the trailing-edge fan spreads over the wake), half with the
//      line's index (so the lines the cosine spacing crowds at the edges spread out);
//   2. the single grid: the O-grid's lines continued radially from the circle to far_radius,
//      their cells growing by `growth` from the O-grid's last;
//   3. the background: a square `extent` chords across centred on the pivot, uniform cells of
//      `spacing` (or the circle's tangential size) in the core [-core_upstream, core_downstream] x
//      [-core_side, core_side] chords, growing by `growth` to the sides;
//   4. the solid: the section as a prism through the grids' thickness and beyond.
// Frame: the pivot at the origin, the chord along +x (leading edge at -pivot chord), z across.
// Patches: O-grid "foil" (wall), "outer" (overset); single grid "foil", "far"; background
// "west", "east", "south", "north"; all "front", "back" (empty).
#pragma once

#include <memory>

#include "auvloop/geometry/naca.hpp"
#include "auvloop/geometry/surface_fwd.hpp"
#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

struct FoilOversetSpec {
  geometry::NacaSection section;  // NACA 0012 with a sharp trailing edge by default
  double chord = 1.0;             // m
  double pivot = 0.25;            // chord fraction of the pivot, on the chord line
  int chordwise_cells = 48;       // per side, cosine spacing
  int trailing_edge_fan = 8;      // lines fanning out of the sharp trailing edge
  int normal_cells = 32;          // from the wall to the O-grid's circle
  double first_cell = 4e-3;       // in chords, at the wall
  double outer_radius = 1.0;      // in chords, the O-grid's circle about the pivot
  double far_radius = 20.0;       // in chords, the single grid's far field
  double growth = 1.1;            // beyond the circle (single grid) and the core (background)
  double extent = 40.0;           // in chords, the background's side
  double spacing = 0;  // in chords, the background's core cells (0: the circle's tangential size)
  double core_upstream = 1.2, core_downstream = 2.5, core_side = 1.2;  // in chords
  double thickness = 0.1;                                              // in chords
};

struct FoilGrids {
  Grid foil, background, single;
  std::shared_ptr<const geometry::SurfaceMesh> solid;  // in the foil grid's frame
};

// Throws std::invalid_argument naming the setting when the spec is unusable (the circle must
// contain the section and fit in the background's core, the far field lie beyond the circle).
FoilGrids foil_grids(const FoilOversetSpec& spec);

}  // namespace auvloop::mesher
