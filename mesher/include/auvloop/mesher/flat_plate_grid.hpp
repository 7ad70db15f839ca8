// SPDX-License-Identifier: GPL-3.0-or-later
// The zero-pressure-gradient flat plate of NASA's Turbulence Modeling Resource (case 2DZP, the
// SST verification of issue 16) as a one-cell-thick 2D grid: the plate from x = 0 to
// `plate_length` on y = 0, a symmetry plane ahead of it from x = -`upstream`, the domain `height`
// high. Cells grow geometrically away from the wall (first cell `first_height`) and both ways from
// the leading edge (first cells `leading_edge_dx`), as the TMR's grids are clustered. A family of
// nested grids, as the TMR's (each coarser grid every other node of the next finer): `level` 0 is
// the finest the spec describes, level l takes every 2^l-th node in x and y (the cell counts must
// be divisible by 2^l).
// Patches: inlet (x = -upstream), outlet (x = plate_length), symmetry (y = 0 ahead of the plate),
// plate (wall), top (y = height: `top_type`, by default a pressure outlet, through which the
// boundary layer's displacement leaves), front and back (empty).
#pragma once

#include <string>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

struct FlatPlateSpec {
  double plate_length = 2.0;      // m
  double upstream = 1.0 / 3;      // m, symmetry plane ahead of the leading edge
  double height = 1.0;            // m
  double thickness = 0.1;         // m, z extent of the one-cell-thick grid
  int plate_cells = 256;          // along the plate
  int upstream_cells = 64;        // ahead of it
  int normal_cells = 192;         // wall-normal
  double first_height = 1e-6;     // m, wall-normal size of the first cell (finest level)
  double leading_edge_dx = 2e-4;  // m, streamwise size of the cells at x = 0 (finest level)
  PatchType top_type = PatchType::outlet;
};

// Throws std::invalid_argument naming the bad setting (sizes not positive, a first cell larger
// than its side allows, cell counts not divisible by 2^level).
Grid flat_plate(const FlatPlateSpec& spec, int level = 0, const std::string& name = "flat-plate");

}  // namespace auvloop::mesher
