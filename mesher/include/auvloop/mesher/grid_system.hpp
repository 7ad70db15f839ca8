// SPDX-License-Identifier: GPL-3.0-or-later
// The overset grid system of a vehicle: the hull grid, one grid per fin (placed at its
// deflection), and the background box, all in the body frame.
#pragma once

#include <vector>

#include "auvloop/geometry/fin.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/grid.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

namespace auvloop::mesher {

struct GridSystem {
  Grid hull;
  std::vector<Grid> fins;  // vehicle file order; placement = deflection
  std::vector<geometry::FinGeometry> fin_geometry;
  std::vector<double> fin_deflections;  // rad
  Grid background;

  // hull, fins..., background
  [[nodiscard]] std::vector<const Grid*> grids() const;
  [[nodiscard]] long long total_cells() const;
};

// Checks the settings (check_mesh_settings) and builds every grid; throws std::invalid_argument
// naming a bad setting.
GridSystem build_grid_system(const geometry::Vehicle& vehicle, const MeshSettings& settings);

// Turns the fin grids to new deflections (rad, one per fin): placements only, no points move.
void set_fin_deflections(GridSystem& system, const std::vector<double>& deflections);

}  // namespace auvloop::mesher
