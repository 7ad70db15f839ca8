// SPDX-License-Identifier: GPL-3.0-or-later
// Grid output: OpenFOAM polyMesh (so a peer solver runs the very same grid) and VTK unstructured
// XML (.vtu, for ParaView) with cell fields. Files are written atomically.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

// Writes DIR/constant/polyMesh/{points,faces,owner,neighbour,boundary} (ASCII, FoamFile v2.0).
void write_openfoam_polymesh(const std::filesystem::path& case_dir, const Grid& g);

// Cells as VTK polyhedra (type 42) with the given cell fields (one value per cell, or three per
// cell for a vector field); points in the body frame. Throws std::invalid_argument otherwise.
void write_vtu(const std::filesystem::path& file, const Grid& g,
               const std::map<std::string, std::vector<double>>& cell_fields = {});

// A VTK multi-block file (.vtm) listing one .vtu per grid, so that ParaView opens the whole
// overset system at once: writes DIR/NAME.vtm and DIR/<grid name>.vtu with each grid's fields.
void write_vtm(const std::filesystem::path& dir, const std::string& name,
               const std::vector<const Grid*>& grids,
               const std::vector<std::map<std::string, std::vector<double>>>& cell_fields);

}  // namespace auvloop::mesher
