// SPDX-License-Identifier: GPL-3.0-or-later
// The rigid body's equations (rigid_body.hpp: mass matrix, Coriolis term, weight and buoyancy)
// against the conservation laws of a free body and Fossen's restoring forces (eq. 4.6), and the
// DFBI coupling (dfbi.hpp) against the exact motion of a body in a model fluid that answers its
// acceleration with an added mass, as the flow's pressure does:
//   - with the fluid's added mass as the estimate one correction converges; with half of it a
//     few; without it and unrelaxed the iteration diverges when the added mass exceeds the
//     body's (REMUS in sway), and relaxation within the bound restores it;
//   - BDF2 is exact for a constant force and second order for a damped body;
//   - held degrees of freedom stay held; the pose of a steady turn is a circle;
//   - a restore continues bitwise.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "auvloop/engine/dfbi.hpp"

using namespace auvloop::engine;

namespace {
Matrix6d random_spd(unsigned seed) {
  std::srand(seed);
  const Matrix6d A = Matrix6d::Random();
  return A * A.transpose() + 6 * Matrix6d::Identity();
}
}  // namespace

TEST(RigidBodyEquations, CoriolisDoesNoWork) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Matrix6d M = random_spd(seed);
    const Vector6d nu = Vector6d::Random();
    EXPECT_NEAR(nu.dot(coriolis(M, nu)), 0.0, 1e-13 * (M * nu).norm() * nu.norm());
  }
}

// A free rigid body with its centre of gravity off the origin: its linear momentum R p1, its
// angular momentum about a point fixed in the Earth frame, R p2 + x_o x R p1, and its energy
// are invariants of the exact motion, which M nu' = -C(nu) nu with rigid_body_mass must keep.
TEST(RigidBodyEquations, AFreeBodyOffItsCentreOfGravityKeepsMomentumAndEnergy) {
  const double m = 31.0;
  const Eigen::Vector3d rg(0.01, -0.02, 0.0196);
  Eigen::Matrix3d Ig;
  Ig << 0.177, 0.01, -0.02, 0.01, 3.45, 0.03, -0.02, 0.03, 3.45;
  Eigen::Matrix3d S;
  S << 0, -rg.z(), rg.y(), rg.z(), 0, -rg.x(), -rg.y(), rg.x(), 0;
  const Matrix6d M = rigid_body_mass(m, rg, Ig - m * S * S);  // I_o, the parallel axes
  const Eigen::PartialPivLU<Matrix6d> lu(M);
  BodyState s;
  s.nu << 1.5, 0.2, -0.1, 0.4, 0.3, -0.5;
  const auto invariants = [&](const BodyState& b) {
    const Vector6d h = M * b.nu;
    const Eigen::Vector3d P = b.attitude * h.head<3>();
    const Eigen::Vector3d H = b.attitude * h.tail<3>() + b.position.cross(P);
    return std::tuple{P, H, 0.5 * b.nu.dot(h)};
  };
  const auto [P0, H0, E0] = invariants(s);
  for (int k = 0; k < 4000; ++k)
    s = rk4_step(s, 1e-3,
                 [&](const BodyState& b) -> Vector6d { return lu.solve(-coriolis(M, b.nu)); });
  const auto [P, H, E] = invariants(s);
  EXPECT_LT((P - P0).norm() / P0.norm(), 1e-10);
  EXPECT_LT((H - H0).norm() / H0.norm(), 1e-10);
  EXPECT_NEAR(E / E0, 1.0, 1e-10);
}

