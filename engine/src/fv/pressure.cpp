// SPDX-License-Identifier: GPL-3.0-or-later
// PIMPLE step 3 (docs/cfd.md): one pressure corrector.
//   a. A = the diagonal of the momentum matrix, D = V / A, HbyA = H(U) / A with H(U) the
//      off-diagonal part and sources (old time levels, deferred corrections): U = HbyA - D grad p.
//   b. Rhie-Chow face flux phiHbyA = (HbyA)_f . S + (D / dt)_f sum_k (-c_k) (phi_k - (U_k)_f . S)
//      over the old time levels k: the old-time part of H is taken from the old face fluxes,
//      not from interpolated velocities, so the converged flux does not depend on dt.
//   c. laplacian(D_f, p) == div(phiHbyA), with non-orthogonal correctors.
//   d. phi = phiHbyA - the pressure equation's face flux (conservative to the solver tolerance);
//      p relaxed in all but the final outer iteration; U = HbyA - D grad(p).
#include "auvloop/engine/fv/pimple.hpp"

#include <Eigen/LU>

#include "diagnosis.hpp"

namespace auvloop::engine::fv {

namespace {
Eigen::Vector3d cell_vector(const std::array<std::vector<double>, 3>& u, std::size_t c) {
  return {u[0][c], u[1][c], u[2][c]};
}

// The value the cell gradients see on zero-gradient pressure patches (walls, inlets). p_b = p_P
// there means dp/dn = 0 to the least-squares fit, which is wrong wherever the wall-normal pressure
// gradient is not zero (mu d2u_n/dn2 at a no-slip wall, the stagnation region of a cylinder): the
// wall cells' grad(p), and through U = HbyA - D grad(p) their velocity, then carry an O(1) error.
// Instead p_b = p_P + g_P . (x_b - x_P) with g_P the least-squares gradient of the cell's other
// points (neighbours, fixed and empty faces): consistent with the fit, so every later grad(p)
// returns g_P there. The pressure equation still sees the flux condition only.
bool free_pressure_face(const Mesh& mesh, const ScalarField& p, int f) {
  if (f < mesh.internal_faces()) return false;
  return p.bcs[static_cast<std::size_t>(mesh.patch_of(f - mesh.internal_faces()))].kind ==
         BcKind::zero_gradient;
}

void extrapolate_zero_gradient(const Mesh& mesh, ScalarField& p) {
  for (int c = 0; c < mesh.cells(); ++c) {
    const auto cell_faces = mesh.cell_faces(c);
    bool any = false;
    for (int f : cell_faces) any = any || free_pressure_face(mesh, p, f);
    if (!any) continue;
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    const auto P = static_cast<std::size_t>(c);
    for (int f : cell_faces) {
      if (free_pressure_face(mesh, p, f)) continue;
      double other;
      Eigen::Vector3d d;
      if (f < mesh.internal_faces()) {
        const int n = mesh.owner(f) == c ? mesh.neighbour(f) : mesh.owner(f);
        d = mesh.centre(n) - mesh.centre(c);
        other = p.cells[static_cast<std::size_t>(n)];
      } else {
        d = mesh.face_centre(f) - mesh.centre(c);
        other = p.boundary[static_cast<std::size_t>(f - mesh.internal_faces())];
      }
      M += d * d.transpose() / d.squaredNorm();
      rhs += d * (other - p.cells[P]) / d.squaredNorm();
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
    if (!lu.isInvertible()) continue;  // too few other points: keep p_b = p_P
    const Eigen::Vector3d g = lu.solve(rhs);
    for (int f : cell_faces) {
      if (!free_pressure_face(mesh, p, f)) continue;
      p.boundary[static_cast<std::size_t>(f - mesh.internal_faces())] =
          p.cells[P] + g.dot(mesh.face_centre(f) - mesh.centre(c));
    }
  }
}
}  // namespace

std::vector<double> Pimple::face_flux(const std::array<std::vector<double>, 3>& u) const {
  // Skewness-corrected interpolation (mesh.hpp, "skew") of each active component: with plain
  // w u_P + (1 - w) u_N the flux is first order wherever the skewness does not shrink under
  // refinement (an O-grid's corners), and the converged flow then depends on where they are.
  // The gradients see U's boundary values on fixed-velocity patches, the cell value elsewhere.
  std::vector<double> f(static_cast<std::size_t>(mesh_.faces()), 0.0);
  if (!mesh_.skewed()) {
    for (int j = 0; j < mesh_.internal_faces(); ++j) {
      const double w = mesh_.weight(j);
      f[static_cast<std::size_t>(j)] =
          (w * cell_vector(u, static_cast<std::size_t>(mesh_.owner(j))) +
           (1 - w) * cell_vector(u, static_cast<std::size_t>(mesh_.neighbour(j))))
              .dot(mesh_.area(j));
    }
    return f;
  }
  std::vector<double> boundary(static_cast<std::size_t>(mesh_.boundary_faces()));
  std::vector<Eigen::Vector3d> g(static_cast<std::size_t>(mesh_.cells()));
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    for (int b = 0; b < mesh_.boundary_faces(); ++b) {
      const bool fixed = U.c[i].value_coeffs(mesh_, b)[0] == 0.0;
      boundary[static_cast<std::size_t>(b)] =
          fixed ? U.c[i].boundary[static_cast<std::size_t>(b)]
                : u[i][static_cast<std::size_t>(mesh_.owner(b + mesh_.internal_faces()))];
    }
    mesh_.gradient(u[i], boundary, g);
    const auto e = static_cast<Eigen::Index>(i);
    for (int j = 0; j < mesh_.internal_faces(); ++j)
      f[static_cast<std::size_t>(j)] += interpolate(mesh_, u[i], g, j) * mesh_.area(j)[e];
  }
  return f;
}

void Pimple::correct_pressure(const Momentum& m, StepReport& r, bool first, bool final) {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  const std::size_t a0 = active_[0] ? 0 : (active_[1] ? 1 : 2);
  const auto& A = m.eq[a0].diag;
  std::vector<double> D(n);
  for (std::size_t c = 0; c < n; ++c) D[c] = mesh_.volume(static_cast<int>(c)) / A[c];
  std::array<std::vector<double>, 3> HbyA{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0),
                                          std::vector<double>(n, 0.0)};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    m.eq[i].h_operator(mesh_, U.c[i].cells, HbyA[i]);
    for (std::size_t c = 0; c < n; ++c) HbyA[i][c] /= A[c];
  }
  // b. Rhie-Chow flux with the time-consistent correction.
  std::vector<double> phiHbyA = face_flux(HbyA);
  const auto coeffs = time_scheme().coeffs();
  for (std::size_t k = 0; k < 2; ++k) {
    if (coeffs[k + 1] == 0.0) continue;
    const auto& interpolated = U_old_flux_[k];
    for (int f = 0; f < mesh_.internal_faces(); ++f) {
      const auto fs = static_cast<std::size_t>(f);
      const double w = mesh_.weight(f);
      const double Df = w * D[static_cast<std::size_t>(mesh_.owner(f))] +
                        (1 - w) * D[static_cast<std::size_t>(mesh_.neighbour(f))];
      phiHbyA[fs] += Df / dt_ * -coeffs[k + 1] * (phi_old_[k][fs] - interpolated[fs]);
    }
  }
  std::vector<double> Df(static_cast<std::size_t>(mesh_.faces()));
  for (int f = 0; f < mesh_.faces(); ++f) {
    const auto P = static_cast<std::size_t>(mesh_.owner(f));
    if (f < mesh_.internal_faces()) {
      const double w = mesh_.weight(f);
      Df[static_cast<std::size_t>(f)] =
          w * D[P] + (1 - w) * D[static_cast<std::size_t>(mesh_.neighbour(f))];
    } else {
      const int b = f - mesh_.internal_faces();
      Df[static_cast<std::size_t>(f)] = D[P];
      const bool fixed_u = U.c[a0].value_coeffs(mesh_, b)[0] == 0.0;
      phiHbyA[static_cast<std::size_t>(f)] =
          U.c[a0].is_empty(mesh_, b)
              ? 0.0
              : (fixed_u ? U.face(b) : cell_vector(HbyA, P)).dot(mesh_.area(f));
    }
  }
  // c. and d.
  const std::vector<double> p_prev = p.cells;
  const auto net = div(mesh_, phiHbyA);
  for (int corr = 0; corr <= settings_.non_orthogonal_correctors; ++corr) {
    const auto gp = grad(mesh_, p);
    Matrix eq = laplacian(mesh_, Df, p);
    for (std::size_t c = 0; c < n; ++c) eq.source[c] += net[c] * mesh_.volume(static_cast<int>(c));
    if (!pressure_fixed_) eq.diag[0] += eq.diag[0];  // reference value p = 0 in cell 0
    const auto s = solve_named(mesh_, eq, p.cells, "pressure equation", [&] {
      return solver_.solve_symmetric(eq, p.cells, *settings_.pressure_solver);
    });
    if (first && corr == 0) r.pressure_residual = s.initial_residual;
    r.pressure_iterations += s.iterations;
    // Face flux of the pressure equation with the same explicit part as its source.
    for (int f = 0; f < mesh_.faces(); ++f) {
      const auto fs = static_cast<std::size_t>(f);
      const auto P = static_cast<std::size_t>(mesh_.owner(f));
      double pf;
      Eigen::Vector3d g;
      if (f < mesh_.internal_faces()) {
        pf = p.cells[static_cast<std::size_t>(mesh_.neighbour(f))];
        g = interpolate(mesh_, gp, f);
      } else {
        const int b = f - mesh_.internal_faces();
        const auto [ca, cb] = p.value_coeffs(mesh_, b);
        if (p.is_empty(mesh_, b) || ca == 1.0) {
          phi[fs] = phiHbyA[fs];
          continue;
        }
        pf = cb;
        g = gp[P];
      }
      phi[fs] = phiHbyA[fs] - Df[fs] * (mesh_.alpha(f) * (pf - p.cells[P]) + mesh_.k(f).dot(g));
    }
  }
  if (!final && settings_.relax_p < 1) {
    for (std::size_t c = 0; c < n; ++c)
      p.cells[c] = p_prev[c] + settings_.relax_p * (p.cells[c] - p_prev[c]);
  }
  p.update_boundary(mesh_);
  extrapolate_zero_gradient(mesh_, p);
  const auto gp = grad(mesh_, p);
  for (std::size_t i = 0; i < 3; ++i) {
    if (!active_[i]) continue;
    for (std::size_t c = 0; c < n; ++c)
      U.c[i].cells[c] = HbyA[i][c] - D[c] * gp[c][static_cast<Eigen::Index>(i)];
    U.c[i].update_boundary(mesh_);
  }
}

// The predictor force (pimple.hpp): (H(U) - A U) / V per active component with the equation of
// the last corrector. With U_k = HbyA(U_{k-1}) - D grad(p) this is grad(p) + N (U_{k-1} - U_k) / V:
// the pressure gradient plus the part of H that lagged one corrector behind.
void Pimple::store_predictor_force(const Momentum& m) {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  std::vector<double> h(n);
  for (std::size_t i = 0; i < 3; ++i) {
    auto& force = predictor_force_[i];
    if (!active_[i]) {
      force.clear();
      continue;
    }
    m.eq[i].h_operator(mesh_, U.c[i].cells, h);
    force.resize(n);
    for (std::size_t c = 0; c < n; ++c)
      force[c] = (h[c] - m.eq[i].diag[c] * U.c[i].cells[c]) / mesh_.volume(static_cast<int>(c));
  }
}

}  // namespace auvloop::engine::fv
