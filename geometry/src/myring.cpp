// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/myring.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace auvloop::geometry {

MyringProfile::MyringProfile(const MyringParameters& p)
    : p_(p),
      nose_end_(p.a - p.a_offset),
      tail_start_(p.a - p.a_offset + p.b),
      length_(p.a - p.a_offset + p.b + p.c - p.c_offset) {}

// Tail: r = d/2 - (3d/(2c^2) - tan(theta)/c) t^2 + (d/c^3 - tan(theta)/c^2) t^3, t = station - l_f.
// Prestero's thesis prints (x - l) where t = x - l_f is meant; only the latter gives r = d/2 at
// l_f.
double MyringProfile::radius(double station) const {
  const double x = std::clamp(station, 0.0, length_);
  const double r_max = p_.d / 2;
  if (x < nose_end_) {
    const double s = (x + p_.a_offset - p_.a) / p_.a;
    return r_max * std::pow(std::max(0.0, 1 - s * s), 1 / p_.n);
  }
  if (x <= tail_start_) return r_max;
  const double t = x - tail_start_;
  const double tn = std::tan(p_.theta);
  const double c2 = 3 * p_.d / (2 * p_.c * p_.c) - tn / p_.c;
  const double c3 = p_.d / (p_.c * p_.c * p_.c) - tn / (p_.c * p_.c);
  return r_max - c2 * t * t + c3 * t * t * t;
}

double MyringProfile::slope(double station) const {
  const double x = std::clamp(station, 0.0, length_);
  const double r_max = p_.d / 2;
  if (x < nose_end_) {
    const double s = (x + p_.a_offset - p_.a) / p_.a;
    const double q = std::max(1e-300, 1 - s * s);
    return r_max * (1 / p_.n) * std::pow(q, 1 / p_.n - 1) * (-2 * s / p_.a);
  }
  if (x <= tail_start_) return 0.0;
  const double t = x - tail_start_;
  const double tn = std::tan(p_.theta);
  const double c2 = 3 * p_.d / (2 * p_.c * p_.c) - tn / p_.c;
  const double c3 = p_.d / (p_.c * p_.c * p_.c) - tn / (p_.c * p_.c);
  return -2 * c2 * t + 3 * c3 * t * t;
}

HullProperties hull_properties(const MyringProfile& profile) {
  constexpr double pi = std::numbers::pi;
  // Integrate piecewise: the profile is smooth inside nose, body and tail but not across them.
  const double breaks[] = {0.0, profile.nose_end(), profile.tail_start(), profile.length()};
  auto over_hull = [&](auto&& f) {
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
      if (breaks[i + 1] > breaks[i]) sum += integrate(f, breaks[i], breaks[i + 1], 256);
    }
    return sum;
  };
  HullProperties h;
  h.length = profile.length();
  h.volume = over_hull([&](double x) { return pi * std::pow(profile.radius(x), 2); });
  h.centroid_station =
      over_hull([&](double x) { return x * pi * std::pow(profile.radius(x), 2); }) / h.volume;
  h.wetted_area_curved = over_hull([&](double x) {
    return 2 * pi * profile.radius(x) * std::sqrt(1 + std::pow(profile.slope(x), 2));
  });
  h.projected_area = over_hull([&](double x) { return 2 * profile.radius(x); });
  h.nose_radius = profile.radius(0);
  h.tail_radius = profile.radius(profile.length());
  h.end_face_area = pi * (h.nose_radius * h.nose_radius + h.tail_radius * h.tail_radius);
  h.frontal_area = pi * profile.max_radius() * profile.max_radius();
  return h;
}

}  // namespace auvloop::geometry
