// SPDX-License-Identifier: GPL-3.0-or-later
// Surface files through assimp: round trips in every format, and clear errors for broken files.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "auvloop/geometry/error.hpp"
#include "auvloop/geometry/surface_io.hpp"
#include "temp_dir.hpp"

using namespace auvloop::geometry;
using ::testing::HasSubstr;

namespace {
const std::vector<SurfacePart>& remus_union() {
  static const std::vector<SurfacePart> parts = [] {
    const auto v = preset_vehicle("remus100");
    const std::vector<double> d{-0.3, 0.1, 0.3, -0.1};
    return std::vector<SurfacePart>{{"vehicle", merge_parts(vehicle_parts(v, d, {0.01}))}};
  }();
  return parts;
}

std::string read_error(const std::filesystem::path& path, SurfaceReadOptions options = {}) {
  try {
    read_surface(path, options);
  } catch (const GeometryError& e) {
    return e.what();
  }
  return "";
}

// A tetrahedron of 0.5 m edges as ASCII STL; faces listed outward-oriented unless changed.
struct Tetra {
  std::vector<std::array<int, 3>> faces{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  double size = 0.5;
  std::string stl() const {
    const double p[4][3] = {{0, 0, 0}, {size, 0, 0}, {0, size, 0}, {0, 0, size}};
    std::string s = "solid t\n";
    for (const auto& f : faces) {
      s += "facet normal 0 0 0\nouter loop\n";
      for (int i : f) s += fmt::format("vertex {} {} {}\n", p[i][0], p[i][1], p[i][2]);
      s += "endloop\nendfacet\n";
    }
    return s + "endsolid t\n";
  }
};
}  // namespace

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, PreservesVolumeAndArea) {
  auvloop::test::TempDir dir;
  const auto path = dir.path() / ("vehicle" + GetParam());
  write_surface(path, remus_union());
  const auto back = read_surface(path);
  ASSERT_EQ(back.size(), 1U);
  const auto a = measure(remus_union().front().mesh), b = measure(back.front().mesh);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_NEAR(b.volume / a.volume - 1, 0.0, 1e-6);
  EXPECT_NEAR(b.area / a.area - 1, 0.0, 1e-6);
  // Atomic write: nothing but the output (and a .gltf's buffer) is left in the directory.
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const auto name = entry.path().filename().string();
    EXPECT_TRUE(name == path.filename().string() || name == "vehicle.bin") << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip,
                         ::testing::Values(".stl", ".obj", ".ply", ".gltf", ".glb"),
                         [](const auto& param_info) { return param_info.param.substr(1); });

TEST(SurfaceIo, PartsKeepTheirNames) {
  auvloop::test::TempDir dir;
  const auto v = preset_vehicle("remus100");
  const auto parts = vehicle_parts(v, {}, {0.02});
  write_surface(dir.path() / "parts.glb", parts);
  const auto back = read_surface(dir.path() / "parts.glb");
  ASSERT_EQ(back.size(), parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) EXPECT_EQ(back[i].name, parts[i].name);
}

TEST(SurfaceIo, AValidTetrahedronReads) {
  auvloop::test::TempDir dir;
  const auto parts = read_surface(dir.write("t.stl", Tetra{}.stl()));
  EXPECT_NEAR(measure(parts.at(0).mesh).volume, 0.125 / 6, 1e-12);
}

TEST(SurfaceIo, OpenSurfaceIsReported) {
  auvloop::test::TempDir dir;
  Tetra t;
  t.faces.pop_back();
  EXPECT_THAT(read_error(dir.write("open.stl", t.stl())),
              HasSubstr("the surface is open: 3 boundary edges"));
}

TEST(SurfaceIo, InconsistentOrientationIsReported) {
  auvloop::test::TempDir dir;
  Tetra t;
  std::swap(t.faces[3][1], t.faces[3][2]);
  EXPECT_THAT(read_error(dir.write("flip.stl", t.stl())), HasSubstr("inconsistently oriented"));
}

TEST(SurfaceIo, InsideOutIsReported) {
  auvloop::test::TempDir dir;
  Tetra t;
  for (auto& f : t.faces) std::swap(f[1], f[2]);
  EXPECT_THAT(read_error(dir.write("inside-out.stl", t.stl())), HasSubstr("inside out"));
}

TEST(SurfaceIo, NonManifoldEdgeIsReported) {
  auvloop::test::TempDir dir;
  std::string stl = Tetra{}.stl();
  stl.insert(stl.rfind("endsolid"),
             "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0.5 0 0\nvertex 0.25 -0.5 0.25\n"
             "endloop\nendfacet\n");
  EXPECT_THAT(read_error(dir.write("fin.stl", stl)), HasSubstr("not manifold"));
}

TEST(SurfaceIo, MillimetresAreDetectedAndScaleFixesThem) {
  auvloop::test::TempDir dir;
  Tetra t;
  t.size = 500;
  const auto path = dir.write("mm.stl", t.stl());
  EXPECT_THAT(read_error(path), HasSubstr("if the file is in millimetres use a scale of 0.001"));
  SurfaceReadOptions mm;
  mm.scale = 0.001;
  EXPECT_NEAR(measure(read_surface(path, mm).at(0).mesh).volume, 0.125 / 6, 1e-12);
}

TEST(SurfaceIo, GarbageEmptyAndUnknownFilesAreReported) {
  auvloop::test::TempDir dir;
  std::string garbage;
  std::uint32_t state = 12345;
  for (int i = 0; i < 1000; ++i) {
    state = state * 1664525U + 1013904223U;
    garbage += static_cast<char>(state >> 24);
  }
  EXPECT_THAT(read_error(dir.write("garbage.stl", garbage)), HasSubstr("garbage.stl"));
  EXPECT_THAT(read_error(dir.write("garbage.glb", garbage)),
              HasSubstr("not a readable surface file"));
  EXPECT_THAT(read_error(dir.write("empty.obj", "")), HasSubstr("the file is empty"));
  EXPECT_THAT(read_error(dir.write("model.step", "x")),
              HasSubstr("unsupported surface format \".step\""));
  EXPECT_THAT(read_error(dir.path() / "missing.stl"), HasSubstr("no such file"));
}

TEST(SurfaceIo, UnsupportedOutputFormatWritesNothing) {
  auvloop::test::TempDir dir;
  EXPECT_THROW(write_surface(dir.path() / "x.dxf", remus_union()), GeometryError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}
