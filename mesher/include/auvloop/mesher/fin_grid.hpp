// SPDX-License-Identifier: GPL-3.0-or-later
// The body-fitted grid of one fin (docs/mesher.md).
//
// Topology: an O-grid around the NACA section (index p round the section, j outward along
// straight wall-normal lines to `extent`; a fan of lines round a sharp trailing edge), stacked
// along the fin post from inside the hull (the fin solid's inner end) to `cap_height` beyond the
// tip. Above the tip the section's interior is filled by a column of chordwise strips joining
// matching upper and lower points (triangular prisms at the leading and sharp trailing edges),
// whose bottom faces are the flat tip: the tip is a wall of this grid, not a staircase left by hole
// cutting. Wall points lie on the analytic section at every span station, including the root
// station where taper and sweep begin. Patches: "<fin>" (wall: sides and tip) and "<fin>_overset"
// (outer surface, inner end inside the hull, top). The grid is built at zero deflection in the body
// frame; a deflection is a placement.
#pragma once

#include "auvloop/geometry/fin.hpp"
#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

struct FinGridSpec {
  int chordwise_cells = 16;   // per side, leading to trailing edge (cosine spacing)
  int normal_cells = 0;       // wall to outer surface; 0: the fewest that keep `growth`
  int embedded_cells = 3;     // along the post from the inner end (inside the hull) to the root
  int span_cells = 12;        // root station to tip, clustered towards the tip
  int cap_cells = 0;          // tip to top; 0: the fewest that keep `growth`
  int trailing_edge_fan = 8;  // lines fanning out of a sharp trailing edge (upper to lower normal)
  double first_cell = 2e-4;   // m, first cell height at the sides and on the tip
  double growth = 1.2;        // largest ratio of neighbouring sizes (normal_cells, cap_cells 0)
  double extent = 0.03;       // m, from the section to the outer surface
  double cap_height = 0.03;   // m, from the tip to the top
};

// Throws std::invalid_argument naming the offending setting when the spec is unusable.
Grid fin_grid(const geometry::FinGeometry& fin, const FinGridSpec& spec);

// Rigid placement of a fin grid at a deflection (rad): rotation about the fin post.
Eigen::Isometry3d fin_placement(const geometry::FinGeometry& fin, double deflection);

}  // namespace auvloop::mesher
