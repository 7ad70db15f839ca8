// SPDX-License-Identifier: GPL-3.0-or-later
// Implicit finite-volume operators (fvm) and the explicit ones they rely on (fvc). Each implicit
// one returns the volume integral of its term as a term (matrix.hpp) that adds itself to a
// Matrix; an equation is their sum. Boundary
// conditions enter through ScalarField::value_coeffs; empty faces carry no flux.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "auvloop/engine/fv/field.hpp"
#include "auvloop/engine/fv/matrix.hpp"

namespace auvloop::engine::fv {

// --- explicit -------------------------------------------------------------------------------
std::vector<Eigen::Vector3d> grad(const Mesh& mesh, const ScalarField& phi);
// Linear interpolation of a cell-centred vector to the internal faces (boundary: face values).
Eigen::Vector3d interpolate(const Mesh& mesh, std::span<const Eigen::Vector3d> cells, int f);
// Skewness-corrected linear interpolation of a cell scalar to internal face f, given its cell
// gradients: w phi_P + (1 - w) phi_N + grad(phi)_f . skew_f (mesh.hpp); exact for linear fields
// on any grid, second order where the skewness does not shrink under refinement.
double interpolate(const Mesh& mesh, std::span<const double> cells,
                   std::span<const Eigen::Vector3d> gradients, int f);
// Cell divergence of a face flux field: sum of outgoing fluxes / volume (into `out`, n values).
std::vector<double> div(const Mesh& mesh, std::span<const double> face_flux);
void div(const Mesh& mesh, std::span<const double> face_flux, std::span<double> out);

// --- implicit -------------------------------------------------------------------------------
// Each returns a term (matrix.hpp): evaluated when assigned or added to a Matrix.

// laplacian(gamma, phi) = div(gamma grad phi): per face, gamma_f alpha_f (phi_N - phi_P) implicit
// and gamma_f k_f . grad(phi)_f explicit (deferred non-orthogonal correction from the current
// phi; exact on orthogonal faces, k = 0, where it is skipped). gamma per face, or uniform.
struct LaplacianTerm {
  const Mesh* m;
  std::span<const double> gamma_faces;  // empty: gamma_uniform
  double gamma_uniform;
  const ScalarField* phi;
  std::span<const Eigen::Vector3d> grad;  // phi's cell gradient if already computed, or empty
  [[nodiscard]] const Mesh& mesh() const { return *m; }
  void add_to(Matrix& eq, double sign) const;
};
inline LaplacianTerm laplacian(const Mesh& mesh, std::span<const double> gamma,
                               const ScalarField& phi) {
  return {&mesh, gamma, 0.0, &phi, {}};
}
inline LaplacianTerm laplacian(const Mesh& mesh, double gamma, const ScalarField& phi) {
  return {&mesh, {}, gamma, &phi, {}};
}
// The same with phi's cell gradient (Mesh::gradient of its current values) supplied, as when the
// convection term of the same equation needs it too: the non-orthogonal correction then does not
// compute it again (the same values, so the same result bit for bit).
inline LaplacianTerm laplacian(const Mesh& mesh, std::span<const double> gamma,
                               const ScalarField& phi, std::span<const Eigen::Vector3d> grad) {
  return {&mesh, gamma, 0.0, &phi, grad};
}
inline LaplacianTerm laplacian(const Mesh& mesh, double gamma, const ScalarField& phi,
                               std::span<const Eigen::Vector3d> grad) {
  return {&mesh, {}, gamma, &phi, grad};
}

// div(F, phi) with face volume fluxes F (m^3/s, positive out of the owner): upwind implicit and
// the scheme's difference to upwind as a deferred (explicit) correction from the current phi.
enum class Convection {
  upwind,         // first order, bounded
  linear_upwind,  // phi_C + grad(phi)_C . (x_f - x_C): second order, unbounded
  // linear_upwind with the gradient limited per cell (Barth and Jespersen 1989; OpenFOAM's
  // cellLimited, coefficient 1): grad_C scaled by the largest psi_C in [0, 1] that keeps the
  // extrapolated value at every face centre of C within the range of phi over C and its face
  // neighbours. Second order where the field is smooth and not at an extremum; a step convected
  // implicitly stays within its bounds (test_fv_operators; unlimited: 4 % overshoot), though
  // the limiter is not TVD in general.
  linear_upwind_limited,
  van_leer,  // TVD (Darwish-Moukalled r on unstructured grids): second order, bounded
  // van Leer's limited value (which sits at the mid-point between the two centres) moved to the
  // face centre with the upwind gradient, then clipped to the range of the two cell values:
  // identical to van_leer on uniform grids, second order also where the grid's skewness does
  // not shrink under refinement (van_leer is first order there: its value is off the face by
  // the skewness). The default.
  van_leer_skew,
};
// "upwind", "linear-upwind", "linear-upwind-limited", "van-leer", "van-leer-skew" (the names
// command lines and case files use).
const char* to_string(Convection c);
// The inverse; throws std::invalid_argument naming the accepted names.
Convection convection_from_string(const std::string& s);
struct ConvectionTerm {
  const Mesh* m;
  std::span<const double> flux;
  const ScalarField* phi;
  Convection scheme;
  std::span<const Eigen::Vector3d> grad;  // phi's cell gradient if already computed, or empty
  [[nodiscard]] const Mesh& mesh() const { return *m; }
  void add_to(Matrix& eq, double sign) const;
};
inline ConvectionTerm div(const Mesh& mesh, std::span<const double> flux, const ScalarField& phi,
                          Convection scheme) {
  return {&mesh, flux, &phi, scheme, {}};
}
// The same with phi's cell gradient (Mesh::gradient of its current values) supplied, as when the
// caller needs it anyway: the scheme's deferred correction then does not compute it again.
inline ConvectionTerm div(const Mesh& mesh, std::span<const double> flux, const ScalarField& phi,
                          Convection scheme, std::span<const Eigen::Vector3d> grad) {
  return {&mesh, flux, &phi, scheme, grad};
}

// Time derivative: (c0 phi + c1 phi_old + c2 phi_oldold) / dt, BDF2 or Euler (1, -1, 0) for the
// first step after a start. BDF2 on variable steps, with w = dt / dt_old (the previous step):
//   c0 = (1 + 2w) / (1 + w),  c1 = -(1 + w),  c2 = w^2 / (1 + w)
// (the derivative at t^{n+1} of the quadratic through the three levels; (3/2, -2, 1/2) for w = 1;
// zero-stable for w < 1 + sqrt 2).
struct TimeScheme {
  double dt = 1;
  bool bdf2 = true;
  double dt_old = 0;  // the previous step; 0: equal to dt
  [[nodiscard]] std::array<double, 3> coeffs() const {
    if (!bdf2) return {1.0, -1.0, 0.0};
    const double w = dt_old > 0 ? dt / dt_old : 1.0;
    return {(1 + 2 * w) / (1 + w), -(1 + w), w * w / (1 + w)};
  }
};
struct DdtTerm {
  const Mesh* m;
  TimeScheme ts;
  std::span<const double> old, oldold;
  [[nodiscard]] const Mesh& mesh() const { return *m; }
  void add_to(Matrix& eq, double sign) const;
};
inline DdtTerm ddt(const Mesh& mesh, const TimeScheme& ts, std::span<const double> old,
                   std::span<const double> oldold) {
  return {&mesh, ts, old, oldold};
}

// Sp(rate, phi): the implicit source rate phi (rate in 1/s, per cell), volume-integrated into the
// diagonal: diag += rate V. A destruction term reads `+ Sp(...)` on the left-hand side (its rate
// positive), which keeps the matrix diagonally dominant: positivity of k and omega rests on it.
struct SpTerm {
  const Mesh* m;
  std::span<const double> rate;
  [[nodiscard]] const Mesh& mesh() const { return *m; }
  void add_to(Matrix& eq, double sign) const;
};
inline SpTerm Sp(const Mesh& mesh, std::span<const double> rate) {
  return {&mesh, rate};
}

// Sums of terms, evaluated term by term into the matrix they are assigned or added to.
template <Term A, Term B>
struct TermSum {
  A a;
  B b;
  double sign_b;
  [[nodiscard]] const Mesh& mesh() const { return a.mesh(); }
  void add_to(Matrix& eq, double sign) const {
    a.add_to(eq, sign);
    b.add_to(eq, sign * sign_b);
  }
};
template <Term A, Term B>
TermSum<A, B> operator+(const A& a, const B& b) {
  return {a, b, 1.0};
}
template <Term A, Term B>
TermSum<A, B> operator-(const A& a, const B& b) {
  return {a, b, -1.0};
}

}  // namespace auvloop::engine::fv
