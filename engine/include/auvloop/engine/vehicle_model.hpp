// SPDX-License-Identifier: GPL-3.0-or-later
// A vehicle file read in full: geometry, mass properties and the hydrodynamic-derivative model.
#pragma once

#include <string>
#include <string_view>

#include "auvloop/engine/prestero.hpp"
#include "auvloop/geometry/vehicle.hpp"

namespace auvloop::engine {

struct VehicleModel {
  geometry::Vehicle vehicle;
  PresteroCoefficients hydrodynamics;
};

// `spec` is a TOML path or preset:NAME (empty: preset:remus100). Throws input::InputError listing
// every problem of the file, or std::invalid_argument for an unknown preset.
VehicleModel load_vehicle_model(std::string_view spec);
// The same from a file's text (`source_name` appears in error messages).
VehicleModel parse_vehicle_model(std::string_view toml_text, const std::string& source_name);

}  // namespace auvloop::engine
