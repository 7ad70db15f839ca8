// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh settings: presets, the [mesh] table of a case or vehicle file, and their validation.
//
// A preset fixes every count and the target y+ of the first cells; the first-cell heights follow
// from y+ at the design speed with a flat-plate skin-friction estimate (hull: Reynolds number on
// the hull length; fins: on the mean chord). Anything may be overridden in the file.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "auvloop/geometry/input.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/fin_grid.hpp"
#include "auvloop/mesher/generators.hpp"
#include "auvloop/mesher/hull_grid.hpp"

namespace auvloop::mesher {

struct MeshSettings {
  std::string preset;
  double design_speed = 1.54;            // m/s, REMUS 100 at 1500 rpm
  double kinematic_viscosity = 1.05e-6;  // m^2/s, sea water at 20 C (ITTC 2011 tables)
  double hull_yplus = 1;                 // target y+ of the first cell on the hull
  double fin_yplus = 1;                  // and on the fins
  HullGridSpec hull;
  FinGridSpec fin;
  BackgroundSpec background;
  std::vector<double> fin_deflections;  // rad, one per fin in file order (empty: all zero)
};

std::vector<std::string> mesh_preset_names();  // coarse, medium, fine
// The presets' revision: raised whenever a preset's grids change (counts, spacing, the grid
// generators). A CFD case names its mesh by preset, so the revision is part of its content hash:
// cached results and stored straight runs of an older grid are never taken for a newer one.
// 2: the rims rounded by a 5 mm fillet (session 33).
int mesh_preset_revision();
// The preset for a vehicle (first-cell heights from y+, background extents from the hull).
// Throws std::invalid_argument listing the presets when the name is unknown.
MeshSettings mesh_preset(std::string_view name, const geometry::Vehicle& vehicle);

// Wall distance of y+ at `speed` over a flat plate of `length`: turbulent skin friction
// Cf = 0.026 Re^(-1/7) (White, Fluid Mechanics, eq. 7.45), u_tau = U sqrt(Cf / 2), y = y+ nu /
// u_tau.
double flat_plate_wall_distance(double yplus, double speed, double nu, double length);
// The y+ of a first cell of height `height` under the same estimate (inverse of the above).
double flat_plate_yplus(double height, double speed, double nu, double length);

// Reads a [mesh] table (keys in docs/mesher.md) on top of its preset; problems go to the table's
// document with file:line:column. Calls mesh.finish(). A non-empty `preset` (from the command
// line) replaces the file's preset; the file's other settings still apply on top of it.
MeshSettings read_mesh_settings(input::Table mesh, const geometry::Vehicle& vehicle,
                                std::string_view preset = {});

// Every setting that shapes the grids (speed, viscosity, y+, the hull's, fins' and background's
// specs, the fin deflections), as compact JSON with sorted keys: equal settings give equal text.
// For content hashes (a CFD case's [mesh] table) and checkpoints.
std::string mesh_settings_json(const MeshSettings& s);

// Throws std::invalid_argument naming the setting (negative counts, a first cell taller than the
// hull radius, a deflection beyond the fin set's max_deflection, ...).
void check_mesh_settings(const MeshSettings& s, const geometry::Vehicle& vehicle);

}  // namespace auvloop::mesher
