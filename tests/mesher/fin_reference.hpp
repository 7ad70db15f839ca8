// SPDX-License-Identifier: GPL-3.0-or-later
// Closed-form wall area and volume of a NACA 00xx fin (closed trailing edge), from Abbott & von
// Doenhoff's thickness polynomial, written here independently of geometry/ and mesher/.
#pragma once

#include <cmath>

#include "auvloop/geometry/fin.hpp"
#include "auvloop/geometry/myring.hpp"

namespace auvloop::test {

struct Measures {
  double area = 0, volume = 0;
};

// NACA 00tt with the closed trailing edge in u = sqrt(x/c): x = u^2 and the thickness
// y = 5 t (0.2969 u - 0.1260 u^2 - 0.3516 u^4 + 0.2843 u^6 - 0.1036 u^8), a polynomial.
inline double y_of(double t, double u) {
  return 5 * t *
         (0.2969 * u - 0.1260 * u * u - 0.3516 * std::pow(u, 4) + 0.2843 * std::pow(u, 6) -
          0.1036 * std::pow(u, 8));
}
inline double dy_du(double t, double u) {
  return 5 * t *
         (0.2969 - 0.2520 * u - 1.4064 * std::pow(u, 3) + 1.7058 * std::pow(u, 5) -
          0.8288 * std::pow(u, 7));
}
// Section area per chord^2: int_0^1 2 y dx, term by term.
inline double section_area(double t) {
  return 10 * t * (0.2969 * 2 / 3 - 0.1260 / 2 - 0.3516 / 3 + 0.2843 / 4 - 0.1036 / 5);
}

// Area of both sides of a ruled piece between similar sections, per unit integral of chord over
// the span: |P_u x P_rho| / c = sqrt(x_u^2 + y_u^2 + (x_u c' y - y_u (le' + c' x))^2).
inline double side_factor(double t, double dc, double dle) {
  return 2 *
         geometry::integrate(
             [&](double u) {
               const double x = u * u, xu = 2 * u, y = y_of(t, u), yu = dy_du(t, u);
               return std::sqrt(xu * xu + yu * yu + std::pow(xu * dc * y - yu * (dle + dc * x), 2));
             },
             0.0, 1.0, 200);
}

inline Measures exact_fin(const geometry::FinGeometry& fin) {
  const auto& s = fin.set();
  const double t = s.section.thickness_percent / 100.0, cr = s.root_chord, ct = s.tip_chord;
  const double dc = (ct - cr) / s.span, dle = std::tan(s.sweep);
  Measures m;
  m.area = side_factor(t, 0, 0) * cr * s.embed_depth +
           side_factor(t, dc, dle) * 0.5 * (cr + ct) * s.span + section_area(t) * ct * ct;
  m.volume =
      section_area(t) * (cr * cr * s.embed_depth + s.span * (cr * cr + cr * ct + ct * ct) / 3);
  return m;
}

}  // namespace auvloop::test
