// SPDX-License-Identifier: GPL-3.0-or-later
// Prestero's hydrodynamic-derivative model of REMUS 100 (T. Prestero, MIT/WHOI S.M. thesis, 2001,
// Appendix B/C): the nonlinear six-degree-of-freedom equations his simulator runs, origin at CB.
// Every coefficient is read from the vehicle file's [hydrodynamics] table with its source; the
// known inconsistencies of the thesis are explicit options (docs/derivative-plant.md).
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "auvloop/engine/rigid_body.hpp"
#include "auvloop/geometry/input.hpp"
#include "auvloop/geometry/vehicle.hpp"

namespace auvloop::engine {

struct PresteroCoefficients {
  // Names follow the thesis: X_uu is dX / d(u|u|), Y_uudr is dY / d(u^2 delta_r), and so on.
  double X_uu = 0, X_udot = 0, X_wq = 0, X_qq = 0, X_vr = 0, X_rr = 0;
  double Y_vv = 0, Y_rr = 0, Y_uv = 0, Y_vdot = 0, Y_rdot = 0, Y_ur = 0, Y_wp = 0, Y_pq = 0,
         Y_uudr = 0;
  double Z_ww = 0, Z_qq = 0, Z_uw = 0, Z_wdot = 0, Z_qdot = 0, Z_uq = 0, Z_vp = 0, Z_rp = 0,
         Z_uuds = 0;
  double K_pp = 0, K_pdot = 0;
  double M_ww = 0, M_qq = 0, M_uw = 0, M_wdot = 0, M_qdot = 0, M_uq = 0, M_vp = 0, M_rp = 0,
         M_uuds = 0;
  double N_vv = 0, N_rr = 0, N_uv = 0, N_vdot = 0, N_rdot = 0, N_ur = 0, N_wp = 0, N_pq = 0,
         N_uudr = 0;

  // Propeller: thrust X_prop (N) and torque K_prop (N m) at reference_rpm, scaled by (n / n_ref)^2
  // (the thesis gives them at 1500 rpm only).
  double X_prop = 0, K_prop = 0, reference_rpm = 0;
  // Multiplies the four fin coefficients (Y_uudr, N_uudr, Z_uuds, M_uuds). 1: as printed, read as
  // the force of the fin pair; 2: the printed values taken as one fin's, doubled for the pair.
  double fin_pair_factor = 1;

  std::string source;                        // provenance of the set
  std::map<std::string, std::string> notes;  // per-coefficient provenance where given

  // Name, unit and member of every coefficient, for reading, writing and reporting.
  struct Field {
    std::string_view name;
    std::string_view unit;
    double PresteroCoefficients::*member;
  };
  static const std::vector<Field>& fields();
};

// Reads [hydrodynamics] (model = "prestero2001"); problems go to the table's document.
PresteroCoefficients read_prestero(input::Table hydrodynamics);

// The added-mass matrix of the coefficients (kg, kg m, kg m^2; body axes about CB): minus the
// acceleration derivatives, -X_udot ... -N_rdot on the diagonal and -Y_rdot, -N_vdot, -Z_qdot,
// -M_wdot off it, made symmetric (the mean of a pair; the thesis prints equal pairs). The CFD
// plant's coupling estimate (dfbi.hpp).
Matrix6d prestero_added_mass(const PresteroCoefficients& c);

// How the weight-buoyancy difference enters. REMUS 100 is 7 N positively buoyant (W = 299 N,
// B = 306 N). With no depth control, that makes it rise; the Munk moment M_uw u w of the rising
// body (about -5.5 N m) outweighs the metacentric restoring moment (z_g W = 5.9 N m at most), so it
// pitches nose down and X = -(W - B) sin(theta) brakes it. The published behaviour of Prestero's
// model (yaw ramp: -39 deg at 5 s, r -> -9 deg/s, u -> 1.38-1.40 m/s) is reproduced with B = W,
// which is therefore what horizontal-plane manoeuvres use by default (docs/derivative-plant.md).
enum class Buoyancy {
  neutral,  // B = W: horizontal-plane manoeuvres without a depth controller
  vehicle,  // B from the vehicle file
};

// The model's forces and mass matrix for a given vehicle. Body-frame origin at CB (x_b = 0).
class PresteroModel {
 public:
  PresteroModel(const geometry::Vehicle& vehicle, const PresteroCoefficients& c,
                Buoyancy buoyancy = Buoyancy::neutral);

  // Rigid-body plus added mass, the matrix multiplying nu' in Prestero's equations.
  [[nodiscard]] const Matrix6d& mass_matrix() const { return mass_; }
  // External and Coriolis/centripetal terms [X Y Z K M N] for the state and actuator values
  // (angles in rad, rpm in rev/min).
  [[nodiscard]] Vector6d forces(const Vector6d& nu, double phi, double theta, double delta_r,
                                double delta_s, double rpm) const;
  // nu' = M^-1 * forces.
  [[nodiscard]] Vector6d acceleration(const Vector6d& nu, double phi, double theta, double delta_r,
                                      double delta_s, double rpm) const;
  [[nodiscard]] const PresteroCoefficients& coefficients() const { return c_; }
  // Forward speed at which thrust balances X_uu drag at `rpm`.
  [[nodiscard]] double equilibrium_speed(double rpm) const;

 private:
  PresteroCoefficients c_;
  double m_, W_, B_;
  Eigen::Vector3d rg_;
  Eigen::Vector3d inertia_;  // Ixx, Iyy, Izz about CB
  Matrix6d mass_;
  Eigen::PartialPivLU<Matrix6d> mass_lu_;
};

}  // namespace auvloop::engine
