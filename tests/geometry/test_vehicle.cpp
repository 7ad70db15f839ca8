// SPDX-License-Identifier: GPL-3.0-or-later
// The vehicle file: the remus100 preset carries the reference values, and bad files are rejected
// with file:line and the reason.
#include <cmath>
#include <numbers>
#include <regex>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "auvloop/geometry/vehicle.hpp"
#include "temp_dir.hpp"

using namespace auvloop::geometry;
using auvloop::input::InputError;
using ::testing::HasSubstr;

namespace {
constexpr double kDeg = std::numbers::pi / 180;

std::string preset_with(const std::string& from, const std::string& to) {
  std::string text(preset_text("remus100"));
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

std::string load_error(const std::string& text) {
  auvloop::test::TempDir dir;
  const auto path = dir.write("vehicle.toml", text);
  try {
    load_vehicle(path);
  } catch (const InputError& e) {
    return std::regex_replace(e.what(), std::regex(dir.path().string() + "/"), "");
  }
  return "";
}

int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}
}  // namespace

TEST(Vehicle, PresetMatchesPrestero) {
  const Vehicle v = preset_vehicle("remus100");
  EXPECT_EQ(v.name, "REMUS 100");
  EXPECT_DOUBLE_EQ(v.hull.a, 0.191);
  EXPECT_NEAR(v.hull.theta, 0.436, 1e-5);  // written as 24.981 deg
  EXPECT_EQ(v.fin_set.fins.size(), 4U);
  EXPECT_EQ(v.fin_set.section.thickness_percent, 12);
  EXPECT_NEAR(v.fin_set.root_radius(), 0.131 - 0.0857, 1e-15);
  EXPECT_NEAR(v.fin_set.post_station - v.mass.cb_station, 0.638,
              1e-12);  // Prestero: -0.638 m wrt CB
  EXPECT_NEAR(v.mass.weight(), 299.0, 0.05);
  EXPECT_DOUBLE_EQ(v.mass.inertia(2, 2), 3.45);
  EXPECT_DOUBLE_EQ(v.mass.cg_from_cb.z(), 0.0196);
}

TEST(Vehicle, RudderAndSternPlaneGainsFollowPrestero) {
  const Vehicle v = preset_vehicle("remus100");
  const auto& f = v.fin_set.fins;
  EXPECT_EQ(fin_deflection(f[0], 1.0, 0.0), -1.0);  // upper rudder
  EXPECT_EQ(fin_deflection(f[2], 1.0, 0.0), 1.0);   // lower rudder
  EXPECT_EQ(fin_deflection(f[1], 1.0, 0.0), 0.0);
  EXPECT_EQ(fin_deflection(f[1], 0.0, 1.0), 1.0);   // starboard stern plane
  EXPECT_EQ(fin_deflection(f[3], 0.0, 1.0), -1.0);  // port stern plane
}

TEST(Vehicle, UnknownKeyRejectedWithLine) {
  const auto text = preset_with("span = 0.0857", "span = 0.0857\nspam = 1");
  const auto e = load_error(text);
  EXPECT_THAT(
      e, HasSubstr(fmt::format("vehicle.toml:{}:1: fins.spam: unknown key (did you mean \"span\"?)",
                               line_of(text, "spam"))));
}

TEST(Vehicle, WrongTypeRejectedWithLine) {
  const auto text = preset_with("mass = 30.48", "mass = \"heavy\"");
  EXPECT_THAT(load_error(text),
              HasSubstr(fmt::format("vehicle.toml:{}:1: mass.mass: expected a number, got a string",
                                    line_of(text, "mass = \"heavy\""))));
}

TEST(Vehicle, OutOfRangeRejectedWithLineValueAndRange) {
  const auto text = preset_with("d = 0.191", "d = -0.191");
  EXPECT_THAT(load_error(text),
              HasSubstr(fmt::format(
                  "vehicle.toml:{}:1: hull.d: value -0.191 is out of range: must be > 0 m",
                  line_of(text, "d = -0.191"))));
  EXPECT_THAT(load_error(preset_with("max_deflection = 35", "max_deflection = 95")),
              HasSubstr("fins.max_deflection: value 95 is out of range: must be in [0, 90) deg"));
}

