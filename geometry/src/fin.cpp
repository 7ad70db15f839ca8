// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/fin.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace auvloop::geometry {

FinGeometry::FinGeometry(const FinSetParameters& set, const FinPlacement& placement,
                         const MyringProfile& hull, double cb_station)
    : set_(set),
      placement_(placement),
      hull_(hull),
      e_span_(0.0, std::sin(placement.roll), -std::cos(placement.roll)),
      e_chord_(-1.0, 0.0, 0.0),
      e_normal_(e_span_.cross(e_chord_)),
      post_origin_(cb_station - set.post_station, 0.0, 0.0) {}

double FinGeometry::chord_at(double rho) const {
  const double t = (rho - set_.root_radius()) / set_.span;
  return set_.root_chord + t * (set_.tip_chord - set_.root_chord);
}

double FinGeometry::le_offset_at(double rho) const {
  return set_.root_le_station - set_.post_station +
         (rho - set_.root_radius()) * std::tan(set_.sweep);
}

double FinGeometry::root_rho_at_offset(double s) const {
  // The chord line lies in the meridian plane of the post, so its distance from the hull axis is
  // rho itself and its station is post_station + s.
  const double station = set_.post_station + s;
  if (station < 0 || station > hull_.length()) return std::numeric_limits<double>::infinity();
  return hull_.radius(station) + set_.root_gap;
}

double FinGeometry::root_rho(double x) const {
  // rho - root_rho_at_offset(s(rho)) rises with rho (the hull slope times ds/drho stays far below
  // one for any sensible planform), so bisection between the axis and the tip finds the root.
  double lo = 0, hi = set_.tip_radius;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * set_.tip_radius; ++it) {
    const double mid = 0.5 * (lo + hi);
    (mid < root_rho_at_offset(le_offset_at(mid) + x * chord_at(mid)) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double FinGeometry::hull_clearance(double deflection) const {
  double clearance = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 100; ++i) {
    const double x = i / 100.0, rho = root_rho(x);
    const Eigen::Vector3d upper = point(rho, x, 1, deflection),
                          lower = point(rho, x, -1, deflection);
    // The edges and the middle of the root face's line across the section (the part nearest the
    // axis on a turned fin).
    for (const Eigen::Vector3d& p : {upper, lower, Eigen::Vector3d(0.5 * (upper + lower))}) {
      const double station = set_.post_station + post_origin_.x() - p.x();
      const double outside = station < 0 || station > hull_.length() ? 0 : hull_.radius(station);
      clearance = std::min(clearance, std::hypot(p.y(), p.z()) - outside);
    }
  }
  return clearance;
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
  if (rho < root_rho_at_offset(q.dot(e_chord_)) || rho > set_.tip_radius) return false;
  const double c = chord_at(rho);
  const double x = (q.dot(e_chord_) - le_offset_at(rho)) / c;
  if (x < 0 || x > 1) return false;
  return std::abs(q.dot(e_normal_)) <= c * set_.section.half_thickness(x);
}

double FinGeometry::planform_area() const {
  return 0.5 * (set_.root_chord + set_.tip_chord) * set_.span;
}

}  // namespace auvloop::geometry
