// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/vehicle_model.hpp"

#include <fmt/format.h>

namespace auvloop::engine {

namespace {
VehicleModel read_vehicle_model(input::Document& doc) {
  auto root = doc.root();
  VehicleModel m;
  m.vehicle = geometry::read_vehicle(root);
  m.hydrodynamics = read_prestero(root.table("hydrodynamics"));
  root.finish();
  if (m.vehicle.mass.inertia.isDiagonal(0.0) == false) {
    root.fail("mass",
              "Prestero's equations assume principal axes: the products of inertia must be 0");
  }
  doc.check();
  m.vehicle.source = doc.source_name();
  return m;
}
}  // namespace

VehicleModel load_vehicle_model(std::string_view spec) {
  const bool preset = spec.empty() || spec.starts_with("preset:");
  const std::string name = spec.empty() ? "remus100" : std::string(spec.substr(7));
  auto doc = preset ? input::Document::parse(geometry::preset_text(name), "preset:" + name)
                    : input::Document::load(std::filesystem::path(spec));
  return read_vehicle_model(doc);
}

VehicleModel parse_vehicle_model(std::string_view toml_text, const std::string& source_name) {
  auto doc = input::Document::parse(toml_text, source_name);
  return read_vehicle_model(doc);
}

}  // namespace auvloop::engine
