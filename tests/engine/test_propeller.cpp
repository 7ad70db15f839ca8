// SPDX-License-Identifier: GPL-3.0-or-later
// The propeller's open-water curves and body-force disk (engine/propeller.hpp), each against
// something independent of the code:
//   - the B-series polynomials against the check values of propeller.md (computed from the
//     published coefficients, P/D 1.0, Z 3, AE/A0 0.65 and 0.718) and against the two points
//     Fossen's MSS remus100 model quotes;
//   - the Hough-Ordway disk's force, integrated over the disk by quadrature in r (the code
//     evaluated point by point), against the thrust and torque it was given, and its directions
//     (thrown aft; the torque on the fluid along +axis for a right-handed turn);
//   - the table's interpolation and its errors; the operating point worked by hand;
//   - the disk on a grid (fv::DiskForce): the fluid gets exactly the thrust and torque on
//     coarse and fine grids, each cell's force tends to the continuous distribution, and the
//     disk speed of a uniform stream is its axial component.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/fv/propeller_disk.hpp"
#include "auvloop/engine/propeller.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
using namespace auvloop::engine;

TEST(BSeries, ReproducesTheCheckValuesOfThePublishedCoefficients) {
  struct Row {
    double J, kt65, kq65_10, kt718, kq718_10;
  };
  const std::vector<Row> rows{{0.0, 0.44152, 0.67188, 0.45663, 0.70029},
                              {0.4, 0.29568, 0.47178, 0.30106, 0.48530},
                              {0.6, 0.20859, 0.34909, 0.20960, 0.35473},
                              {0.8, 0.11721, 0.21850, 0.11461, 0.21829}};
  for (const auto& row : rows) {
    const auto a = b_series({3, 1.0, 0.65}, row.J);
    const auto b = b_series({3, 1.0, 0.718}, row.J);
    EXPECT_NEAR(a.KT, row.kt65, 1e-4) << "J " << row.J;
    EXPECT_NEAR(10 * a.KQ, row.kq65_10, 1e-4) << "J " << row.J;
    EXPECT_NEAR(b.KT, row.kt718, 1e-4) << "J " << row.J;
    EXPECT_NEAR(10 * b.KQ, row.kq718_10, 1e-4) << "J " << row.J;
  }
  // Fossen's remus100 (B3-71.8, P/D 1.0): KT 0.4566, KQ 0.0700 at J = 0; 0.1798, 0.0312 at 0.6632.
  EXPECT_NEAR(b_series({3, 1.0, 0.718}, 0).KT, 0.4566, 1e-4);
  EXPECT_NEAR(b_series({3, 1.0, 0.718}, 0).KQ, 0.0700, 1e-4);
  EXPECT_NEAR(b_series({3, 1.0, 0.718}, 0.6632).KT, 0.1798, 1e-4);
  EXPECT_NEAR(b_series({3, 1.0, 0.718}, 0.6632).KQ, 0.0312, 1e-4);
}

TEST(BSeries, NamesTheBoundAPropellerBreaks) {
  EXPECT_FALSE(b_series_range_problem({3, 1.0, 0.718}).has_value());
  const auto low_pitch = b_series_range_problem({3, 0.43, 0.718});
  ASSERT_TRUE(low_pitch.has_value());
  EXPECT_NE(low_pitch->find("P/D 0.43"), std::string::npos) << *low_pitch;
  EXPECT_TRUE(b_series_range_problem({8, 1.0, 0.718}).has_value());
  EXPECT_TRUE(b_series_range_problem({3, 1.0, 1.2}).has_value());
}

