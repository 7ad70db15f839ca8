// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/fin.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace auvloop::geometry {

FinGeometry::FinGeometry(const FinSetParameters& set, const FinPlacement& placement,
                         double cb_station)
    : set_(set),
      placement_(placement),
      e_span_(0.0, std::sin(placement.roll), -std::cos(placement.roll)),
      e_chord_(-1.0, 0.0, 0.0),
      e_normal_(e_span_.cross(e_chord_)),
      post_origin_(cb_station - set.post_station, 0.0, 0.0) {}

double FinGeometry::chord_at(double rho) const {
  const double t = std::clamp((rho - set_.root_radius()) / set_.span, 0.0, 1.0);
  return set_.root_chord + t * (set_.tip_chord - set_.root_chord);
}

double FinGeometry::le_offset_at(double rho) const {
  const double above_root = std::max(0.0, rho - set_.root_radius());
  return set_.root_le_station - set_.post_station + above_root * std::tan(set_.sweep);
}

Eigen::Matrix3d FinGeometry::rotation(double deflection) const {
  return Eigen::AngleAxisd(deflection, e_span_).toRotationMatrix();
}

Eigen::Vector3d FinGeometry::point(double rho, double x, int side, double deflection) const {
  const double c = chord_at(rho);
  const Eigen::Vector2d s = set_.section.surface(x, side);
  const Eigen::Vector3d in_plane =
      (le_offset_at(rho) + c * s.x()) * e_chord_ + c * s.y() * e_normal_;
  return post_origin_ + rho * e_span_ + rotation(deflection) * in_plane;
}

bool FinGeometry::contains(const Eigen::Vector3d& p_body, double deflection) const {
  const Eigen::Vector3d q = rotation(-deflection) * (p_body - post_origin_);
  const double rho = q.dot(e_span_);
  if (rho < inner_radius() || rho > set_.tip_radius) return false;
  const double c = chord_at(rho);
  const double x = (q.dot(e_chord_) - le_offset_at(rho)) / c;
  if (x < 0 || x > 1) return false;
  return std::abs(q.dot(e_normal_)) <= c * set_.section.half_thickness(x);
}

double FinGeometry::planform_area() const {
  return 0.5 * (set_.root_chord + set_.tip_chord) * set_.span;
}

}  // namespace auvloop::geometry
