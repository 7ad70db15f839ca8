// SPDX-License-Identifier: GPL-3.0-or-later
// The `auvloop geometry` commands as a user runs them: the preset's published figures in the
// JSON, exports, and exit codes with clear messages for bad input.
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

using ::testing::HasSubstr;

namespace {
using auvloop::test::run_cli;
const auto& run = run_cli;
void expect_rel(const nlohmann::json& value, double reference) {
  EXPECT_NEAR(value.get<double>() / reference - 1, 0.0, 5e-3) << value << " vs " << reference;
}
}  // namespace

TEST(GeometryCli, InfoJsonHasThePublishedFigures) {
  const auto r = run("geometry info --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  const auto& h = j["hull"];
  expect_rel(h["length_m"], 1.3327);
  expect_rel(h["volume_m3"], 0.03166);
  expect_rel(h["frontal_area_m2"], 0.02865);
  expect_rel(h["projected_area_m2"], 0.2265);
  expect_rel(h["wetted_area_curved_m2"], 0.7195);
  expect_rel(h["centroid_from_nose_m"], 0.6058);
  EXPECT_NEAR(h["nose_face_radius_m"].get<double>(), 0.0388, 5e-5);
  EXPECT_NEAR(h["tail_face_radius_m"].get<double>(), 0.0162, 5e-5);
  EXPECT_EQ(j["fins"]["count"], 4);
  EXPECT_EQ(j["fins"]["section"], "NACA 0012");
  EXPECT_GT(j["triangulated"]["hull_and_fins"]["volume_m3"].get<double>(),
            h["volume_m3"].get<double>());
}

TEST(GeometryCli, ExportWritesTheRequestedFormat) {
  auvloop::test::TempDir dir;
  const auto out = dir.path() / "sub" / "remus.ply";
  const auto r = run("geometry export --rudder 15 --edge-length 0.01 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
  const auto c = run("geometry check --json " + out.string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_TRUE(nlohmann::json::parse(c.output)["ok"].get<bool>());
}

TEST(GeometryCli, BadVehicleFileExitsThreeWithFileAndLine) {
  auvloop::test::TempDir dir;
  const auto preset = run("geometry preset");
  ASSERT_EQ(preset.exit_code, 0);
  std::string text = preset.output;
  text.replace(text.find("span = 0.0857"), 13, "span = \"long\"");
  const auto path = dir.write("bad.toml", text);
  const auto r = run("geometry info " + path.string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr(path.string() + ":"));
  EXPECT_THAT(r.output, HasSubstr("fins.span: expected a number, got a string"));
}

TEST(GeometryCli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("geometry export").exit_code, 2);  // --out missing
  EXPECT_EQ(run("geometry export --out x.stl --rudder 5 --fin-deflection 1 2 3 4").exit_code, 2);
  EXPECT_EQ(run("geometry frobnicate").exit_code, 2);
  EXPECT_EQ(run("geometry info --edge-length -1").exit_code, 2);
}

TEST(GeometryCli, FailuresExitFour) {
  auvloop::test::TempDir dir;
  const auto r = run("geometry export --rudder 50 --out " + (dir.path() / "x.stl").string());
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_THAT(r.output, HasSubstr("exceeds the vehicle's max_deflection of 35 deg"));
  const auto empty = dir.write("empty.stl", "");
  EXPECT_EQ(run("geometry check " + empty.string()).exit_code, 4);
}

TEST(GeometryCli, HelpTeachesExitCodes) {
  const auto r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("Exit codes"));
  EXPECT_THAT(run("geometry export --help").output, HasSubstr("body frame"));
}
