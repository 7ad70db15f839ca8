// SPDX-License-Identifier: GPL-3.0-or-later
// The body-fitted grid of one fin (docs/mesher.md).
//
// Topology: an O-grid around the NACA section (index p round the section, j outward along
// straight wall-normal lines to `extent`; a fan of lines round a sharp trailing edge), stacked
// along the fin post in levels that follow the fin's root face (the hull a gap away): from
// `root_depth` below the root face, across the gap and into the hull, to `cap_height` beyond the
// tip. Below the root face and above the tip the section's interior is filled by a column of
// chordwise strips joining matching upper and lower points (triangular prisms at the leading and
// sharp trailing edges): root face and tip are walls of this grid, not staircases left by hole
// cutting, and the gap holds layers of both this grid and the hull grid. Wall points lie on the
// analytic fin at every level. Patches: "<fin>" (wall: sides, root face and tip) and
// "<fin>_overset" (outer surface, bottom, top). The grid is built at zero deflection in the body
// frame; a deflection is a placement.
#pragma once

#include "auvloop/geometry/fin.hpp"
#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

struct FinGridSpec {
  int chordwise_cells = 16;   // per side, leading to trailing edge (cosine spacing)
  int normal_cells = 0;       // wall to outer surface; 0: the fewest that keep `growth`
  int gap_cells = 4;          // levels across the root gap (uniform; wall cells grow to them)
  int span_cells = 12;        // root face to tip, clustered towards both
  int cap_cells = 0;          // tip to top; 0: the fewest that keep `growth`
  int trailing_edge_fan = 8;  // lines fanning out of a sharp trailing edge (upper to lower normal)
  double first_cell = 2e-4;   // m, first cell height at the sides, root face and tip
  double growth = 1.2;        // largest ratio of neighbouring sizes (the counts left at 0)
  double extent = 0.03;       // m, from the section to the outer surface
  double cap_height = 0.03;   // m, from the tip to the top
  double root_depth = 0.015;  // m, from the root face to the bottom (inside the hull)
};

// Throws std::invalid_argument naming the offending setting when the spec is unusable.
Grid fin_grid(const geometry::FinGeometry& fin, const FinGridSpec& spec);

// Rigid placement of a fin grid at a deflection (rad): rotation about the fin post.
Eigen::Isometry3d fin_placement(const geometry::FinGeometry& fin, double deflection);

}  // namespace auvloop::mesher
