// SPDX-License-Identifier: GPL-3.0-or-later
// The Myring hull profile r(station) and the properties of the body of revolution it generates.
#pragma once

#include "auvloop/geometry/vehicle.hpp"

namespace auvloop::geometry {

class MyringProfile {
 public:
  explicit MyringProfile(const MyringParameters& p);

  [[nodiscard]] double length() const { return length_; }          // l = l_f + c - c_offset
  [[nodiscard]] double nose_end() const { return nose_end_; }      // a - a_offset
  [[nodiscard]] double tail_start() const { return tail_start_; }  // l_f = a - a_offset + b
  [[nodiscard]] double max_radius() const { return p_.d / 2; }
  // Radius (m) at a station (m aft of the nose tip), 0 <= station <= length().
  [[nodiscard]] double radius(double station) const;
  [[nodiscard]] double slope(double station) const;  // dr / dstation
  [[nodiscard]] const MyringParameters& parameters() const { return p_; }

 private:
  MyringParameters p_;
  double nose_end_, tail_start_, length_;
};

// Properties of the hull of revolution without fins, by Gauss-Legendre quadrature of the profile
// (exact to round-off for this smooth profile).
struct HullProperties {
  double length = 0;              // m
  double volume = 0;              // m^3
  double wetted_area_curved = 0;  // m^2, curved surface only
  double end_face_area = 0;       // m^2, flat nose and tail faces together
  double frontal_area = 0;        // m^2, pi d^2 / 4
  double projected_area = 0;      // m^2, side (planform) projection, integral of 2 r
  double centroid_station = 0;    // m aft of nose: volume centroid (centre of buoyancy of the hull)
  double nose_radius = 0;         // m, radius of the flat nose face
  double tail_radius = 0;         // m, radius of the flat tail face
};

HullProperties hull_properties(const MyringProfile& profile);

// Quadrature helper shared by the profile properties: integral of f over [a, b] by composite
// 8-point Gauss-Legendre on `panels` equal panels.
template <class F>
double integrate(F&& f, double a, double b, int panels = 64);

}  // namespace auvloop::geometry

#include "auvloop/geometry/detail/integrate.ipp"
