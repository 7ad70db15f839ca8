// SPDX-License-Identifier: GPL-3.0-or-later
// The walls of a grid as triangles, for distance queries (the turbulence model's wall distance).
#pragma once

#include <vector>

#include "auvloop/geometry/triangle_distance.hpp"
#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

// The faces of the grid's wall patches as triangles about each face's point average (the
// decomposition compute_geometry uses), mapped by `to` from the grid's own frame (the identity: in
// that frame; g.placement: in the body frame).
std::vector<geometry::Triangle> wall_triangles(const Grid& g, const Eigen::Isometry3d& to);
// The same for the wall faces whose cell lies in [first_cell, end_cell) (one component of a
// composite grid).
std::vector<geometry::Triangle> wall_triangles(const Grid& g, const Eigen::Isometry3d& to,
                                               int first_cell, int end_cell);

}  // namespace auvloop::mesher
