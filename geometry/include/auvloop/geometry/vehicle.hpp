// SPDX-License-Identifier: GPL-3.0-or-later
// The vehicle description: hull, fin set, mass properties and propeller, read from a TOML file
// (format in docs/vehicle-file.md) or from a built-in preset.
//
// Frames. Hull positions along the axis are *stations*: metres aft of the (truncated) nose tip, the
// coordinate of the Myring formulas. 3D geometry is built in the body frame of Fossen / SNAME:
// origin at the centre of buoyancy (CB), x forward, y starboard, z down; x_body = cb_station -
// station. Angles are radians here; users write degrees in the file.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "auvloop/geometry/input.hpp"
#include "auvloop/geometry/naca.hpp"

namespace auvloop::geometry {

// Myring body of revolution (Myring 1976; Prestero 2001 Table 2.1; the paper's Table 1). Lengths m.
struct MyringParameters {
  double a = 0;         // nose length of the full (untruncated) nose
  double a_offset = 0;  // length cut off the nose tip (leaves a flat nose face)
  double b = 0;         // parallel mid-body length
  double c = 0;         // tail length of the full tail
  double c_offset = 0;  // length cut off the tail end (leaves a flat tail face)
  double d = 0;         // maximum diameter
  double n = 0;         // nose shape exponent (-)
  double theta = 0;     // tail semi-angle (rad)
};

struct FinPlacement {
  std::string name;
  // Roll angle of the fin about the body x axis (rad): 0 points up (-z), pi/2 starboard (+y),
  // pi down (+z), 3pi/2 port (-y).
  double roll = 0;
};

struct FinSetParameters {
  std::vector<FinPlacement> fins;
  NacaSection section;
  double root_chord = 0;       // m, chord at the exposed root station
  double tip_chord = 0;        // m
  double span = 0;             // m, exposed span from root station to tip
  double sweep = 0;            // rad, leading-edge sweep (positive: tip leading edge further aft)
  double root_le_station = 0;  // m aft of nose: leading edge at the root station
  double tip_radius = 0;       // m, distance of the fin tip from the hull axis
  double post_station = 0;     // m aft of nose: the fin post (axis of deflection, radial)
  // m, radial clearance between the fin root and the hull along the chord line at zero deflection
  // (the paper's rudder-hull gap; it changes as the fin turns, docs/vehicle-file.md)
  double root_gap = 0;
  double max_deflection = 0;  // rad, mechanical limit (magnitude)

  [[nodiscard]] double root_radius() const { return tip_radius - span; }
};

struct MassProperties {
  double mass = 0;                                       // kg
  double buoyancy = 0;                                   // N
  double gravity = 0;                                    // m/s^2
  double cb_station = 0;                                 // m aft of nose: origin of the body frame
  Eigen::Vector3d cg_from_cb = Eigen::Vector3d::Zero();  // m, body axes
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();     // kg m^2 about CB, body axes (tensor)
  double water_density = 0;                              // kg/m^3

  [[nodiscard]] double weight() const { return mass * gravity; }  // N
};

// The propeller's open-water curve: KT and KQ at advance ratios J (strictly increasing, at least
// two), with where the numbers come from. Empty when the file gives none.
struct OpenWaterCurve {
  std::string source;
  std::vector<double> J, KT, KQ;
  [[nodiscard]] bool empty() const { return J.empty(); }
};

struct PropellerParameters {
  double diameter = 0;        // m
  double hub_diameter = 0;    // m
  double station = 0;         // m aft of nose: centre of the actuator disk
  double disk_thickness = 0;  // m, axial extent of the body-force disk
  OpenWaterCurve open_water;  // [propeller.open_water]
};

struct Vehicle {
  std::string name;
  std::string description;
  std::string source;  // file path or "preset:NAME"
  MyringParameters hull;
  FinSetParameters fin_set;
  MassProperties mass;
  PropellerParameters propeller;
};

// Reads the vehicle tables from `root`, recording problems in its document. Unknown keys in the
// tables it owns are reported; it does not call root.finish(), so that other modules (e.g. the
// hydrodynamic-derivative plant) can read further tables of the same file.
Vehicle read_vehicle(input::Table root);
// Parses a whole vehicle file (unknown top-level keys are errors); throws input::InputError.
Vehicle load_vehicle(const std::filesystem::path& path);
Vehicle parse_vehicle(std::string_view toml_text, const std::string& source_name);

// Built-in presets, shipped inside the binary as the TOML files under geometry/presets/.
std::vector<std::string> preset_names();
std::string_view preset_text(std::string_view name);  // throws std::invalid_argument if unknown
Vehicle preset_vehicle(std::string_view name);
// A path to a TOML file, or "preset:NAME"; an empty spec gives the default preset (remus100).
Vehicle resolve_vehicle(std::string_view spec);

// Deflection of one fin (rad, right-handed about its outward post axis) produced by a rudder angle
// delta_r and a stern-plane angle delta_s in Prestero's sign convention (delta_r > 0: trailing
// edges to port; delta_s > 0: trailing edges down). For a cruciform set the gains are 0 or +-1; for
// an X-tail they mix both.
double fin_deflection(const FinPlacement& fin, double delta_r, double delta_s);

}  // namespace auvloop::geometry
