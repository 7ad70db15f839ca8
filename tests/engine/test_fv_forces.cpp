// SPDX-License-Identifier: GPL-3.0-or-later
// Forces and moments on wall patches against analytic flows:
//   - plane Couette flow (exact on any grid, test_fv_pimple): the wall shear nu U / H per area
//     acts at a known lever arm, so the moment about any point is exact too;
//   - circular Couette flow between a rotating inner cylinder (R1, Omega) and a fixed outer one
//     (R2): u_theta = A r + B / r and the torque per unit length on the inner cylinder
//     T = -4 pi nu Omega R1^2 R2^2 / (R2^2 - R1^2) (per unit density; Schlichting and Gersten,
//     Boundary-Layer Theory, 8th ed., section 5.2.3; Landau and Lifshitz, Fluid Mechanics,
//     section 18). The one-sided wall gradient is first order on the curved profile, so the
//     torque converges at first order.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "auvloop/engine/fv/forces.hpp"
#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"
#include "couette_flow.hpp"

using namespace auvloop;
using engine::fv::Pimple;

namespace {
constexpr double kPi = std::numbers::pi;

// Annulus R1 < r < R2, nr x nt cells, one layer of thickness dz with empty sides.
mesher::Grid annulus(double R1, double R2, int nr, int nt, double dz) {
  std::vector<Eigen::Vector3d> points;
  auto index = [&](int i, int j, int k) { return (k * nt + j % nt) * (nr + 1) + i; };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < nt; ++j)
      for (int i = 0; i <= nr; ++i) {
        const double r = R1 + (R2 - R1) * i / nr, t = 2 * kPi * j / nt;
        points.emplace_back(r * std::cos(t), r * std::sin(t), k * dz);
      }
  std::vector<std::array<int, 8>> hexes;
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < nr; ++i)
      hexes.push_back({index(i, j, 0), index(i + 1, j, 0), index(i + 1, j + 1, 0),
                       index(i, j + 1, 0), index(i, j, 1), index(i + 1, j, 1),
                       index(i + 1, j + 1, 1), index(i, j + 1, 1)});
  std::vector<mesher::Patch> patches{{"inner", mesher::PatchType::wall},
                                     {"outer", mesher::PatchType::wall},
                                     {"front", mesher::PatchType::empty},
                                     {"back", mesher::PatchType::empty}};
  const double r_mid = 0.5 * (R1 + R2);
  return mesher::hex_grid(
      points, hexes, patches,
      [&](const Eigen::Vector3d& x) {
        if (x.z() < 0.25 * dz) return 2;
        if (x.z() > 0.75 * dz) return 3;
        return std::hypot(x.x(), x.y()) < r_mid ? 0 : 1;
      },
      "annulus");
}

// Torque (z) on the inner cylinder per unit length over its exact value.
double taylor_couette_torque_ratio(int nr, int nt) {
  const double R1 = 1, R2 = 2, omega = 1, nu = 0.1, dz = 0.1;
  const auto grid = annulus(R1, R2, nr, nt, dz);
  const engine::fv::Mesh mesh(grid);
  engine::fv::PimpleSettings s;
  s.nu = nu;
  s.dt = 0.1;
  s.bdf2 = false;
  s.tolerance = 1e-10;
  Pimple flow(mesh, s);
  flow.U.fix(mesh, "outer", {0, 0, 0});
  flow.U.fix(mesh, "inner", {0, 0, 0});
  const auto& inner = grid.patches[0];
  for (int i = 0; i < inner.size; ++i) {
    const Eigen::Vector3d u = Eigen::Vector3d(0, 0, omega).cross(mesh.face_centre(inner.start + i));
    for (std::size_t c = 0; c < 3; ++c)
      flow.U.c[c].bcs[0].value[static_cast<std::size_t>(i)] = u[static_cast<Eigen::Index>(c)];
  }
  flow.initialise();
  for (int k = 0; k < 120; ++k) flow.step();  // 12 s: 12 decay times (R2 - R1)^2 / (pi^2 nu)
  const auto force = engine::fv::patch_force(flow, "inner");
  // Normal pressure forces on the faces of a regular polygon pass through the axis.
  EXPECT_LT(std::abs(force.pressure_moment.z()), 1e-9 * std::abs(force.viscous_moment.z()));
  const double exact = -4 * kPi * nu * omega * R1 * R1 * R2 * R2 / (R2 * R2 - R1 * R1) * dz;
  return force.total_moment().z() / exact;
}
}  // namespace

TEST(FvForces, CouetteMomentHasTheExactLeverArm) {
  const test::CouetteFlow couette;
  const auto& flow = couette.flow;
  const double H = test::CouetteFlow::H, dz = test::CouetteFlow::dz;
  const Eigen::Vector3d x0(0.3, -0.1, 0.02);
  const double shear = test::CouetteFlow::shear();
  const auto walls = engine::fv::wall_forces(flow, x0);
  ASSERT_EQ(walls.size(), 2u);  // inlet and outlet are not walls
  EXPECT_EQ(walls[0].first, "bottom");
  EXPECT_EQ(walls[1].first, "top");
  // Force +shear on the bottom (y = 0), -shear on the top (y = H), both along x, uniform over
  // the wall: M_z = -(y_wall - y0) F_x, M_y = (z_mid - z0) F_x with the wall's mid-depth z.
  const auto& bottom = walls[0].second;
  const auto& top = walls[1].second;
  EXPECT_NEAR(bottom.total_moment().z(), -(0 - x0.y()) * shear, 1e-9 * shear);
  EXPECT_NEAR(top.total_moment().z(), -(H - x0.y()) * -shear, 1e-9 * shear);
  EXPECT_NEAR(top.total_moment().y(), (0.5 * dz - x0.z()) * -shear, 1e-9 * shear);
  const auto total = engine::fv::total_wall_force(flow, x0);
  EXPECT_NEAR(total.total_moment().z(), H * shear, 1e-9 * shear);
  EXPECT_NEAR(total.total().x(), 0.0, 1e-9 * shear);
}

TEST(FvForces, TaylorCouetteTorqueConvergesToTheExactValue) {
  const double coarse = taylor_couette_torque_ratio(8, 48);
  const double fine = taylor_couette_torque_ratio(16, 96);
  const double order = std::log2(std::abs(coarse - 1) / std::abs(fine - 1));
  std::printf("Taylor-Couette torque / exact: 8 x 48 %.5f, 16 x 96 %.5f, order %.2f\n", coarse,
              fine, order);
  EXPECT_GT(order, 0.8);  // first order: the one-sided wall gradient
  EXPECT_LT(std::abs(fine - 1), 0.05);
}

TEST(FvForces, UnknownPatchIsNamed) {
  mesher::BoxPatches patches;
  const auto grid =
      mesher::cartesian_box(mesher::graded_nodes(0, 1, 3), mesher::graded_nodes(0, 1, 3),
                            mesher::graded_nodes(0, 1, 3), patches);
  const engine::fv::Mesh mesh(grid);
  Pimple flow(mesh, {});
  flow.initialise();
  EXPECT_THROW(engine::fv::patch_force(flow, "hull"), std::invalid_argument);
}
