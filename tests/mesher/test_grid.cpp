// SPDX-License-Identifier: GPL-3.0-or-later
// The polyhedral grid: geometry of Cartesian and distorted hexahedra against exact values,
// invariants, and the OpenFOAM / VTK writers.
#include <fstream>
#include <random>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "auvloop/mesher/generators.hpp"
#include "auvloop/mesher/grid_io.hpp"
#include "temp_dir.hpp"

using namespace auvloop::mesher;
using ::testing::HasSubstr;

namespace {
std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(Grid, UniformBoxHasExactGeometry) {
  const Grid g = cartesian_box(graded_nodes(0, 1, 3), graded_nodes(0, 2, 4), graded_nodes(0, 3, 5));
  const GridGeometry geo = compute_geometry(g);
  EXPECT_NO_THROW(validate(g, geo));
  EXPECT_EQ(g.cells, 60);
  EXPECT_EQ(g.internal_faces(), 2 * 4 * 5 + 3 * 3 * 5 + 3 * 4 * 4);
  EXPECT_EQ(g.faces() - g.internal_faces(), 2 * (4 * 5 + 3 * 5 + 3 * 4));
  for (double v : geo.cell_volume) EXPECT_NEAR(v, 0.1, 1e-15);
  const GridQuality q = measure_quality(g, geo);
  EXPECT_NEAR(q.total_volume, 6.0, 1e-13);
  EXPECT_LT(q.max_closure_error, 1e-15);
  EXPECT_NEAR(q.max_non_orthogonality, 0.0, 1e-6);
  EXPECT_NEAR(q.max_skewness, 0.0, 1e-12);
  // Cell 0 spans [0, 1/3] x [0, 1/2] x [0, 3/5]: its centre is the box centre.
  EXPECT_NEAR((geo.cell_centre[0] - Eigen::Vector3d(1.0 / 6, 0.25, 0.3)).norm(), 0.0, 1e-15);
  // Boundary area vectors point outward and add up to the box's surface area.
  double area = 0;
  for (int f = g.internal_faces(); f < g.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    area += geo.face_area[fs].norm();
    EXPECT_GT(geo.face_area[fs].dot(geo.face_centre[fs] - Eigen::Vector3d(0.5, 1, 1.5)), 0.0);
  }
  EXPECT_NEAR(area, 2 * (1 * 2 + 2 * 3 + 1 * 3), 1e-12);
}

TEST(Grid, GradedNodes) {
  const auto x = graded_nodes(0, 1, 10, 1.2);
  ASSERT_EQ(x.size(), 11U);
  EXPECT_DOUBLE_EQ(x.front(), 0.0);
  EXPECT_DOUBLE_EQ(x.back(), 1.0);
  for (std::size_t i = 2; i < x.size(); ++i)
    EXPECT_NEAR((x[i] - x[i - 1]) / (x[i - 1] - x[i - 2]), 1.2, 1e-12);
  const auto s = graded_nodes(0, 1, 10, 1.2, true);  // clustered at both ends, symmetric
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_NEAR(s[i] + s[s.size() - 1 - i], 1.0, 1e-15);
}

// Vinokur's two-sided stretching corrected to its end cells: both within 1e-8 of their targets,
// sizes growing monotonically to a single largest cell and back, and bad arguments refused.
TEST(Grid, TwoSidedNodesHitTheirEndSizes) {
  struct Case {
    double a, b;
    int n;
    double first, last;
  };
  for (const Case& c : {Case{0, 1, 48, 0.002, 0.005}, Case{0.3, 1.7, 20, 0.01, 0.01},
                        Case{0, 2, 96, 1e-3, 4e-3}, Case{-1, 0, 12, 0.02, 0.05}}) {
    const auto x = two_sided_nodes(c.a, c.b, c.n, c.first, c.last);
    ASSERT_EQ(static_cast<int>(x.size()), c.n + 1);
    EXPECT_EQ(x.front(), c.a);
    EXPECT_EQ(x.back(), c.b);
    EXPECT_NEAR((x[1] - x[0]) / c.first, 1, 1e-8) << c.n;
    EXPECT_NEAR((x[x.size() - 1] - x[x.size() - 2]) / c.last, 1, 1e-8) << c.n;
    std::size_t rising = 1;
    while (rising + 1 < x.size() && x[rising + 1] - x[rising] > x[rising] - x[rising - 1]) ++rising;
    for (std::size_t i = rising + 1; i + 1 < x.size(); ++i)
      EXPECT_LT(x[i + 1] - x[i], x[i] - x[i - 1]) << "not a single peak at node " << i;
  }
  EXPECT_THROW((void)two_sided_nodes(0, 1, 10, 0.1, 0.2), std::invalid_argument);   // not finer
  EXPECT_THROW((void)two_sided_nodes(0, 1, 2, 0.01, 0.01), std::invalid_argument);  // 2 cells
  EXPECT_THROW((void)two_sided_nodes(0, 1, 4, 0.9, 0.05), std::invalid_argument);   // one coarse
  EXPECT_THROW((void)two_sided_nodes(1, 0, 10, 0.01, 0.01), std::invalid_argument);
}

TEST(Grid, DistortedHexahedraStayClosedAndConserveVolume) {
  // Interior points moved at random: faces become non-planar, cells skewed. Closure must hold to
  // round-off and the cell volumes must still add up to the box (each face contributes the same
  // S . C_f to both of its cells).
  Grid g =
      cartesian_box(graded_nodes(0, 1, 6, 1.3), graded_nodes(0, 1, 5), graded_nodes(0, 1, 4, 0.8));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  for (auto& p : g.points) {
    const bool interior = p.minCoeff() > 1e-12 && p.maxCoeff() < 1 - 1e-12;
    if (interior) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
  }
  const GridGeometry geo = compute_geometry(g);
  EXPECT_NO_THROW(validate(g, geo, 1e-12));
  const GridQuality q = measure_quality(g, geo);
  EXPECT_NEAR(q.total_volume, 1.0, 1e-13);
  EXPECT_GT(q.max_non_orthogonality, 1.0);
  EXPECT_GT(q.max_skewness, 1e-3);
}

TEST(Grid, ValidateNamesTheBrokenInvariant) {
  Grid g = cartesian_box(graded_nodes(0, 1, 2), graded_nodes(0, 1, 2), graded_nodes(0, 1, 2));
  // Reverse one boundary face: its cell no longer closes.
  const int f = g.internal_faces();
  std::reverse(g.face_points.begin() + g.face_offsets[static_cast<std::size_t>(f)],
               g.face_points.begin() + g.face_offsets[static_cast<std::size_t>(f) + 1]);
  try {
    validate(g, compute_geometry(g));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("not closed"));
  }
  Grid h = cartesian_box(graded_nodes(0, 1, 2), graded_nodes(0, 1, 2), graded_nodes(0, 1, 2));
  std::swap(h.owner[0], h.neighbour[0]);
  EXPECT_THROW(validate(h, compute_geometry(h)), std::runtime_error);
}

