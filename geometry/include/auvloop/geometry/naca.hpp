// SPDX-License-Identifier: GPL-3.0-or-later
// NACA four-digit wing sections (Abbott & von Doenhoff, Theory of Wing Sections, 1959, sec. 6.4).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace auvloop::geometry {

struct NacaSection {
  int max_camber_percent = 0;      // first digit: maximum camber, % chord
  int camber_position_tenths = 0;  // second digit: position of maximum camber, tenths of chord
  int thickness_percent = 12;      // last two digits: maximum thickness, % chord
  // Sharp: the closed-trailing-edge variant (x^4 coefficient -0.1036), so that the section ends in
  // a point. Blunt: the classical coefficient -0.1015, leaving a trailing-edge base of 0.126 % t/c.
  bool sharp_trailing_edge = true;

  // Accepts "NACA0012", "NACA 0012" or "0012" (case-insensitive).
  static std::optional<NacaSection> parse(std::string_view designation);
  [[nodiscard]] std::string designation() const;  // "NACA 0012"

  // Half thickness y_t / c at x / c in [0, 1], measured normal to the mean line.
  [[nodiscard]] double half_thickness(double x) const;
  [[nodiscard]] double camber(double x) const;        // mean line y_c / c
  [[nodiscard]] double camber_slope(double x) const;  // dy_c / dx
  // Upper (side = +1) or lower (side = -1) surface point for unit chord.
  [[nodiscard]] Eigen::Vector2d surface(double x, int side) const;
};

}  // namespace auvloop::geometry
