// SPDX-License-Identifier: GPL-3.0-or-later
// The native binary grid format: an exact round trip, and clear errors for other versions,
// damaged and truncated files.
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/fin_grid.hpp"
#include "auvloop/mesher/grid_binary_io.hpp"
#include "temp_dir.hpp"

using namespace auvloop;
using namespace auvloop::mesher;
using ::testing::HasSubstr;

namespace {
Grid sample_grid() {
  const auto v = geometry::preset_vehicle("remus100");
  const geometry::FinGeometry fin(v.fin_set, v.fin_set.fins[1], geometry::MyringProfile(v.hull),
                                  v.mass.cb_station);
  FinGridSpec s;
  s.chordwise_cells = 6;
  s.normal_cells = 4;
  s.span_cells = 4;
  s.cap_cells = 2;
  s.gap_cells = 1;
  s.trailing_edge_fan = 3;
  Grid g = fin_grid(fin, s);
  g.placement = fin_placement(fin, 0.3);
  g.zones.push_back({"some_cells", {0, 5, 7}});
  return g;
}

std::string bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string read_error(const std::filesystem::path& p) {
  try {
    (void)read_grid_binary(p);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST(GridBinaryIo, RoundTripIsExact) {
  const Grid g = sample_grid();
  test::TempDir tmp;
  const auto file = tmp.path() / "fin.agrid";
  write_grid_binary(file, g);
  const Grid r = read_grid_binary(file);
  EXPECT_EQ(r.name, g.name);
  EXPECT_EQ(r.points, g.points);  // bit-exact doubles
  EXPECT_EQ(r.face_offsets, g.face_offsets);
  EXPECT_EQ(r.face_points, g.face_points);
  EXPECT_EQ(r.owner, g.owner);
  EXPECT_EQ(r.neighbour, g.neighbour);
  EXPECT_EQ(r.cells, g.cells);
  ASSERT_EQ(r.patches.size(), g.patches.size());
  for (std::size_t i = 0; i < g.patches.size(); ++i) {
    EXPECT_EQ(r.patches[i].name, g.patches[i].name);
    EXPECT_EQ(r.patches[i].type, g.patches[i].type);
    EXPECT_EQ(r.patches[i].start, g.patches[i].start);
    EXPECT_EQ(r.patches[i].size, g.patches[i].size);
  }
  ASSERT_EQ(r.zones.size(), 1U);
  EXPECT_EQ(r.zones[0].cells, g.zones[0].cells);
  EXPECT_EQ(r.placement.matrix(), g.placement.matrix());
}

TEST(GridBinaryIo, RejectsOtherVersionsAndDamage) {
  test::TempDir tmp;
  const auto file = tmp.path() / "fin.agrid";
  write_grid_binary(file, sample_grid());
  const std::string good = bytes(file);
  std::string newer = good;
  const std::uint32_t v2 = kGridFormatVersion + 1;
  std::memcpy(newer.data() + 8, &v2, sizeof v2);
  EXPECT_THAT(read_error(tmp.write("newer.agrid", newer)),
              HasSubstr("format version 2 (this build reads version 1)"));
  EXPECT_THAT(read_error(tmp.write("short.agrid", good.substr(0, good.size() / 2))),
              HasSubstr("truncated"));
  EXPECT_THAT(read_error(tmp.write("other.agrid", "P3\n1 1\n")), HasSubstr("AUVLGRID"));
  EXPECT_THAT(read_error(tmp.path() / "missing.agrid"), HasSubstr("missing.agrid"));
}
