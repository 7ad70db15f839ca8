// SPDX-License-Identifier: GPL-3.0-or-later
// Body-fitted grid of a circular cylinder in a 2D channel (one cell thick, empty sides), as the
// Schaefer-Turek DFG benchmark needs: an O-grid from the cylinder to a square box around it (four
// blocks, radial lines straight, cells graded towards the wall), Cartesian blocks from the box to
// the channel's inlet and walls with about the box side's spacing, and a Cartesian block from the
// box to the outlet. The O-grid's corners (where its lines kink) lie inside the flow, not on the
// channel's walls: there its cells would be 45-degree rhombi with non-orthogonal wall faces.
// Patches: inlet (x = 0), outlet (x = length), walls (channel bottom and top), cylinder, front and
// back (empty).
#pragma once

#include <memory>

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "auvloop/geometry/surface_fwd.hpp"
#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

struct CylinderChannelSpec {
  double length = 2.2;  // channel [0, length] x [0, height]
  double height = 0.41;
  double cx = 0.2, cy = 0.2;  // cylinder centre
  double radius = 0.05;
  double box_half_width = 0.1;    // the O-grid's square box spans c -/+ this in x and y
  int cells_per_side = 32;        // cells along each side of the box (4 x around the cylinder)
  int radial_cells = 16;          // from the cylinder to the box
  double radial_ratio = 4.0;      // outermost / innermost radial cell size
  int downstream_cells = 80;      // from the rectangle to the outlet
  double downstream_ratio = 6.0;  // last / first cell size downstream
  double thickness = 0.01;        // z extent of the one-cell-thick grid
};

Grid cylinder_channel(const CylinderChannelSpec& spec, const std::string& name = "cylinder");

// The same channel and cylinder as an overset pair (issue 17's schaefer-turek-*-overset cases):
//   - "cylinder": an O-grid from the cylinder (patch "cylinder", wall) to the circle of
//     outer_radius (patch "outer", overset), `around` cells round it, `radial_cells` graded
//     outermost / innermost = radial_ratio; front and back empty;
//   - "background": the channel, Cartesian, uniform cells of about `spacing` (0: the O-grid's
//     outer tangential cell size, 2 pi outer_radius / around) up to x = near_end, then
//     `downstream_cells` growing to the outlet; patches inlet, outlet, bottom and top (walls),
//     front and back (empty), and no cylinder: the assembly cuts it out;
//   - the cylinder's solid for the assembly's hole cutting, longer than the grids are thick.
// Throws std::invalid_argument when the O-grid does not fit in the channel with a cell to spare.
struct CylinderOversetSpec {
  double length = 2.2, height = 0.41;
  double cx = 0.2, cy = 0.2, radius = 0.05;
  double outer_radius = 0.15;
  int around = 64;
  int radial_cells = 16;
  double radial_ratio = 4.0;
  double spacing = 0;
  double near_end = 0.5;
  int downstream_cells = 40;
  double thickness = 0.01;
};

struct CylinderOverset {
  Grid cylinder, background;
  std::shared_ptr<const geometry::SurfaceMesh> solid;  // in the cylinder grid's frame
};

CylinderOverset cylinder_overset(const CylinderOversetSpec& spec);

// The unconfined cylinder (issue 17's galilean-cylinder; validation-data.md section 3 asks for a
// domain at least 30 D across): the same O-grid round a cylinder of `diameter` centred at the
// origin, out to outer_radius diameters, over a square background `extent` diameters across
// centred on it, whose cells are uniform (the O-grid's outer tangential size) in the core
// [-core_upstream, core_downstream] x [-core_side, core_side] diameters and grow by at most
// `growth` per cell from there to the sides. Patches of the background: west, east, south,
// north (for a far field: Pimple::far_field) and front, back (empty); the O-grid's as in
// cylinder_overset. Throws std::invalid_argument when the O-grid does not fit in the core.
struct UnconfinedCylinderSpec {
  double diameter = 1.0;
  double outer_radius = 1.5;  // in diameters
  int around = 64;
  int radial_cells = 32;
  double radial_ratio = 8.0;
  double extent = 40.0;                                                // in diameters
  double core_upstream = 2.0, core_downstream = 6.0, core_side = 2.0;  // in diameters
  double growth = 1.1;
  double thickness = 0.1;  // in diameters
};
CylinderOverset unconfined_cylinder_overset(const UnconfinedCylinderSpec& spec);

// Face-addressed grid from hexahedra given by eight point indices each (VTK/OpenFOAM hex order:
// bottom quad 0-1-2-3 counter-clockwise seen from above, top quad 4-5-6-7 above it). Shared faces
// become internal faces (owner < neighbour, upper-triangular order); boundary faces are grouped
// into patches by `patch_of(face centre)` returning an index into `patches`.
Grid hex_grid(std::vector<Eigen::Vector3d> points, const std::vector<std::array<int, 8>>& hexes,
              std::vector<Patch> patches,
              const std::function<int(const Eigen::Vector3d&)>& patch_of, const std::string& name);

}  // namespace auvloop::mesher
