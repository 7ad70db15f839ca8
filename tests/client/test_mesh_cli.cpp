// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop mesh` as a user runs it: files written, the report consistent with them, and bad
// settings refused with the setting named.
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

using auvloop::test::run_cli;
using ::testing::HasSubstr;

TEST(MeshCli, WritesGridsAndReport) {
  auvloop::test::TempDir tmp;
  const auto out = tmp.path() / "mesh";
  const auto r = run_cli("mesh --preset coarse --fin-deflection 30 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("upper_rudder"));
  EXPECT_THAT(r.output, HasSubstr("fringe fallback   orphan"));  // the table's columns
  for (const char* f : {"mesh.vtm", "hull.vtu", "hull.agrid", "background.vtu", "mesh-report.json",
                        "port_stern_plane.vtu"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  const auto report = nlohmann::json::parse(std::ifstream(out / "mesh-report.json"));
  long long total = 0;
  for (const auto& g : report["grids"]) total += g["cells"].get<long long>();
  EXPECT_EQ(report["total_cells"].get<long long>(), total);
  EXPECT_EQ(report["grids"].size(), 6U);  // hull, four fins, background
  EXPECT_DOUBLE_EQ(report["fin_deflections_deg"][0].get<double>(), 30.0);
  // The overset assembly ran: each component grid has fringe cells round its outer boundary,
  // and at 30 deg none takes a fallback donor (docs/mesher.md).
  for (const auto& g : report["grids"]) {
    EXPECT_GT(g["overset"]["fringe"].get<int>(), 0) << g["name"];
    EXPECT_EQ(g["overset"]["fallback"].get<int>(), 0) << g["name"];
  }
  std::ifstream vtm(out / "mesh.vtm");
  const std::string text((std::istreambuf_iterator<char>(vtm)), {});
  EXPECT_THAT(text, HasSubstr("file=\"upper_rudder.vtu\""));
}

TEST(MeshCli, RefusesBadSettings) {
  auvloop::test::TempDir tmp;
  auto r = run_cli("mesh --preset coarse --fin-deflection 40 --out " + tmp.path().string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("max_deflection"));
  const auto file = tmp.write("case.toml",
                              "vehicle = \"preset:remus100\"\n[mesh]\npreset = \"coarse\"\n"
                              "[mesh.hull]\nbody_cells = -5\n");
  r = run_cli("mesh " + file.string() + " --out " + (tmp.path() / "m").string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_THAT(r.output, HasSubstr("case.toml:5:1: mesh.hull.body_cells"));
  r = run_cli("mesh --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("--fin-deflection"));
  EXPECT_THAT(r.output, HasSubstr("Examples"));
}
