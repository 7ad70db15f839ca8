// SPDX-License-Identifier: GPL-3.0-or-later
// One fin of the set as a solid in the body frame, before triangulation.
//
// The fin is a ruled solid between NACA sections stacked along its post axis: from the root station
// (rho = tip_radius - span, where the planform of the file starts) to the tip, plus a prismatic
// extension of the root section down to rho = root_radius - embed_depth so that the fin solid
// crosses the tapering hull surface completely at every deflection (the hull radius under a REMUS
// fin falls from 62 mm at the leading edge to 36 mm at the trailing edge, while the root station is
// at 45 mm). The exposed fin is what remains outside the hull after the union.
#pragma once

#include <Eigen/Core>

#include "auvloop/geometry/vehicle.hpp"

namespace auvloop::geometry {

class FinGeometry {
 public:
  FinGeometry(const FinSetParameters& set, const FinPlacement& placement, double cb_station);

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

  [[nodiscard]] double inner_radius() const { return set_.root_radius() - set_.embed_depth; }
  [[nodiscard]] double chord_at(double rho) const;      // m
  [[nodiscard]] double le_offset_at(double rho) const;  // m aft of the post, leading edge
  // Body-frame point of the section surface at radius rho, chord fraction x in [0, 1], side +-1.
  [[nodiscard]] Eigen::Vector3d point(double rho, double x, int side, double deflection) const;
  // Rotation about the post axis taking undeflected points to the deflected fin.
  [[nodiscard]] Eigen::Matrix3d rotation(double deflection) const;
  // Exact inside test of the analytic solid for symmetric sections (NACA 00xx).
  [[nodiscard]] bool contains(const Eigen::Vector3d& p_body, double deflection) const;
  // Exposed planform area (m^2): trapezoid between root station and tip.
  [[nodiscard]] double planform_area() const;

 private:
  FinSetParameters set_;
  FinPlacement placement_;
  Eigen::Vector3d e_span_, e_chord_, e_normal_, post_origin_;
};

}  // namespace auvloop::geometry