TEST(Vehicle, CrossFieldChecks) {
  EXPECT_THAT(load_error(preset_with("a_offset = 0.0165", "a_offset = 0.3")),
              HasSubstr("hull.a_offset: must be smaller than a = 0.191 m"));
  EXPECT_THAT(load_error(preset_with("[0.0, 0.0, 3.45]]", "[0.0, 0.0, 9.0]]")),
              HasSubstr("violate I3 <= I1 + I2"));
  EXPECT_THAT(load_error(preset_with("[0.0, 3.45, 0.0]", "[0.1, 3.45, 0.0]")),
              HasSubstr("mass.inertia: the inertia tensor must be symmetric"));
  EXPECT_THAT(load_error(preset_with("root_gap = 0.003", "root_gap = 0.09")),
              HasSubstr("fins.root_gap: the root face of fin \"upper_rudder\" (hull radius plus "
                        "root_gap) cannot be placed at its leading edge: the hull radius plus "
                        "root_gap reaches tip_radius there"));
  EXPECT_THAT(load_error(preset_with("root_gap = 0.003", "root_gap = 0")),
              HasSubstr("fins.root_gap: value 0 is out of range"));
  EXPECT_THAT(load_error(preset_with("hub_diameter = 0.0324", "hub_diameter = 0.2")),
              HasSubstr("propeller.hub_diameter: must be smaller than diameter"));
  EXPECT_THAT(load_error(preset_with("section = \"NACA 0012\"", "section = \"NACA 12\"")),
              HasSubstr("is not a NACA four-digit designation"));
  EXPECT_THAT(load_error(preset_with("roll = 180", "roll = 90")),
              HasSubstr("two fins have the same roll angle"));
  EXPECT_THAT(
      load_error(preset_with("J  = [0.00, 0.02, 0.04,", "J  = [0.00, 0.04, 0.04,")),
      HasSubstr("propeller.open_water.J: must increase strictly: entry 3 (0.04) follows 0.04"));
  EXPECT_THAT(load_error(preset_with("KQ = [0.017446, ", "KQ = [")),
              HasSubstr("J, KT and KQ must have as many entries (now 23, 23, 22)"));
}

// The preset's curve is the B-series B3-71.8 at P/D 0.5 with J scaled by 0.71: its points are
// the series' at J / 0.71 (engine::b_series checks the series against propeller.md's table).
TEST(Vehicle, PresetCarriesItsCalibratedOpenWaterCurve) {
  const auto v = preset_vehicle("remus100");
  const auto& w = v.propeller.open_water;
  ASSERT_EQ(w.J.size(), 23U);
  EXPECT_THAT(w.source, HasSubstr("calibrated to 1.54 m/s at 1500 rpm"));
  EXPECT_DOUBLE_EQ(w.KT[0], 0.18920);
  EXPECT_DOUBLE_EQ(w.J.back(), 0.44);
  EXPECT_DOUBLE_EQ(w.KQ.back(), 0.002790);
}

TEST(Vehicle, EveryProblemOfAFileIsReportedAtOnce) {
  auto text = preset_with("d = 0.191", "d = -1");
  text = text.replace(text.find("mass = 30.48"), 12, "mass = -3");
  const auto e = load_error(text);
  EXPECT_THAT(e, HasSubstr("hull.d"));
  EXPECT_THAT(e, HasSubstr("mass.mass"));
}

TEST(Vehicle, ResolveVehicleSpecs) {
  EXPECT_EQ(resolve_vehicle("").name, "REMUS 100");
  EXPECT_EQ(resolve_vehicle("preset:remus100").source, "preset:remus100");
  EXPECT_THROW(resolve_vehicle("preset:remus600"), std::invalid_argument);
  EXPECT_THROW(resolve_vehicle("/no/such/vehicle.toml"), InputError);
}

TEST(Naca, ParsesDesignations) {
  ASSERT_TRUE(NacaSection::parse("NACA 0012"));
  EXPECT_EQ(NacaSection::parse("naca0012")->thickness_percent, 12);
  EXPECT_EQ(NacaSection::parse("2412")->max_camber_percent, 2);
  EXPECT_EQ(NacaSection::parse("NACA 2412")->designation(), "NACA 2412");
  EXPECT_FALSE(NacaSection::parse("NACA 12"));
  EXPECT_FALSE(NacaSection::parse("NACA 0000"));
  EXPECT_FALSE(NacaSection::parse("NACA 2012"));  // camber without its position
}

TEST(Naca, ThicknessFormula) {
  // Abbott & von Doenhoff: y_t = 5 t (0.2969 sqrt(x) - 0.1260 x - 0.3516 x^2 + 0.2843 x^3 - 0.1015
  // x^4), maximum 0.5 t near x = 0.30; the sharp variant closes the trailing edge.
  NacaSection blunt = *NacaSection::parse("0012");
  blunt.sharp_trailing_edge = false;
  EXPECT_NEAR(blunt.half_thickness(0.3), 0.06002, 2e-5);
  EXPECT_NEAR(blunt.half_thickness(1.0), 0.00126, 1e-5);  // 0.126 % chord base
  const NacaSection sharp = *NacaSection::parse("0012");
  EXPECT_NEAR(sharp.half_thickness(1.0), 0.0, 1e-6);
  EXPECT_EQ(sharp.half_thickness(0.0), 0.0);
  // Leading-edge radius 1.1019 t^2: y_t ~ sqrt(2 r x) as x -> 0.
  const double x = 1e-8;
  EXPECT_NEAR(sharp.half_thickness(x) / std::sqrt(2 * 1.1019 * 0.12 * 0.12 * x), 1.0, 1e-3);
}
