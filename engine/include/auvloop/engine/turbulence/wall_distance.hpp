// SPDX-License-Identifier: GPL-3.0-or-later
// Wall distance for the turbulence model (SST's blending functions F1 and F2, the wall
// treatment's y+): for every cell centre of a grid, the distance to the nearest wall face of the
// whole grid system, so that the cells of a fin grid see the hull and the other fins as well as
// their own fin, and the background's cells every body.
//   1. walls: the faces of every wall patch of every grid, split into triangles about each face's
//      point average (the decomposition of the face geometry), in the body frame
//      (mesher::wall_triangles), in a CGAL AABB tree (geometry::TriangleDistance): once per
//      relative placement of the grids;
//   2. per cell: the distance from its centre, placed in the body frame, to the nearest triangle:
//      exact for the walls as the grids discretise them (a cell at a curved wall sees the chords,
//      as its face fluxes do). In parallel over cells; every query is independent, so the result
//      does not depend on the number of threads.
#pragma once

#include <span>
#include <vector>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/geometry/triangle_distance.hpp"
#include "auvloop/mesher/wall_triangles.hpp"

namespace auvloop::engine::turbulence {

// Step 1. Throws std::invalid_argument naming the grids when none of them has a wall patch face.
geometry::TriangleDistance wall_surface(std::span<const mesher::Grid* const> grids);

// Step 2: the distance of each cell centre of `mesh` (its grid's placement applied) to `walls`
// (m), one per cell.
std::vector<double> wall_distance(const fv::Mesh& mesh, const geometry::TriangleDistance& walls);

}  // namespace auvloop::engine::turbulence