TEST(Grid, WritesOpenFoamPolyMeshAndVtu) {
  auvloop::test::TempDir tmp;
  BoxPatches patches;
  patches.types[4] = patches.types[5] = PatchType::empty;  // a 2D cavity: one cell thick
  patches.names[3] = "lid";
  const Grid g = cartesian_box(graded_nodes(0, 1, 4), graded_nodes(0, 1, 4),
                               graded_nodes(0, 0.1, 1), patches, "cavity");
  write_openfoam_polymesh(tmp.path(), g);
  const auto dir = tmp.path() / "constant" / "polyMesh";
  EXPECT_THAT(read(dir / "owner"),
              HasSubstr("note        \"nPoints:50 nCells:16 nFaces:72 nInternalFaces:24\""));
  EXPECT_THAT(read(dir / "faces"), HasSubstr("72\n(\n4("));
  EXPECT_THAT(read(dir / "boundary"),
              HasSubstr("lid\n    {\n        type            wall;\n        nFaces          4;"));
  EXPECT_THAT(read(dir / "boundary"), HasSubstr("type            empty;"));
  std::vector<double> volume(16, 0.00625);
  write_vtu(tmp.path() / "cavity.vtu", g, {{"volume", volume}});
  const std::string vtu = read(tmp.path() / "cavity.vtu");
  EXPECT_THAT(vtu, HasSubstr("NumberOfCells=\"16\""));
  EXPECT_THAT(vtu, HasSubstr("Name=\"faceoffsets\""));
  EXPECT_THAT(vtu, HasSubstr("Name=\"volume\""));
}

