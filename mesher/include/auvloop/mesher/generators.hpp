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

// Hexahedral grid on the tensor product of the node lists (cell (i, j, k) has index
// i + nx (j + ny k)). Periodic sides pair up (x- with x+, ...).
Grid cartesian_box(const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<double>& z, const BoxPatches& patches = {},
                   const std::string& name = "box");

}  // namespace auvloop::mesher