TEST(RigidBodyEquations, WeightAndBuoyancyAreFossensRestoringForces) {
  const double W = 299, B = 306;
  const Eigen::Vector3d rg(0.01, -0.005, 0.0196), rb(0.002, 0.001, -0.003);
  for (const auto& e : {EulerAngles{0.1, -0.3, 1.2}, EulerAngles{-0.7, 0.4, -2.5}}) {
    const double sp = std::sin(e.phi), cp = std::cos(e.phi);
    const double st = std::sin(e.theta), ct = std::cos(e.theta);
    Vector6d g;  // Fossen (2011) eq. 4.6
    g << (W - B) * st, -(W - B) * ct * sp, -(W - B) * ct * cp,
        -(rg.y() * W - rb.y() * B) * ct * cp + (rg.z() * W - rb.z() * B) * ct * sp,
        (rg.z() * W - rb.z() * B) * st + (rg.x() * W - rb.x() * B) * ct * cp,
        -(rg.x() * W - rb.x() * B) * ct * sp - (rg.y() * W - rb.y() * B) * st;
    const Vector6d tau = gravity_and_buoyancy(W, B, rg, rb, quaternion_from_euler(e));
    EXPECT_LT((tau + g).norm(), 1e-12 * W);
  }
}

namespace {
// A body of mass m in a model fluid that answers the iterate's acceleration a with -m_a a (the
// added mass, in every degree of freedom alike) and a linear damping -d nu, under a force F in
// surge: (m + m_a) u' = F - d u.
struct ModelFluid {
  double m_a = 0, d = 0, F = 0;
  [[nodiscard]] Vector6d load(const Dfbi& dfbi) const {
    Vector6d tau = -m_a * dfbi.acceleration() - d * dfbi.iterate().nu;
    tau[0] += F;
    return tau;
  }
};

DfbiBody point_body(double m, double estimate, double relax) {
  DfbiBody b;
  b.mass = rigid_body_mass(m, Eigen::Vector3d::Zero(), m * Eigen::Matrix3d::Identity());
  b.added_mass = estimate * Matrix6d::Identity();
  b.relax = relax;
  return b;
}

// The largest acceleration change of the last correction after `corrections` per step; the first
// step Euler when `euler_first` (as the flow's first step: BDF2 from a steady past is not exact
// for a force that starts at once).
double run(Dfbi& dfbi, const ModelFluid& fluid, int steps, double dt, int corrections,
           bool euler_first = false) {
  double change = 0;
  for (int n = 0; n < steps; ++n) {
    dfbi.begin_step(dt, !(euler_first && n == 0));
    for (int k = 0; k < corrections; ++k) dfbi.correct(fluid.load(dfbi));
    change = std::max(change, dfbi.change());
    dfbi.accept();
  }
  return change;
}
}  // namespace

TEST(Dfbi, TheAddedMassEstimateMakesTheCouplingOfALightBodyConverge) {
  const double m = 1.0, m_a = 2.0, F = 3.0, dt = 0.01;  // added mass twice the body's
  const double exact = F / (m + m_a);                   // u' (m/s^2)
  const ModelFluid fluid{m_a, 0, F};
  struct Case {
    double estimate, relax;
    int corrections;
    double tolerance;  // on u' after the step
  };
  // The iteration's factor: (m_a - estimate) / (m + estimate) with relax 1; 0, 1/3 and (with
  // relax 0.5 and no estimate) 1 - 0.5 (1 + m_a / m) = -1/2.
  for (const Case& c :
       {Case{m_a, 1.0, 1, 1e-14}, Case{0.5 * m_a, 1.0, 40, 1e-14}, Case{0.0, 0.5, 60, 1e-14}}) {
    Dfbi dfbi(point_body(m, c.estimate, c.relax));
    dfbi.reset(BodyState{});
    (void)run(dfbi, fluid, 10, dt, c.corrections, true);
    EXPECT_NEAR(dfbi.acceleration()[0], exact, c.tolerance) << "estimate " << c.estimate;
    // Euler, then BDF2, are exact for a constant acceleration: u = a t, x = a t^2 / 2.
    EXPECT_NEAR(dfbi.state().u(), exact * 10 * dt, 1e-13) << "estimate " << c.estimate;
    EXPECT_NEAR(dfbi.state().position.x(), 0.5 * exact * std::pow(10 * dt, 2), 1e-13);
  }
  // No estimate, unrelaxed: the factor -m_a / m = -2, the iterates run away.
  Dfbi naive(point_body(m, 0.0, 1.0));
  naive.reset(BodyState{});
  EXPECT_GT(run(naive, fluid, 1, dt, 20), 1e3);
}

