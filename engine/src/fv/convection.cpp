// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::div(F, phi): upwind in the matrix, the higher-order scheme as a deferred correction
// F (phi_f^scheme - phi_f^upwind) from the current iterate (Khosla and Rubin 1974), so the matrix
// stays an M-matrix and the converged solution is the scheme's.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "auvloop/engine/fv/operators.hpp"
#include "parallel.hpp"
#include "scratch.hpp"

namespace auvloop::engine::fv {

const char* to_string(Convection c) {
  switch (c) {
    case Convection::upwind:
      return "upwind";
    case Convection::linear_upwind:
      return "linear-upwind";
    case Convection::linear_upwind_limited:
      return "linear-upwind-limited";
    case Convection::van_leer:
      return "van-leer";
    case Convection::van_leer_skew:
      return "van-leer-skew";
  }
  return "?";
}

Convection convection_from_string(const std::string& s) {
  for (auto c : {Convection::upwind, Convection::linear_upwind, Convection::linear_upwind_limited,
                 Convection::van_leer, Convection::van_leer_skew})
    if (s == to_string(c)) return c;
  throw std::invalid_argument("unknown convection scheme '" + s +
                              "' (upwind, linear-upwind, linear-upwind-limited, van-leer, "
                              "van-leer-skew)");
}

namespace {
// van Leer's limited value at the mid-point of the upwind centre C and downwind centre D, with
// the Darwish-Moukalled ratio r = 2 grad(phi)_C . d_CD / (phi_D - phi_C) - 1.
double van_leer(double phiC, double phiD, const Eigen::Vector3d& gradC, const Eigen::Vector3d& xC,
                const Eigen::Vector3d& xD) {
  const double delta = phiD - phiC;
  if (std::abs(delta) < 1e-300) return phiC;
  const double r = 2 * gradC.dot(xD - xC) / delta - 1;
  const double psi = (r + std::abs(r)) / (1 + std::abs(r));
  return phiC + 0.5 * psi * delta;
}

// The range of phi over each cell and its face neighbours (boundary values included).
void neighbourhood_range(const Mesh& mesh, const ScalarField& phi,
                         std::span<std::pair<double, double>> r) {
  auto widen = [&](std::size_t c, double v) {
    r[c] = {std::min(r[c].first, v), std::max(r[c].second, v)};
  };
  const int internal = mesh.internal_faces();
  scatter_faces(
      mesh,
      [&](int b, int e) {
        for (auto c = static_cast<std::size_t>(b); c < static_cast<std::size_t>(e); ++c)
          r[c] = {phi.cells[c], phi.cells[c]};
      },
      [&](int f, bool own, bool nei) {
        const auto P = static_cast<std::size_t>(mesh.owner(f));
        if (f < internal) {
          const auto N = static_cast<std::size_t>(mesh.neighbour(f));
          if (own) widen(P, phi.cells[N]);
          if (nei) widen(N, phi.cells[P]);
        } else if (!phi.is_empty(mesh, f - internal)) {
          widen(P, phi.boundary[static_cast<std::size_t>(f - internal)]);
        }
      });
}

// Barth and Jespersen's limiter (Convection::linear_upwind_limited): out_c = psi_c grad_c with
// psi_c the largest value in [0, 1] for which phi_c + psi_c grad_c . (x_f - x_c) lies within
// range_c at the centre of every face f of c (boundary faces included, empty ones not; a
// periodic neighbour sees the face from its image, neighbour_centre). A minimum: exact in any
// order, so the same bits for any number of threads.
void limit_gradient(const Mesh& mesh, const ScalarField& phi, std::span<const Eigen::Vector3d> grad,
                    std::span<const std::pair<double, double>> range,
                    std::span<Eigen::Vector3d> out) {
  Scratch<double> psi(out.size());
  const auto limit = [&](std::size_t c, const Eigen::Vector3d& d) {
    const double delta = grad[c].dot(d);
    const double v = phi.cells[c];
    double l = 1;
    if (delta > 0) {
      l = (range[c].second - v) / delta;
    } else if (delta < 0) {
      l = (range[c].first - v) / delta;
    }
    (*psi)[c] = std::min((*psi)[c], std::max(0.0, l));
  };
  const int internal = mesh.internal_faces();
  scatter_faces(
      mesh,
      [&](int b, int e) {
        for (auto c = static_cast<std::size_t>(b); c < static_cast<std::size_t>(e); ++c)
          (*psi)[c] = 1;
      },
      [&](int f, bool own, bool nei) {
        const auto P = static_cast<std::size_t>(mesh.owner(f));
        if (f >= internal) {
          if (own && !phi.is_empty(mesh, f - internal))
            limit(P, mesh.face_centre(f) - mesh.centre(static_cast<int>(P)));
          return;
        }
        if (own) limit(P, mesh.face_centre(f) - mesh.centre(static_cast<int>(P)));
        if (nei)
          limit(static_cast<std::size_t>(mesh.neighbour(f)),
                mesh.face_centre(f) - mesh.neighbour_centre(f));
      });
  parallel_for(mesh.cells(), [&](int c) {
    const auto s = static_cast<std::size_t>(c);
    out[s] = (*psi)[s] * grad[s];
  });
}

// Face value of phi on the face between upwind cell C and downwind cell D; rangeC is the range
// of phi around C (van_leer_skew only).
double high_order(const Mesh& mesh, Convection scheme, int f, double phiC, double phiD,
                  const Eigen::Vector3d& gradC, const Eigen::Vector3d& xC,
                  const Eigen::Vector3d& xD, std::pair<double, double> rangeC) {
  switch (scheme) {
    case Convection::upwind:
      return phiC;
    case Convection::linear_upwind:
    case Convection::linear_upwind_limited:  // gradC is the limited gradient
      return phiC + gradC.dot(mesh.face_centre(f) - xC);
    case Convection::van_leer:
      return van_leer(phiC, phiD, gradC, xC, xD);
    case Convection::van_leer_skew: {
      // The shift is bounded by the range around C, not by [phi_C, phi_D]: on a face whose
      // centre line is nearly normal to grad(phi), phi_C ~ phi_D while the face centre's value
      // differs by O(skewness h), and clipping to [phi_C, phi_D] would keep that error.
      const double mid = van_leer(phiC, phiD, gradC, xC, xD);
      const double shifted = mid + gradC.dot(mesh.face_centre(f) - 0.5 * (xC + xD));
      return std::clamp(shifted, rangeC.first, rangeC.second);
    }
  }
  return phiC;
}
}  // namespace

// One parallel face scatter (scatter_faces), as in laplacian(): each cell's sums in ascending
// face order, whatever the number of threads.
void ConvectionTerm::add_to(Matrix& eq, double sign) const {
  const Mesh& mesh = *m;
  const ScalarField& field = *phi;
  const auto n = static_cast<std::size_t>(mesh.cells());
  const bool own_gradient = scheme != Convection::upwind && grad.empty();
  Scratch<Eigen::Vector3d> computed(own_gradient ? n : 0);
  if (own_gradient) mesh.gradient(field.cells, field.boundary, *computed);
  const std::span<const Eigen::Vector3d> g =
      own_gradient ? std::span<const Eigen::Vector3d>(*computed) : grad;
  if (scheme != Convection::upwind && g.size() != n)
    throw std::invalid_argument("div(phi): a supplied gradient needs one vector per cell");
  const auto& v = field.cells;
  const bool limited = scheme == Convection::linear_upwind_limited;
  const bool ranged = scheme == Convection::van_leer_skew || limited;
  Scratch<std::pair<double, double>> range(ranged ? n : 0);
  if (ranged) neighbourhood_range(mesh, field, *range);
  Scratch<Eigen::Vector3d> limited_gradient(limited ? n : 0);
  if (limited) limit_gradient(mesh, field, g, *range, *limited_gradient);
  const std::span<const Eigen::Vector3d> gC =
      limited ? std::span<const Eigen::Vector3d>(*limited_gradient) : g;
  const int internal = mesh.internal_faces();
  scatter_faces(
      mesh, [](int, int) {},
      [&](int f, bool own, bool nei) {
        const auto fs = static_cast<std::size_t>(f);
        const double F = sign * flux[fs];
        const auto P = static_cast<std::size_t>(mesh.owner(f));
        if (f >= internal) {  // F phi_b = F (a phi_P + value)
          const int b = f - internal;
          if (field.is_empty(mesh, b)) return;
          const auto [a, value] = field.value_coeffs(mesh, b);
          eq.diag[P] += F * a;
          eq.source[P] -= F * value;
          return;
        }
        // Upwind in the matrix, the scheme's difference to upwind as a deferred correction.
        double correction = 0;
        const auto N = static_cast<std::size_t>(mesh.neighbour(f));
        if (scheme != Convection::upwind) {
          const bool fromP = F * sign >= 0;  // upwind by the flux, whatever the term's sign
          const auto C = fromP ? P : N, D = fromP ? N : P;
          // Centres in the owner's frame (a periodic neighbour is seen at its image).
          const Eigen::Vector3d& xP = mesh.centre(static_cast<int>(P));
          const Eigen::Vector3d xN = mesh.neighbour_centre(f);
          correction =
              F * (high_order(mesh, scheme, f, v[C], v[D], gC[C], fromP ? xP : xN, fromP ? xN : xP,
                              ranged ? range[C] : std::pair<double, double>{}) -
                   v[C]);
        }
        // With the term's sign in F: sign * (upwind coefficients of the flux).
        const double out = sign * std::max(sign * F, 0.0), in = sign * std::min(sign * F, 0.0);
        if (own) {
          eq.upper[fs] += in;
          eq.lower[fs] -= out;
          eq.diag[P] += out;
          eq.source[P] -= correction;
        }
        if (nei) {
          eq.diag[N] -= in;
          eq.source[N] += correction;
        }
      });
}

}  // namespace auvloop::engine::fv
