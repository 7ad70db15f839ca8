// SPDX-License-Identifier: GPL-3.0-or-later
// Mesh settings: the flat-plate first-cell estimate against a hand calculation, presets, the
// [mesh] table with located errors, and checks that name the bad setting.
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "auvloop/geometry/input.hpp"
#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/grid_system.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

using namespace auvloop;
using namespace auvloop::mesher;
using ::testing::HasSubstr;

namespace {
const geometry::Vehicle& remus() {
  static const geometry::Vehicle v = geometry::preset_vehicle("remus100");
  return v;
}

MeshSettings parse(const std::string& text) {
  auto doc = input::Document::parse(text, "case.toml");
  MeshSettings s = read_mesh_settings(doc.root().table("mesh"), remus());
  doc.check();
  return s;
}

std::string parse_error(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const input::InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

// Hand calculation (Python, independent of this code): U = 1.54 m/s, L = 1.3327 m,
// nu = 1.05e-6 m^2/s: Re = 1.954627e6, Cf = 0.026 Re^(-1/7) = 3.282842e-3,
// u_tau = U sqrt(Cf / 2) = 0.0623937 m/s, y(y+ = 1) = nu / u_tau = 1.682901e-5 m.
TEST(MeshSettings, FlatPlateFirstCellMatchesAHandCalculation) {
  EXPECT_NEAR(flat_plate_wall_distance(1, 1.54, 1.05e-6, 1.3327), 1.682901e-5, 1e-11);
  EXPECT_NEAR(flat_plate_wall_distance(30, 1.54, 1.05e-6, 1.3327), 30 * 1.682901e-5, 3e-10);
  EXPECT_NEAR(flat_plate_yplus(1.682901e-5 * 7, 1.54, 1.05e-6, 1.3327), 7.0, 1e-5);
}

TEST(MeshSettings, PresetsSetFirstCellsFromYPlus) {
  const double L = geometry::MyringProfile(remus().hull).length();
  for (const auto& name : mesh_preset_names()) {
    const MeshSettings s = mesh_preset(name, remus());
    EXPECT_NEAR(flat_plate_yplus(s.hull.first_cell, s.design_speed, s.kinematic_viscosity, L),
                s.hull_yplus, 1e-9);
    EXPECT_NO_THROW(check_mesh_settings(s, remus()));
  }
  EXPECT_THROW(mesh_preset("huge", remus()), std::invalid_argument);
}

TEST(MeshSettings, FileOverridesThePreset) {
  const MeshSettings s = parse(
      "[mesh]\npreset = \"coarse\"\nhull_yplus = 2\n"
      "fin_deflections = [10, -10, 0, 35]\n"
      "[mesh.hull]\nbody_cells = 33\nrim_radius = 0\n[mesh.fin]\nfirst_cell = 1e-4\n"
      "[mesh.background]\nspacing = 0.07\n");
  EXPECT_EQ(s.preset, "coarse");
  EXPECT_EQ(s.hull.body_cells, 33);
  EXPECT_EQ(mesh_preset("coarse", remus()).hull.rim_radius, 0.005);  // every preset's fillet
  EXPECT_EQ(s.hull.rim_radius, 0.0);                                 // the sharp rims again
  EXPECT_EQ(s.hull.circumferential, mesh_preset("coarse", remus()).hull.circumferential);
  const double L = geometry::MyringProfile(remus().hull).length();
  EXPECT_NEAR(flat_plate_yplus(s.hull.first_cell, s.design_speed, s.kinematic_viscosity, L), 2,
              1e-9);
  EXPECT_DOUBLE_EQ(s.fin.first_cell, 1e-4);
  EXPECT_DOUBLE_EQ(s.background.spacing, 0.07);
  ASSERT_EQ(s.fin_deflections.size(), 4U);
  EXPECT_NEAR(s.fin_deflections[3], 35 * std::numbers::pi / 180, 1e-15);
}

TEST(MeshSettings, BadSettingsAreLocatedAndNamed) {
  EXPECT_THAT(parse_error("[mesh]\n[mesh.hull]\nbody_cells = -4\n"),
              HasSubstr("case.toml:3:1: mesh.hull.body_cells"));
  EXPECT_THAT(parse_error("[mesh]\nfin_deflections = [0, 0, 40, 0]\n"),
              HasSubstr("mesh.fin_deflections"));
  EXPECT_THAT(parse_error("[mesh]\n[mesh.hull]\ncircumferential = 30\n"),
              HasSubstr("not a multiple of 4"));
  EXPECT_THAT(parse_error("[mesh]\npreset = \"medum\"\n"), HasSubstr("mesh.preset"));
  EXPECT_THAT(parse_error("[mesh]\n[mesh.fin]\nspan_cels = 3\n"), HasSubstr("span_cells"));
  EXPECT_THAT(parse_error("[mesh]\n[mesh.hull]\nrim_radius = -0.001\n"),
              HasSubstr("case.toml:3:1: mesh.hull.rim_radius"));
  // Checks that need the vehicle: a first cell taller than the hull, a deflection past the limit.
  MeshSettings s = mesh_preset("coarse", remus());
  s.hull.first_cell = 0.2;
  EXPECT_THAT(
      [&] {
        try {
          check_mesh_settings(s, remus());
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      }(),
      HasSubstr("hull.first_cell (0.2 m) must be smaller than the hull radius"));
  s = mesh_preset("coarse", remus());
  s.fin_deflections = {0, 0, 0.7, 0};  // 40 deg
  EXPECT_THROW(build_grid_system(remus(), s), std::invalid_argument);
}