TEST(Dfbi, IsSecondOrderInTimeForADampedBody) {
  const double m = 1.0, m_a = 0.8, d = 2.0, T = 1.0;
  const ModelFluid fluid{m_a, d, 0};
  std::array<double, 3> error{};
  for (int level = 0; level < 3; ++level) {
    const int steps = 20 << level;
    Dfbi dfbi(point_body(m, m_a, 1.0));
    BodyState s;
    s.nu[0] = 1.5;
    dfbi.reset(s);
    const double dt = T / steps;
    (void)run(dfbi, fluid, steps, dt, 3, true);
    error[static_cast<std::size_t>(level)] =
        std::abs(dfbi.state().u() - 1.5 * std::exp(-d * T / (m + m_a)));
  }
  EXPECT_NEAR(std::log2(error[0] / error[1]), 2.0, 0.15);
  EXPECT_NEAR(std::log2(error[1] / error[2]), 2.0, 0.1);
}

TEST(Dfbi, HoldsWhatIsHeldAndTurnsInACircle) {
  DfbiBody b = point_body(2.0, 1.0, 1.0);
  b.free = DfbiBody::horizontal;
  Dfbi dfbi(b);
  BodyState s;
  s.nu << 1.54, 0, 0, 0, 0, 0.4;  // a steady turn of radius u / r
  dfbi.reset(s);
  const double dt = 0.005;
  const int steps = 800;
  for (int n = 0; n < steps; ++n) {
    dfbi.begin_step(dt, true);
    Vector6d tau = Vector6d::Zero();
    tau << 0, 2.0 * 1.54 * 0.4, 50, 7, -9, 0;  // the centripetal force; heave, roll, pitch loads
    dfbi.correct(tau);
    dfbi.accept();
  }
  const auto& e = dfbi.state();
  EXPECT_EQ(e.w(), 0.0);
  EXPECT_EQ(e.p(), 0.0);
  EXPECT_EQ(e.q(), 0.0);
  EXPECT_NEAR(e.euler().phi, 0.0, 1e-15);
  EXPECT_NEAR(e.euler().theta, 0.0, 1e-15);
  EXPECT_NEAR(e.u(), 1.54, 1e-12);
  EXPECT_NEAR(e.r(), 0.4, 1e-12);
  // About a fixed axis the heading advances exactly; the position lies on the circle of radius
  // u / r about (0, u / r) to the kinematics' second order.
  EXPECT_NEAR(e.euler().psi, wrap_angle(0.4 * dt * steps), 1e-12);
  const double R = 1.54 / 0.4;
  EXPECT_NEAR((e.position.head<2>() - Eigen::Vector2d(0, R)).norm(), R, 1e-5 * R);
}

TEST(Dfbi, ARestoreContinuesBitwiseAndBadSettingsAreNamed) {
  const ModelFluid fluid{0.7, 1.3, 2.0};
  Dfbi a(point_body(1.0, 0.5, 0.8));
  a.reset(BodyState{});
  (void)run(a, fluid, 7, 0.01, 4);
  const DfbiHistory saved = a.history();
  (void)run(a, fluid, 5, 0.01, 4);
  Dfbi b(point_body(1.0, 0.5, 0.8));
  b.restore(saved);
  (void)run(b, fluid, 5, 0.01, 4);
  EXPECT_EQ(a.state().nu, b.state().nu);
  EXPECT_EQ(a.state().position, b.state().position);
  EXPECT_EQ(a.state().attitude.coeffs(), b.state().attitude.coeffs());
  EXPECT_THROW(Dfbi(point_body(1.0, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(Dfbi(point_body(1.0, 0.0, 1.5)), std::invalid_argument);
  EXPECT_THROW(Dfbi(point_body(-1.0, 0.0, 1.0)), std::invalid_argument);
  DfbiBody skew = point_body(1.0, 0.0, 1.0);
  skew.added_mass(0, 5) = 0.3;
  EXPECT_THROW(Dfbi{skew}, std::invalid_argument);
  Dfbi c(point_body(1.0, 0.0, 1.0));
  EXPECT_THROW(c.begin_step(0.0, true), std::invalid_argument);
}
