// SPDX-License-Identifier: GPL-3.0-or-later
// The propeller of the CFD plant (issue 18, item 2; ../shared/reference/propeller.md): its
// open-water curves and the body-force disk that stands for it in the flow.
//   1. open water: KT(J) and KQ(J), from the Wageningen B-series polynomials (Oosterveld and van
//      Oossanen 1975, Re = 2e6: KT = sum C J^s (P/D)^t (AE/A0)^u Z^v, 39 terms; KQ likewise, 47)
//      or from a table of (J, KT, KQ) interpolated linearly, with T = KT rho n^2 D^4 and
//      Q = KQ rho n^2 D^5 (n in rev/s);
//   2. the Hough-Ordway disk: between the hub radius R_H and the tip radius R_P, over a disk of
//      thickness Delta, with r' = r / R_P, r_h' = R_H / R_P and r* = (r' - r_h') / (1 - r_h'),
//        axial       f_x     = A_x r* sqrt(1 - r*),
//        tangential  f_theta = A_theta r* sqrt(1 - r*) / (r* (1 - r_h') + r_h'),
//      A_x = 105 T / (8 pi Delta (R_P - R_H) (3 R_H + 4 R_P)) and A_theta = 105 Q / (8 pi Delta
//      R_P (R_P - R_H) (3 R_H + 4 R_P)), which integrate over the disk to T and Q exactly
//      (since r f_theta = A_theta R_P r* sqrt(1 - r*)). Per unit density: T in m^4/s^2, f in
//      m/s^2 (force per unit mass of fluid).
// Directions: the thrust axis n_hat is the unit vector along which the disk pushes the vehicle
// (forward, +x body for REMUS); the fluid receives the axial force -f_x n_hat (thrown aft). With
// `sense` +1 the propeller turns right-handed about n_hat; the blades drag the fluid round with
// them, so the fluid receives the tangential force f_theta sense (n_hat x r_hat) and the torque
// +Q sense n_hat about the axis; the vehicle receives the reactions, thrust +T n_hat and torque
// -Q sense n_hat (the hull's counter-torque to the motor).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace auvloop::engine {

struct OpenWaterPoint {
  double J = 0;  // advance ratio V_a / (n D)
  double KT = 0, KQ = 0;
};

// A Wageningen B-series propeller. The polynomials are fitted for Z 2-7, AE/A0 0.30-1.05, P/D
// 0.5-1.4 and J up to where KT vanishes; b_series_range_problem says which bound a propeller
// breaks (none: std::nullopt).
struct BSeries {
  int blades = 3;             // Z
  double pitch_ratio = 1.0;   // P/D
  double area_ratio = 0.718;  // AE/A0
};
std::optional<std::string> b_series_range_problem(const BSeries& p);
OpenWaterPoint b_series(const BSeries& p, double J);

// A measured or computed open-water table, J strictly increasing, at least two points; at(J)
// interpolates linearly and holds the end values beyond the ends (clamped tells whether it did).
// The constructor throws std::invalid_argument naming the first bad point.
class OpenWaterTable {
 public:
  explicit OpenWaterTable(std::vector<OpenWaterPoint> points);
  OpenWaterPoint at(double J, bool* clamped = nullptr) const;
  const std::vector<OpenWaterPoint>& points() const { return points_; }

 private:
  std::vector<OpenWaterPoint> points_;
};

// The operating point from the disk's inflow (OpenFOAM's propellerDisk, propeller.md section 3):
// with u_d the mean axial speed over the disk (fv::DiskForce::disk_speed), J0 = u_d / (n D) and
// T0 = KT(J0) n^2 D^4, the disk's own induction u_i = T0 / (2 u_d A) (A = pi D^2 / 4, light
// loading) is taken off once: J = (u_d - u_i) / (n D), T = KT(J) n^2 D^4, Q = KQ(J) n^2 D^5 (per
// unit density; n in rev/s, its magnitude; the caller gives the disk the sense of n). With
// n = 0 nothing is produced; with u_d <= 0 the point is the bollard pull (J = 0).
struct OperatingPoint {
  double J = 0, KT = 0, KQ = 0;
  double thrust = 0, torque = 0;  // m^4/s^2, m^5/s^2
};
OperatingPoint operating_point(const std::function<OpenWaterPoint(double)>& curve, double n,
                               double D, double disk_speed);

// The disk of step 2 (m). Invariants (checked by hough_ordway): 0 <= hub_radius < radius,
// thickness > 0, |axis| = 1.
struct PropellerDisk {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // n_hat, the thrust on the vehicle
  double radius = 0.07, hub_radius = 0.02, thickness = 0.01;
  int sense = 1;  // +1: turning right-handed about axis
};

// The force per unit mass the fluid receives at x (m/s^2) for thrust T (m^4/s^2) and torque Q
// (m^5/s^2), both per unit density and non-negative: zero outside the disk (axial distance
// beyond thickness / 2, r outside [R_H, R_P]). Throws std::invalid_argument on a bad disk.
Eigen::Vector3d hough_ordway(const PropellerDisk& disk, double T, double Q,
                             const Eigen::Vector3d& x);

}  // namespace auvloop::engine