TEST(OpenWaterTable, InterpolatesLinearlyHoldsTheEndsAndNamesABadPoint) {
  const OpenWaterTable table({{0.0, 0.4, 0.06}, {0.5, 0.2, 0.04}, {1.0, 0.0, 0.01}});
  bool clamped = true;
  const auto mid = table.at(0.25, &clamped);
  EXPECT_FALSE(clamped);
  EXPECT_DOUBLE_EQ(mid.KT, 0.3);
  EXPECT_DOUBLE_EQ(mid.KQ, 0.05);
  EXPECT_DOUBLE_EQ(table.at(0.5, &clamped).KT, 0.2);
  EXPECT_FALSE(clamped);
  EXPECT_DOUBLE_EQ(table.at(1.3, &clamped).KT, 0.0);
  EXPECT_TRUE(clamped);
  EXPECT_DOUBLE_EQ(table.at(-0.1, &clamped).KQ, 0.06);
  EXPECT_TRUE(clamped);
  EXPECT_THROW(OpenWaterTable({{0.0, 0.4, 0.06}}), std::invalid_argument);
  try {
    OpenWaterTable({{0.0, 0.4, 0.06}, {0.5, 0.2, 0.04}, {0.5, 0.1, 0.03}});
    FAIL() << "a repeated J was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 3"), std::string::npos) << e.what();
  }
}

TEST(OperatingPoint, TakesTheDisksOwnInductionOffOnceAndHandlesRestAndBollard) {
  const OpenWaterTable table({{0.0, 0.40, 0.060}, {1.0, 0.0, 0.020}});
  const auto curve = [&](double J) { return table.at(J); };
  const double n = 25, D = 0.14, ud = 1.4;  // 1500 rpm
  const auto op = operating_point(curve, n, D, ud);
  // By hand: J0 = 0.4, KT 0.24, T0 = 0.24 n^2 D^4, u_i = T0 / (2 ud pi D^2 / 4).
  const double T0 = 0.24 * n * n * std::pow(D, 4);
  const double ui = T0 / (2 * ud * std::numbers::pi * D * D / 4);
  const double J = (ud - ui) / (n * D);
  EXPECT_NEAR(op.J, J, 1e-15);
  EXPECT_NEAR(op.KT, 0.4 * (1 - J), 1e-15);
  EXPECT_NEAR(op.KQ, 0.06 - 0.04 * J, 1e-15);
  EXPECT_DOUBLE_EQ(op.thrust, op.KT * n * n * std::pow(D, 4));
  EXPECT_DOUBLE_EQ(op.torque, op.KQ * n * n * std::pow(D, 5));
  EXPECT_LT(op.J, ud / (n * D));  // the induction lowers J, raising the thrust
  // The sense of rotation does not change the magnitudes.
  EXPECT_EQ(operating_point(curve, -n, D, ud).thrust, op.thrust);
  // At rest nothing; against the flow or still water the bollard point.
  EXPECT_EQ(operating_point(curve, 0, D, ud).thrust, 0);
  EXPECT_EQ(operating_point(curve, n, D, -0.3).J, 0);
  EXPECT_NEAR(operating_point(curve, n, D, 0).thrust, 0.4 * n * n * std::pow(D, 4), 1e-15);
  EXPECT_THROW((void)operating_point(curve, n, 0, ud), std::invalid_argument);
}

namespace {
// The disk's thrust and torque on the fluid by quadrature: the midpoint rule in r over [R_H,
// R_P] at azimuth `theta` (the force is axisymmetric, the integral over theta is 2 pi times
// one azimuth's) times the thickness (the force is uniform across it).
struct Integral {
  double thrust = 0, torque = 0;  // along -axis and +axis (on the fluid)
};
Integral integrate(const PropellerDisk& disk, double T, double Q, double theta, int n) {
  const Eigen::Vector3d a = disk.axis;
  const Eigen::Vector3d e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  const double dr = (disk.radius - disk.hub_radius) / n;
  Integral out;
  for (int i = 0; i < n; ++i) {
    const double r = disk.hub_radius + (i + 0.5) * dr;
    const Eigen::Vector3d radial = r * (std::cos(theta) * e1 + std::sin(theta) * e2);
    const Eigen::Vector3d x = disk.centre + 0.3 * disk.thickness * a + radial;
    const Eigen::Vector3d f = hough_ordway(disk, T, Q, x);
    const double ring = 2 * std::numbers::pi * r * dr * disk.thickness;
    out.thrust += -f.dot(a) * ring;
    out.torque += radial.cross(f).dot(a) * ring;
  }
  return out;
}
}  // namespace

