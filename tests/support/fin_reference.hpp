// SPDX-License-Identifier: GPL-3.0-or-later
// Wall area and volume of a NACA 00xx fin (closed trailing edge) between its root face, a gap
// above the hull, and its tip, by quadrature of the formulas alone: Abbott & von Doenhoff's
// thickness polynomial, the file's straight planform lines and the Myring radius. Written here
// independently of geometry::FinGeometry and the mesher (only MyringProfile, checked against
// the published hull volume elsewhere, is shared).
#pragma once

#include <cmath>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/vehicle.hpp"

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

// The planform as the file gives it: chord and leading edge (m aft of the post) linear in rho,
// the distance from the hull axis along the post (a tapered fin: dc != 0).
struct Planform {
  double rho0, c0, dc, le0, dle;  // at the root station rho0 and their slopes
  explicit Planform(const geometry::FinSetParameters& s)
      : rho0(s.root_radius()),
        c0(s.root_chord),
        dc((s.tip_chord - s.root_chord) / s.span),
        le0(s.root_le_station - s.post_station),
        dle(std::tan(s.sweep)) {}
  [[nodiscard]] double chord(double rho) const { return c0 + dc * (rho - rho0); }
  [[nodiscard]] double le(double rho) const { return le0 + dle * (rho - rho0); }
  // Antiderivatives in rho of chord and chord^2.
  [[nodiscard]] double chord_integral(double rho) const {
    return (std::pow(chord(rho), 2) - c0 * c0) / (2 * dc);
  }
  [[nodiscard]] double chord2_integral(double rho) const {
    return (std::pow(chord(rho), 3) - c0 * c0 * c0) / (3 * dc);
  }
};

// Root face at chord fraction x: the chord line's point with rho = R(station) + gap, by fixed
// point iteration (the hull slope times the planform's drift per unit rho is far below one).
inline double root_rho(const geometry::FinSetParameters& s, const geometry::MyringProfile& hull,
                       double x) {
  const Planform p(s);
  double rho = s.root_radius();
  for (int i = 0; i < 200; ++i) {
    rho = hull.radius(s.post_station + p.le(rho) + p.chord(rho) * x) + s.root_gap;
  }
  return rho;
}

inline Measures exact_fin(const geometry::FinSetParameters& s,
                          const geometry::MyringProfile& hull) {
  const double t = s.section.thickness_percent / 100.0, tip = s.tip_radius;
  const Planform p(s);
  const auto root = [&](double u) { return root_rho(s, hull, u * u); };
  Measures m;
  // Sides (the ruled surface between similar sections): |P_u x P_rho| = c sqrt(x_u^2 + y_u^2 +
  // (x_u c' y - y_u (le' + c' x))^2), integrated over rho from the root face to the tip.
  const double sides =
      2 * geometry::integrate(
              [&](double u) {
                const double x = u * u, xu = 2 * u, y = y_of(t, u), yu = dy_du(t, u);
                const double g = std::sqrt(xu * xu + yu * yu +
                                           std::pow(xu * p.dc * y - yu * (p.dle + p.dc * x), 2));
                return g * (p.chord_integral(tip) - p.chord_integral(root(u)));
              },
              0.0, 1.0, 200);
  // Root face: lines along the section normal, 2 c y long, over the root curve (rho_r, s_r) in
  // the plane of post and chord.
  const double root_face = geometry::integrate(
      [&](double u) {
        const double h = 1e-6, r = root(u);
        const auto s_of = [&](double uu) {
          const double rr = root(uu);
          return p.le(rr) + p.chord(rr) * uu * uu;
        };
        const double dr = (root(u + h) - root(u - h)) / (2 * h);
        const double ds = (s_of(u + h) - s_of(u - h)) / (2 * h);
        return 2 * p.chord(r) * y_of(t, u) * std::hypot(dr, ds);
      },
      0.0, 1.0, 200);
  const double ct = s.tip_chord;
  m.area = sides + root_face + section_area(t) * ct * ct;
  // Volume: the section at rho has area c(rho)^2 times the unit section; in (rho, x) the solid is
  // rho_r(x) <= rho <= tip, so V = int 2 y(x) (D(tip) - D(rho_r(x))) dx with D' = c^2.
  m.volume = geometry::integrate(
      [&](double u) {
        return 2 * y_of(t, u) * (p.chord2_integral(tip) - p.chord2_integral(root(u))) * 2 * u;
      },
      0.0, 1.0, 200);
  return m;
}

}  // namespace auvloop::test
