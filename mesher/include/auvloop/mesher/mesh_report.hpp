// SPDX-License-Identifier: GPL-3.0-or-later
// The mesh report: per grid, the counts, quality figures and the estimated y+ of the first cells,
// and (once assembled) the overset status counts; as a printed table and as JSON
// (mesh-report.json).
#pragma once

#include <string>
#include <vector>

#include "auvloop/mesher/grid.hpp"
#include "auvloop/mesher/grid_system.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

namespace auvloop::mesher {

struct OversetCounts {
  int active = 0, fringe = 0, hole = 0, orphan = 0;
  // Fringe cells with fallback donors: no active cell of another grid contains their centre, so
  // their stencils extrapolate (GridAssembly::fallback).
  int fallback = 0;
};

struct GridReport {
  std::string name;
  GridQuality quality;
  int wall_faces = 0;
  double first_cell_min = 0, first_cell_max = 0;  // m, twice the centre-to-wall distance
  double yplus_min = 0, yplus_max = 0;            // flat-plate estimate at the design speed
  bool assembled = false;                         // overset counts below are meaningful
  OversetCounts overset;
};

struct MeshReport {
  std::string preset;
  double design_speed = 0, kinematic_viscosity = 0;
  std::vector<double> fin_deflections;  // rad
  std::vector<GridReport> grids;
  [[nodiscard]] long long total_cells() const;
};

// Quality and first-cell y+ of every grid (reference lengths: hull length for the hull, mean
// chord for fins). Overset counts are filled in by the assembly.
MeshReport mesh_report(const GridSystem& sys, const MeshSettings& s, const geometry::Vehicle& v);

// Largest non-orthogonality (deg) of each cell's faces: a VTK field that shows where it is bad.
std::vector<double> cell_non_orthogonality(const Grid& g, const GridGeometry& geo);

std::string report_table(const MeshReport& r);
std::string report_json(const MeshReport& r);  // pretty-printed

}  // namespace auvloop::mesher