TEST(HoughOrdway, IntegratesToTheThrustAndTorqueItWasGivenWithTheirDirections) {
  PropellerDisk disk;
  disk.centre = Eigen::Vector3d(-0.8, 0.01, -0.02);
  disk.axis = Eigen::Vector3d(1, 0.2, -0.1).normalized();
  disk.radius = 0.0699;  // REMUS 100: D = 5.5 in
  disk.hub_radius = 0.02;
  disk.thickness = 0.012;
  const double T = 3.86 / 1025, Q = 0.543 / 1025;  // Prestero's 1500 rpm point, per density
  for (int sense : {1, -1}) {
    disk.sense = sense;
    for (double theta : {0.0, 1.1, 4.0}) {
      const auto s = integrate(disk, T, Q, theta, 400000);
      EXPECT_NEAR(s.thrust / T, 1.0, 1e-7) << "theta " << theta;
      EXPECT_NEAR(s.torque / (sense * Q), 1.0, 1e-7) << "theta " << theta;
    }
  }
  // No hub: the distribution starts at the axis.
  disk.hub_radius = 0;
  disk.sense = 1;
  const auto s = integrate(disk, T, Q, 0.5, 400000);
  EXPECT_NEAR(s.thrust / T, 1.0, 1e-7);
  EXPECT_NEAR(s.torque / Q, 1.0, 1e-7);
}

TEST(HoughOrdway, IsZeroOutsideTheDiskAndRejectsABadDisk) {
  PropellerDisk disk;  // centre 0, axis +x, R_P 0.07, R_H 0.02, thickness 0.01
  const double T = 1e-3, Q = 1e-4;
  EXPECT_GT(hough_ordway(disk, T, Q, {0.004, 0.05, 0}).norm(), 0);
  EXPECT_EQ(hough_ordway(disk, T, Q, {0.006, 0.05, 0}).norm(), 0);  // beyond half the thickness
  EXPECT_EQ(hough_ordway(disk, T, Q, {0, 0.071, 0}).norm(), 0);     // beyond the tip
  EXPECT_EQ(hough_ordway(disk, T, Q, {0, 0, 0.019}).norm(), 0);     // in the hub
  EXPECT_EQ(hough_ordway(disk, T, Q, {0, 0, 0.07}).norm(), 0);      // at the tip: r* = 1
  auto bad = disk;
  bad.hub_radius = 0.08;
  EXPECT_THROW((void)hough_ordway(bad, T, Q, {0, 0.05, 0}), std::invalid_argument);
  bad = disk;
  bad.axis = Eigen::Vector3d(1, 1, 0);
  EXPECT_THROW((void)hough_ordway(bad, T, Q, {0, 0.05, 0}), std::invalid_argument);
  bad = disk;
  bad.sense = 0;
  EXPECT_THROW((void)hough_ordway(bad, T, Q, {0, 0.05, 0}), std::invalid_argument);
}

namespace {
// A box of cubes of side h round the origin: x in [-half_length, half_length], y and z in
// [-0.1, 0.1] (m).
mesher::Grid box(double h, double half_length = 0.01) {
  mesher::BoxPatches patches;
  patches.names = {"x0", "x1", "y0", "y1", "z0", "z1"};
  patches.types.fill(mesher::PatchType::wall);
  const auto n = [h](double a, double b) { return static_cast<int>(std::lround((b - a) / h)); };
  const double a = half_length;
  return mesher::cartesian_box(mesher::graded_nodes(-a, a, n(-a, a)),
                               mesher::graded_nodes(-0.1, 0.1, n(-0.1, 0.1)),
                               mesher::graded_nodes(-0.1, 0.1, n(-0.1, 0.1)), patches);
}
}  // namespace

