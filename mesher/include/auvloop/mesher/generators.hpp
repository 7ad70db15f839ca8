// SPDX-License-Identifier: GPL-3.0-or-later
// Simple structured grids for verification cases (cavity, periodic boxes, channels).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

// n + 1 nodes from a to b whose cell sizes grow geometrically by `ratio` (1: uniform). Symmetric
// grading (clustering at both ends) with `two_sided`.
std::vector<double> graded_nodes(double a, double b, int n, double ratio = 1.0,
                                 bool two_sided = false);

struct BoxPatches {
  // Names and types of the six sides: x-, x+, y-, y+, z-, z+.
  std::array<std::string, 6> names{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  std::array<PatchType, 6> types{PatchType::wall, PatchType::wall, PatchType::wall,
                                 PatchType::wall, PatchType::wall, PatchType::wall};
};

// Nodes from a to b whose first cell (at a) is `first` and whose cells grow geometrically by at
// most `max_ratio`; the ratio is solved so that the first cell is exactly `first`.
std::vector<double> grown_nodes(double a, double b, double first, double max_ratio);

// Nodes from 0 to `length`: cells from `first` growing by `growth`, but no larger than
// `band_size` until `band_end`, then growing freely (the last cell ends at `length` or beyond by
// less than half a cell, moved onto it). Resolves a thin gap beside a wall with uniform cells.
std::vector<double> banded_nodes(double length, double first, double growth, double band_size,
                                 double band_end);

// n cells from a to b, the first (at a) exactly `first`, sizes in geometric progression (the
// ratio, above or below one, is solved for). Throws std::invalid_argument when n < 1, b <= a or
// first is not in (0, b - a).
std::vector<double> stretched_nodes(double a, double b, double first, int n);

// n cells from a to b clustered towards both ends, the end cells `first` (at a) and `last` (at b):
// Vinokur's two-sided tanh stretching (J. Comput. Phys. 50, 1983), whose end slopes are corrected
// until the end cells match (to 1e-10 relative); neighbouring sizes change smoothly. Throws
// std::invalid_argument unless n >= 3, b > a and both end cells lie in (0, (b - a) / n) (finer than
// uniform: otherwise there is nothing to cluster), or if the correction does not converge.
std::vector<double> two_sided_nodes(double a, double b, int n, double first, double last);

// Nodes from -half to half through the uniform core [lo, hi] (cells of about h), growing by at
// most `growth` from the core's ends outwards (a background box round a body).
std::vector<double> cored_nodes(double half, double lo, double hi, double h, double growth);

// The background box of the overset system (issue 6): the paper's extents by default (inlet 3 L
// ahead of the bow, outlet 5 L behind the stern, 1.4 L from the axis to each side), uniform
// spacing `spacing` in a near-body region that also covers the propeller disk and `wake` behind
// the stern, and geometric growth (at most `growth`) from there to the outer boundary.
struct BackgroundSpec {
  double nose_x = 0;      // body x of the bow (m)
  double length = 0;      // hull length L (m)
  double radius = 0;      // largest distance of the body (fins included) from its axis (m)
  double ahead = 3.0;     // in L
  double behind = 5.0;    // in L
  double side = 1.4;      // in L
  double spacing = 0.02;  // m, near the body
  double margin = 0.05;   // m, near region beyond the body
  double wake = 0.5;      // in L: near-region extension behind the stern
  double growth = 1.15;   // maximum ratio of neighbouring cell sizes
};
Grid background_box(const BackgroundSpec& spec);

// Hexahedral grid on the tensor product of the node lists (cell (i, j, k) has index
// i + nx (j + ny k)). Periodic sides pair up (x- with x+, ...).
Grid cartesian_box(const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<double>& z, const BoxPatches& patches = {},
                   const std::string& name = "box");

}  // namespace auvloop::mesher
