// SPDX-License-Identifier: GPL-3.0-or-later
// One fin of the set as a solid in the body frame, before triangulation.
//
// The fin is a ruled solid between NACA sections stacked along its post axis. Its leading and
// trailing edges are the straight lines of the file's planform (given at the root station
// rho = tip_radius - span and at the tip), and it ends at the tip plane and at a root face that
// follows the hull a gap away, as on the vehicle and in the paper's grids: the root face is the
// ruled surface, along the section normal, over the curve rho = R(station) + root_gap of the chord
// line (R the hull radius; the REMUS hull radius under a fin falls from 62 mm at the leading edge
// to 36 mm at the trailing edge). Fin and hull never touch, so the overset grids need no junction:
// the hull grid's wall layers fill the gap.
#pragma once

#include <Eigen/Core>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/vehicle.hpp"

namespace auvloop::geometry {

class FinGeometry {
 public:
  FinGeometry(const FinSetParameters& set, const FinPlacement& placement, const MyringProfile& hull,
              double cb_station);

  [[nodiscard]] const std::string& name() const { return placement_.name; }
  [[nodiscard]] const FinSetParameters& set() const { return set_; }
  // Unit vector along the fin post, pointing out of the hull (the deflection axis, right-handed).
  [[nodiscard]] const Eigen::Vector3d& span_axis() const { return e_span_; }
  // Unit vector along the chord, leading edge to trailing edge (body -x).
  [[nodiscard]] const Eigen::Vector3d& chord_axis() const { return e_chord_; }
  // Unit normal of the undeflected fin plane: span_axis x chord_axis ("upper" section side).
  [[nodiscard]] const Eigen::Vector3d& normal_axis() const { return e_normal_; }
  // Point of the post on the hull axis, body frame (m).
  [[nodiscard]] const Eigen::Vector3d& post_origin() const { return post_origin_; }

  // Planform lines, extended below the root station down to the root face.
  [[nodiscard]] double chord_at(double rho) const;      // m
  [[nodiscard]] double le_offset_at(double rho) const;  // m aft of the post, leading edge
  // Root face: rho (m from the hull axis along the post) of the chord line's root point at
  // chord fraction x in [0, 1], and of the point `s` (m aft of the post along the chord axis).
  [[nodiscard]] double root_rho(double x) const;
  [[nodiscard]] double root_rho_at_offset(double s) const;
  // Smallest radial clearance (m) between the root face's edges (both sides) and the hull at a
  // deflection (rad): root_gap at zero deflection; turned, the trailing part of the root moves
  // forward over a thicker hull (REMUS: 2.45 mm of 3 mm at 35 deg).
  [[nodiscard]] double hull_clearance(double deflection) const;
  // Body-frame point of the section surface at radius rho, chord fraction x in [0, 1], side +-1.
  [[nodiscard]] Eigen::Vector3d point(double rho, double x, int side, double deflection) const;
  // Rotation about the post axis taking undeflected points to the deflected fin.
  [[nodiscard]] Eigen::Matrix3d rotation(double deflection) const;
  // Exact inside test of the analytic solid for symmetric sections (NACA 00xx).
  [[nodiscard]] bool contains(const Eigen::Vector3d& p_body, double deflection) const;
  // Nominal planform area (m^2): the file's trapezoid between root station and tip.
  [[nodiscard]] double planform_area() const;

 private:
  FinSetParameters set_;
  FinPlacement placement_;
  MyringProfile hull_;
  Eigen::Vector3d e_span_, e_chord_, e_normal_, post_origin_;
};

}  // namespace auvloop::geometry
