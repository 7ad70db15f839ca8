// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/naca.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

namespace auvloop::geometry {

std::optional<NacaSection> NacaSection::parse(std::string_view designation) {
  std::string s;
  for (char ch : designation) {
    if (!std::isspace(static_cast<unsigned char>(ch))) {
      s += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    }
  }
  if (s.starts_with("NACA")) s = s.substr(4);
  if (s.size() != 4 || !std::all_of(s.begin(), s.end(), [](char ch) { return std::isdigit(ch); })) {
    return std::nullopt;
  }
  NacaSection n;
  n.max_camber_percent = s[0] - '0';
  n.camber_position_tenths = s[1] - '0';
  n.thickness_percent = (s[2] - '0') * 10 + (s[3] - '0');
  // A cambered section needs the position of maximum camber; a zero thickness is no solid.
  if (n.thickness_percent == 0) return std::nullopt;
  if ((n.max_camber_percent == 0) != (n.camber_position_tenths == 0)) return std::nullopt;
  return n;
}

std::string NacaSection::designation() const {
  return fmt::format("NACA {}{}{:02d}", max_camber_percent, camber_position_tenths,
                     thickness_percent);
}

double NacaSection::half_thickness(double x) const {
  const double t = thickness_percent / 100.0;
  const double a4 = sharp_trailing_edge ? -0.1036 : -0.1015;
  x = std::clamp(x, 0.0, 1.0);
  return 5.0 * t * (0.2969 * std::sqrt(x) + x * (-0.1260 + x * (-0.3516 + x * (0.2843 + x * a4))));
}

double NacaSection::camber(double x) const {
  const double m = max_camber_percent / 100.0;
  const double p = camber_position_tenths / 10.0;
  if (m == 0.0) return 0.0;
  return x < p ? m / (p * p) * (2 * p * x - x * x)
               : m / ((1 - p) * (1 - p)) * (1 - 2 * p + 2 * p * x - x * x);
}

double NacaSection::camber_slope(double x) const {
  const double m = max_camber_percent / 100.0;
  const double p = camber_position_tenths / 10.0;
  if (m == 0.0) return 0.0;
  return x < p ? 2 * m / (p * p) * (p - x) : 2 * m / ((1 - p) * (1 - p)) * (p - x);
}

Eigen::Vector2d NacaSection::surface(double x, int side) const {
  const double yt = half_thickness(x);
  const double yc = camber(x);
  const double th = std::atan(camber_slope(x));
  return {x - side * yt * std::sin(th), yc + side * yt * std::cos(th)};
}

}  // namespace auvloop::geometry