TEST(DiskForce, GivesTheFluidExactlyTheThrustAndTorqueOnAnyGridAndTheShapeOnAFineOne) {
  const double T = 3.86 / 1025, Q = 0.543 / 1025;
  PropellerDisk disk;
  disk.radius = 0.0699;
  disk.hub_radius = 0.02;
  disk.thickness = 0.01;
  for (double h : {0.01, 0.005, 0.0025}) {
    const auto grid = box(h);
    const fv::Mesh mesh(grid);
    for (int sense : {1, -1}) {
      disk.sense = sense;
      const fv::DiskForce force(mesh, disk);
      std::vector<Eigen::Vector3d> f(static_cast<std::size_t>(mesh.cells()),
                                     Eigen::Vector3d::Zero());
      force.apply(T, Q, f);
      Eigen::Vector3d F = Eigen::Vector3d::Zero(), M = Eigen::Vector3d::Zero();
      for (int c = 0; c < mesh.cells(); ++c) {
        const auto s = static_cast<std::size_t>(c);
        F += mesh.volume(c) * f[s];
        M += (mesh.centre(c) - disk.centre).cross(mesh.volume(c) * f[s]);
      }
      EXPECT_NEAR(F.x() / -T, 1.0, 1e-13) << "h " << h;
      EXPECT_NEAR(F.y(), 0.0, 1e-13 * T);
      EXPECT_NEAR(F.z(), 0.0, 1e-13 * T);
      EXPECT_NEAR(M.x() / (sense * Q), 1.0, 1e-13) << "h " << h;
    }
    // On the finest grid each cell's force is the continuous distribution's at its centre,
    // within the sampling's error (the renormalisation tends to one).
    if (h == 0.0025) {
      disk.sense = 1;
      const fv::DiskForce force(mesh, disk);
      std::vector<Eigen::Vector3d> f(static_cast<std::size_t>(mesh.cells()),
                                     Eigen::Vector3d::Zero());
      force.apply(T, Q, f);
      double worst = 0;
      for (int c : force.cells()) {
        const Eigen::Vector3d exact = hough_ordway(disk, T, Q, mesh.centre(c));
        const double peak =
            105 * T /
            (8 * std::numbers::pi * disk.thickness * (disk.radius - disk.hub_radius) *
             (3 * disk.hub_radius + 4 * disk.radius));
        worst = std::max(worst, (f[static_cast<std::size_t>(c)] - exact).norm() / peak);
      }
      EXPECT_LT(worst, 0.03) << "the sampled distribution differs from the continuous one";
    }
  }
}

TEST(DiskForce, MeasuresTheDiskSpeedAndNamesADiskOffTheGrid) {
  const auto grid = box(0.005);
  const fv::Mesh mesh(grid);
  PropellerDisk disk;
  disk.axis = Eigen::Vector3d(1, 0, 0);
  disk.radius = 0.05;
  disk.hub_radius = 0.01;
  const fv::DiskForce force(mesh, disk);
  fv::VectorField U(mesh, "U");
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto s = static_cast<std::size_t>(c);
    U.c[0].cells[s] = 1.54;
    U.c[1].cells[s] = 0.3;
    U.c[2].cells[s] = -0.2;
  }
  EXPECT_NEAR(force.disk_speed(U), 1.54, 1e-12);  // a sum's round-off
  // Candidates: only the cells with y > 0 carry the disk.
  std::vector<char> upper(static_cast<std::size_t>(mesh.cells()), 0);
  for (int c = 0; c < mesh.cells(); ++c)
    upper[static_cast<std::size_t>(c)] = mesh.centre(c).y() > 0;
  const fv::DiskForce half(mesh, disk, upper);
  EXPECT_LT(half.cells().size(), force.cells().size());
  for (int c : half.cells()) EXPECT_GT(mesh.centre(c).y(), 0);
  auto away = disk;
  away.centre = Eigen::Vector3d(1, 0, 0);
  try {
    const fv::DiskForce none(mesh, away);
    FAIL() << "a disk off the grid was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("off the grid"), std::string::npos) << e.what();
  }
}

