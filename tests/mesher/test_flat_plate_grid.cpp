// SPDX-License-Identifier: GPL-3.0-or-later
// The flat-plate grid family of the TMR's 2DZP case: valid cells, the patches where the case
// needs them (the plate exactly on 0 <= x <= L at y = 0, the symmetry plane ahead of it), the
// first cells of the spec, and nesting (each level every other node of the finer one).
#include <cmath>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "auvloop/mesher/flat_plate_grid.hpp"

using namespace auvloop::mesher;

namespace {
const Patch& patch(const Grid& g, const std::string& name) {
  for (const auto& p : g.patches)
    if (p.name == name) return p;
  throw std::runtime_error("no patch " + name);
}
}  // namespace

TEST(FlatPlateGrid, PatchesCellsAndFirstCellsAreThoseOfTheSpec) {
  FlatPlateSpec spec;
  spec.plate_cells = 64;
  spec.upstream_cells = 16;
  spec.normal_cells = 48;
  for (int level = 0; level <= 2; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    const Grid g = flat_plate(spec, level);
    const auto geo = compute_geometry(g);
    EXPECT_NO_THROW(validate(g, geo));
    const int s = 1 << level;
    EXPECT_EQ(g.cells, (spec.plate_cells + spec.upstream_cells) / s * (spec.normal_cells / s));
    std::vector<std::string> names;
    for (const auto& p : g.patches) names.push_back(p.name);
    EXPECT_EQ(names, (std::vector<std::string>{"inlet", "outlet", "symmetry", "plate", "top",
                                               "front", "back"}));
    const Patch& plate = patch(g, "plate");
    EXPECT_EQ(plate.type, PatchType::wall);
    EXPECT_EQ(plate.size, spec.plate_cells / s);
    double area = 0;
    for (int f = plate.start; f < plate.start + plate.size; ++f) {
      const auto& c = geo.face_centre[static_cast<std::size_t>(f)];
      EXPECT_GT(c.x(), 0);
      EXPECT_LT(c.x(), spec.plate_length);
      EXPECT_EQ(c.y(), 0.0);
      area += geo.face_area[static_cast<std::size_t>(f)].norm();
    }
    EXPECT_NEAR(area, spec.plate_length * spec.thickness, 1e-12);
    const Patch& sym = patch(g, "symmetry");
    EXPECT_EQ(sym.type, PatchType::symmetry);
    for (int f = sym.start; f < sym.start + sym.size; ++f)
      EXPECT_LT(geo.face_centre[static_cast<std::size_t>(f)].x(), 0);
    EXPECT_EQ(patch(g, "top").type, PatchType::outlet);
  }
  // The finest level's first cells: wall-normal first_height, streamwise leading_edge_dx both
  // ways from x = 0 (node coordinates, from the points of the first plate face).
  const Grid g = flat_plate(spec, 0);
  double y1 = 1e300, dx_plate = 1e300, dx_ahead = 1e300;
  for (const auto& p : g.points) {
    if (p.y() > 0) y1 = std::min(y1, p.y());
    if (p.x() > 0) dx_plate = std::min(dx_plate, p.x());
    if (p.x() < 0) dx_ahead = std::min(dx_ahead, -p.x());
  }
  EXPECT_NEAR(y1, spec.first_height, 1e-12 * spec.first_height);
  EXPECT_NEAR(dx_plate, spec.leading_edge_dx, 1e-12 * spec.leading_edge_dx);
  EXPECT_NEAR(dx_ahead, spec.leading_edge_dx, 1e-12 * spec.leading_edge_dx);
}

TEST(FlatPlateGrid, EachLevelIsEveryOtherNodeOfTheFinerOne) {
  FlatPlateSpec spec;
  spec.plate_cells = 32;
  spec.upstream_cells = 8;
  spec.normal_cells = 16;
  const auto nodes = [](const Grid& g) {
    std::set<std::pair<double, double>> xy;
    for (const auto& p : g.points) xy.insert({p.x(), p.y()});
    return xy;
  };
  const auto fine = nodes(flat_plate(spec, 0)), coarse = nodes(flat_plate(spec, 1));
  EXPECT_EQ(coarse.size(), (32 / 2 + 8 / 2 + 1) * (16 / 2 + 1));
  for (const auto& xy : coarse) EXPECT_TRUE(fine.contains(xy)) << xy.first << " " << xy.second;
}

TEST(FlatPlateGrid, BadSettingsAreNamed) {
  FlatPlateSpec spec;
  spec.plate_cells = 30;
  try {
    (void)flat_plate(spec, 2);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("plate_cells"), std::string::npos) << e.what();
  }
  spec = FlatPlateSpec{};
  spec.first_height = 2.0;  // above the domain's height
  EXPECT_THROW((void)flat_plate(spec), std::invalid_argument);
  spec = FlatPlateSpec{};
  spec.height = 0;
  EXPECT_THROW((void)flat_plate(spec), std::invalid_argument);
}