TEST(Grid, GrownNodesStartAtTheRequestedSizeAndNeverGrowTooFast) {
  const auto x = grown_nodes(0, 10, 0.02, 1.15);
  EXPECT_NEAR(x[1] - x[0], 0.02, 1e-9);
  EXPECT_DOUBLE_EQ(x.back(), 10.0);
  for (std::size_t i = 2; i < x.size(); ++i)
    EXPECT_LE((x[i] - x[i - 1]) / (x[i - 1] - x[i - 2]), 1.15 + 1e-9);
}

TEST(Grid, BackgroundBoxHasThePapersExtents) {
  // REMUS 100: L = 1.3327 m, bow at body x = 0.611 m, fin tips 0.131 m from the axis.
  BackgroundSpec s;
  s.nose_x = 0.611;
  s.length = 1.3327;
  s.radius = 0.131;
  s.spacing = 0.04;
  const Grid g = background_box(s);
  const GridGeometry geo = compute_geometry(g);
  EXPECT_NO_THROW(validate(g, geo));
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (const auto& p : g.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  EXPECT_NEAR(hi.x(), 0.611 + 3 * 1.3327, 1e-12);           // inlet 3 L ahead of the bow
  EXPECT_NEAR(lo.x(), 0.611 - 1.3327 - 5 * 1.3327, 1e-12);  // outlet 5 L behind the stern
  EXPECT_NEAR(hi.y(), 1.4 * 1.3327, 1e-12);
  EXPECT_NEAR(lo.z(), -1.4 * 1.3327, 1e-12);
  // The cell holding the propeller disk (just behind the stern) is a near-body cell: the near
  // region is divided into whole cells no larger than the spacing.
  int near = -1;
  for (int c = 0; c < g.cells; ++c) {
    if ((geo.cell_centre[static_cast<std::size_t>(c)] - Eigen::Vector3d(0.611 - 1.3427, 0.02, 0.02))
            .norm() < 0.04)
      near = c;
  }
  ASSERT_GE(near, 0);
  const double size = std::cbrt(geo.cell_volume[static_cast<std::size_t>(near)]);
  EXPECT_LE(size, 0.04);
  EXPECT_GT(size, 0.85 * 0.04);
  const GridQuality q = measure_quality(g, geo);
  EXPECT_LT(q.max_non_orthogonality, 1e-6);
  EXPECT_THAT(quality_table(g, q), HasSubstr("grid background:"));
  std::printf("%s", quality_table(g, q).c_str());
}

TEST(Grid, StretchedNodesHitTheFirstCellAndTheEnd) {
  for (const double first : {1e-5, 0.01, 0.3}) {  // ratios above, near and below one
    const auto x = stretched_nodes(0.5, 1.5, first, 20);
    ASSERT_EQ(x.size(), 21U);
    EXPECT_NEAR(x[1] - x[0], first, 1e-9 * first);
    EXPECT_DOUBLE_EQ(x.back(), 1.5);
    const double r = (x[2] - x[1]) / (x[1] - x[0]);
    for (std::size_t i = 2; i + 1 < x.size(); ++i)
      EXPECT_NEAR((x[i] - x[i - 1]) / (x[i - 1] - x[i - 2]), r, 1e-9);
  }
  EXPECT_THROW(stretched_nodes(0, 1, 2.0, 5), std::invalid_argument);
  EXPECT_THROW(stretched_nodes(0, 1, 0.1, 0), std::invalid_argument);
}