TEST(DiskForce, SamplesTheInflowOnAPlaneAheadRelativeToTheMovingGrid) {
  const auto grid = box(0.005, 0.05);
  const fv::Mesh mesh(grid);
  PropellerDisk disk;
  disk.radius = 0.05;
  disk.hub_radius = 0.01;
  const double offset = 0.02;  // the plane at x = 0.02: cell centres at 0.0175 and 0.0225
  const fv::DiskForce force(mesh, disk, {}, offset);
  // The water: u = a + b x (the wake's recovery ahead of the disk), plus a side flow.
  const double a = -1.2, b = 5.0;
  fv::VectorField U(mesh, "U");
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto s = static_cast<std::size_t>(c);
    U.c[0].cells[s] = a + b * mesh.centre(c).x();
    U.c[1].cells[s] = 0.3;
  }
  ASSERT_FALSE(force.inflow_cells().empty());
  for (int c : force.inflow_cells()) {
    const Eigen::Vector3d x = mesh.centre(c);
    EXPECT_NEAR(std::abs(x.x() - offset), 0.0025, 1e-12);
    EXPECT_LE(std::hypot(x.y(), x.z()), disk.radius);
  }
  // The plane's two layers straddle it symmetrically: the mean of the linear u is u(0.02).
  EXPECT_NEAR(force.inflow_speed(U), -(a + b * offset), 1e-12);
  // The grid moving forward at 1.54 m/s and turning about its z axis (w_x = -r y, whose mean
  // over the plane's symmetric cells vanishes): the water meets the disk 1.54 m/s faster.
  fv::FrameMotion motion;
  motion.velocity = Eigen::Vector3d(1.54, 0.1, 0);
  motion.rate = Eigen::Vector3d(0, 0, 0.7);
  EXPECT_NEAR(force.inflow_speed(U, motion), 1.54 - (a + b * offset), 1e-12);
  // Offset 0: the disk's own cells (the mean of u over |x| <= 0.005 is u(0) = a).
  const fv::DiskForce at_disk(mesh, disk);
  EXPECT_EQ(at_disk.inflow_cells(), at_disk.cells());
  EXPECT_NEAR(at_disk.inflow_speed(U), -a, 1e-12);
  EXPECT_NEAR(at_disk.inflow_speed(U), -at_disk.disk_speed(U), 1e-12);
  // A plane off the grid and a negative offset are named.
  for (double bad : {1.0, -0.01}) {
    try {
      const fv::DiskForce none(mesh, disk, {}, bad);
      FAIL() << "offset " << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("inflow plane"), std::string::npos) << e.what();
    }
  }
}

// The remus100 preset's open-water curve is what its source says: the B3-71.8 at P/D 0.5 with J
// scaled by 0.71 (the calibration, docs/cfd-plant.md), to the table's printed digits.
TEST(BSeries, TheRemusPresetsCurveIsTheScaledSeries) {
  const auto w = auvloop::geometry::preset_vehicle("remus100").propeller.open_water;
  ASSERT_FALSE(w.empty());
  for (std::size_t i = 0; i < w.J.size(); ++i) {
    const auto p = b_series({3, 0.5, 0.718}, w.J[i] / 0.71);
    EXPECT_NEAR(w.KT[i], p.KT, 5e-6) << "J " << w.J[i];
    EXPECT_NEAR(w.KQ[i], p.KQ, 5e-7) << "J " << w.J[i];
  }
}
