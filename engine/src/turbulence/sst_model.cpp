// SPDX-License-Identifier: GPL-3.0-or-later
// SST k-omega transport: steps 1-5 of auvloop/engine/turbulence/sst_model.hpp.
#include "auvloop/engine/turbulence/sst_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/engine/fv/overset.hpp"

#include "../fv/diagnosis.hpp"
#include "../fv/parallel.hpp"
#include "../fv/scratch.hpp"
#include "../fv/stopwatch.hpp"
#include "positivity.hpp"

namespace auvloop::engine::turbulence {

using fv::parallel_for;
using fv::Scratch;

namespace {
[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("SST k-omega: " + what);
}

void require(bool ok, const std::string& what) {
  if (!ok) fail(what);
}

void check_wall_distance(const fv::Mesh& mesh, std::span<const double> d) {
  const auto n = static_cast<std::size_t>(mesh.cells());
  require(d.size() == n, fmt::format("{} wall distances for {} cells", d.size(), n));
  for (std::size_t c = 0; c < n; ++c)  // the message formatted only for a bad value
    if (!(d[c] > 0 && std::isfinite(d[c])))
      fail(fmt::format("the wall distance of {} is {}", fv::cell_at(mesh, static_cast<int>(c)),
                       d[c]));
}
}  // namespace

SstModel::SstModel(const fv::Mesh& mesh, std::vector<double> wall_distance, SstSettings settings)
    : k(mesh, "k"),
      omega(mesh, "omega"),
      nu_t(mesh, "nut"),
      mesh_(mesh),
      settings_(settings),
      d_(std::move(wall_distance)) {
  const auto n = static_cast<std::size_t>(mesh.cells());
  check_wall_distance(mesh, d_);
  require(settings_.nu > 0, "nu must be positive");
  require(settings_.freestream.k > 0 && settings_.freestream.omega > 0,
          fmt::format("free-stream k and omega must be positive, got {} and {}",
                      settings_.freestream.k, settings_.freestream.omega));
  require(settings_.relax > 0 && settings_.relax <= 1, "relax must be in (0, 1]");
  require(settings_.floor > 0 && settings_.floor < 1, "floor must be in (0, 1)");
  // The wall faces and their first cells (step 2's addressing, fixed for the grid).
  const int internal = mesh.internal_faces();
  for (int b = 0; b < mesh.boundary_faces(); ++b) {
    const int pi = mesh.patch_of(b);
    if (mesh.grid().patches[static_cast<std::size_t>(pi)].type != mesher::PatchType::wall) continue;
    const int f = b + internal;
    const Eigen::Vector3d n_hat = mesh.area(f).normalized();
    WallFace w;
    w.face = f;
    w.patch = pi;
    w.y = std::abs((mesh.face_centre(f) - mesh.centre(mesh.owner(f))).dot(n_hat));
    walls_.push_back(w);
    wall_cells_.push_back(mesh.owner(f));
  }
  std::sort(wall_cells_.begin(), wall_cells_.end());
  wall_cells_.erase(std::unique(wall_cells_.begin(), wall_cells_.end()), wall_cells_.end());
  wall_faces_.assign(wall_cells_.size(), 0);
  for (auto& w : walls_) {
    w.cell = static_cast<int>(
        std::lower_bound(wall_cells_.begin(), wall_cells_.end(), mesh.owner(w.face)) -
        wall_cells_.begin());
    ++wall_faces_[static_cast<std::size_t>(w.cell)];
  }
  // Menter's wall-face omega (the TMR's) for the wall-resolved and the blended treatments, and
  // the TMR's k = 0 for the wall-resolved one; the wall-function treatment leaves both zero
  // gradient (its first cell's omega is fixed).
  if (settings_.wall != WallTreatment::wall_function) {
    for (const auto& w : walls_) {
      const auto& patch = mesh.grid().patches[static_cast<std::size_t>(w.patch)];
      const auto i = static_cast<std::size_t>(w.face - patch.start);
      const double d1 = 2 * w.y;  // the first cell's height
      auto& wb = omega.bcs[static_cast<std::size_t>(w.patch)];
      wb.kind = fv::BcKind::fixed_value;
      wb.value.resize(static_cast<std::size_t>(patch.size));
      wb.value[i] = 10 * 6 * settings_.nu / (settings_.constants.beta1 * d1 * d1);
      if (settings_.wall == WallTreatment::resolved) {
        auto& kb = k.bcs[static_cast<std::size_t>(w.patch)];
        kb.kind = fv::BcKind::fixed_value;
        kb.value.resize(static_cast<std::size_t>(patch.size));
        kb.value[i] = 0;
      }
    }
  }
  wall_omega_.assign(wall_cells_.size(), 0.0);
  wall_G_.assign(wall_cells_.size(), 0.0);
  wall_weight_.assign(wall_cells_.size(), 0.0);
  S2_.assign(n, 0.0);
  F1_.assign(n, 1.0);
  nu_eff_.assign(static_cast<std::size_t>(mesh.faces()), settings_.nu);
}

void SstModel::set_wall_distance(std::span<const double> wall_distance) {
  check_wall_distance(mesh_, wall_distance);
  d_.assign(wall_distance.begin(), wall_distance.end());
}

void SstModel::inlet(const std::string& patch) {
  k.fix(mesh_, patch, settings_.freestream.k);
  omega.fix(mesh_, patch, settings_.freestream.omega);
}

void SstModel::far_field(const std::string& patch) {
  k.mix(mesh_, patch, settings_.freestream.k);
  omega.mix(mesh_, patch, settings_.freestream.omega);
  far_field_.push_back(fv::patch_index(mesh_, patch));
}

void SstModel::switch_far_field(std::span<const double> phi) {
  if (far_field_.empty()) return;
  for (auto* field : {&k, &omega}) {
    for (int pi : far_field_) {
      const auto& patch = mesh_.grid().patches[static_cast<std::size_t>(pi)];
      auto& bc = field->bcs[static_cast<std::size_t>(pi)];
      for (int i = 0; i < patch.size; ++i)
        bc.fraction[static_cast<std::size_t>(i)] =
            phi[static_cast<std::size_t>(patch.start + i)] <= 0 ? 1.0 : 0.0;
    }
    field->update_boundary(mesh_);
  }
}

void SstModel::start_from(std::vector<double> k0, std::vector<double> omega0) {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  require(k0.size() == n && omega0.size() == n,
          fmt::format("start_from: {} k and {} omega values for {} cells", k0.size(), omega0.size(),
                      n));
  for (std::size_t c = 0; c < n; ++c)  // the message formatted only for a bad value
    if (!(k0[c] >= 0 && omega0[c] > 0 && std::isfinite(k0[c]) && std::isfinite(omega0[c])))
      fail(fmt::format("start_from: k {} and omega {} in {}", k0[c], omega0[c],
                       fv::cell_at(mesh_, static_cast<int>(c))));
  k0_ = std::move(k0);
  omega0_ = std::move(omega0);
}

void SstModel::initialise(const fv::VectorField& U, std::span<const double> phi) {
  if (k0_.empty()) {
    std::fill(k.cells.begin(), k.cells.end(), settings_.freestream.k);
    std::fill(omega.cells.begin(), omega.cells.end(), settings_.freestream.omega);
  } else {
    k.cells = k0_;
    omega.cells = omega0_;
  }
  if (overset_ != nullptr) {
    const double own = std::numeric_limits<double>::quiet_NaN();  // holes keep their values
    overset_->apply(k.cells, own, fv::Overset::Bound::donors);
    overset_->apply(omega.cells, own, fv::Overset::Bound::donors);
  }
  k.update_boundary(mesh_);
  omega.update_boundary(mesh_);
  switch_far_field(phi);
  strain(U, nullptr);
  wall_treatment(U);
  update_nu_t();
  for (auto& level : k_old_) level = k.cells;
  for (auto& level : omega_old_) level = omega.cells;
}

void SstModel::begin_step() {
  k_old_[1].swap(k_old_[0]);
  k_old_[0] = k.cells;
  omega_old_[1].swap(omega_old_[0]);
  omega_old_[0] = omega.cells;
}

// Step 1 (S^2 = 2 S_ij S_ij from the cell gradients of U, given or computed here).
void SstModel::strain(const fv::VectorField& U,
                      const std::array<std::vector<Eigen::Vector3d>, 3>* given) {
  const auto n = static_cast<std::size_t>(mesh_.cells());
  const bool own = given == nullptr;
  std::array<Scratch<Eigen::Vector3d>, 3> computed{Scratch<Eigen::Vector3d>(own ? n : 0),
                                                   Scratch<Eigen::Vector3d>(own ? n : 0),
                                                   Scratch<Eigen::Vector3d>(own ? n : 0)};
  std::array<std::span<const Eigen::Vector3d>, 3> g;
  for (std::size_t i = 0; i < 3; ++i) {
    if (own) mesh_.gradient(U.c[i].cells, U.c[i].boundary, *computed[i]);
    g[i] = own ? std::span<const Eigen::Vector3d>(*computed[i])
               : std::span<const Eigen::Vector3d>((*given)[i]);
    require(g[i].size() == n, "the velocity gradient needs one vector per cell");
  }
  parallel_for(mesh_.cells(), [&](int c) {
    const auto s = static_cast<std::size_t>(c);
    Eigen::Matrix3d G;  // G(i, j) = d u_i / d x_j
    for (int i = 0; i < 3; ++i) G.row(i) = g[static_cast<std::size_t>(i)][s].transpose();
    const Eigen::Matrix3d Sij = 0.5 * (G + G.transpose());
    S2_[s] = 2 * Sij.squaredNorm();
  });
}

// Step 2.
void SstModel::wall_treatment(const fv::VectorField& U) {
  const double nu = settings_.nu;
  const auto& c = settings_.constants;
  const int internal = mesh_.internal_faces();
  parallel_for(
      static_cast<int>(walls_.size()),
      [&](int i) {
        auto& w = walls_[static_cast<std::size_t>(i)];
        const int b = w.face - internal;
        const Eigen::Vector3d n_hat = mesh_.area(w.face).normalized();
        Eigen::Vector3d u = U.cell(mesh_.owner(w.face)) - U.face(b);  // relative to the wall
        u -= u.dot(n_hat) * n_hat;
        const double ut = u.norm();
        w.u_tau = settings_.law.friction_velocity(ut, w.y, nu);
        w.y_plus = w.y * w.u_tau / nu;
        w.u_plus = w.u_tau > 0 ? ut / w.u_tau : 0.0;
        w.nu_t = ut > 0 && settings_.wall != WallTreatment::resolved
                     ? std::max(0.0, w.u_tau * w.u_tau * w.y / ut - nu)
                     : 0.0;
      },
      64);
  // Per wall cell: the mean over its wall faces (in ascending face order).
  std::fill(wall_omega_.begin(), wall_omega_.end(), 0.0);
  std::fill(wall_G_.begin(), wall_G_.end(), 0.0);
  std::fill(wall_weight_.begin(), wall_weight_.end(), 0.0);
  for (const auto& w : walls_) {
    const auto at = static_cast<std::size_t>(w.cell);
    wall_omega_[at] += wall_omega(w.y, w.u_tau, nu, c);
    wall_G_[at] += wall_production_from_u_plus(settings_.law, w.u_plus, w.u_tau, nu);
    wall_weight_[at] += roughness_share(menter_roughness(2 * w.y_plus, c));  // d1 = 2 y
  }
  rough_cells_.clear();
  rough_omega_.clear();
  for (std::size_t j = 0; j < wall_cells_.size(); ++j) {
    wall_omega_[j] /= wall_faces_[j];
    wall_G_[j] /= wall_faces_[j];
    wall_weight_[j] /= wall_faces_[j];
    if (wall_weight_[j] >= 1) {  // fully rough: the wall-function value alone (ascending)
      rough_cells_.push_back(wall_cells_[j]);
      rough_omega_.push_back(wall_omega_[j]);
      wall_weight_[j] = 0;
    }
  }
}

// Step 5.
void SstModel::update_nu_t() {
  const auto& c = settings_.constants;
  const double nu = settings_.nu;
  parallel_for(mesh_.cells(), [&](int cell) {
    const auto s = static_cast<std::size_t>(cell);
    const double F2 = f2(c, k.cells[s], omega.cells[s], d_[s], nu);
    nu_t.cells[s] = eddy_viscosity(c, k.cells[s], omega.cells[s], std::sqrt(S2_[s]), F2);
  });
  nu_t.update_boundary(mesh_);  // zero gradient everywhere; walls below
  const int internal = mesh_.internal_faces();
  for (const auto& w : walls_) nu_t.boundary[static_cast<std::size_t>(w.face - internal)] = w.nu_t;
  parallel_for(mesh_.faces(), [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    if (f < internal) {
      const double wt = mesh_.weight(f);
      nu_eff_[fs] = nu + wt * nu_t.cells[static_cast<std::size_t>(mesh_.owner(f))] +
                    (1 - wt) * nu_t.cells[static_cast<std::size_t>(mesh_.neighbour(f))];
    } else {
      nu_eff_[fs] = nu + nu_t.boundary[static_cast<std::size_t>(f - internal)];
    }
  });
}

fv::TurbulenceReport SstModel::correct(const fv::TurbulenceInput& in) {
  const auto& c = settings_.constants;
  const double nu = settings_.nu;
  const auto n = static_cast<std::size_t>(mesh_.cells());
  const int internal = mesh_.internal_faces();
  fv::TurbulenceReport report;
  // 1. Gradients, S^2, F1 and the blended constants' diffusivities (the far field's faces
  //    switched by the present flux first).
  switch_far_field(in.phi);
  strain(*in.U, in.grad_U);
  Scratch<Eigen::Vector3d> gk(n), gw(n);
  mesh_.gradient(k.cells, k.boundary, *gk);
  mesh_.gradient(omega.cells, omega.boundary, *gw);
  Scratch<double> cross(n), div_phi(n);  // grad k . grad omega (1/s^3); div(phi) (1/s)
  parallel_for(mesh_.cells(), [&](int cell) {
    const auto s = static_cast<std::size_t>(cell);
    cross[s] = gk[s].dot(gw[s]);
    const double cd = cross_diffusion(c, cross[s], omega.cells[s]);
    F1_[s] = turbulence::f1(c, k.cells[s], omega.cells[s], d_[s], nu, cd);
  });
  fv::div(mesh_, in.phi, *div_phi);
  // 2. The wall treatment with the corrected U.
  wall_treatment(*in.U);
  const bool relax = in.steady || !in.final;
  const auto diffusivity = [&](auto sigma_of) {
    gamma_.resize(static_cast<std::size_t>(mesh_.faces()));
    parallel_for(mesh_.faces(), [&](int f) {
      const auto fs = static_cast<std::size_t>(f);
      const auto P = static_cast<std::size_t>(mesh_.owner(f));
      double sigma_nut;
      if (f < internal) {
        const auto N = static_cast<std::size_t>(mesh_.neighbour(f));
        const double wt = mesh_.weight(f);
        sigma_nut = wt * sigma_of(P) * nu_t.cells[P] + (1 - wt) * sigma_of(N) * nu_t.cells[N];
      } else {
        sigma_nut = sigma_of(P) * nu_t.boundary[static_cast<std::size_t>(f - internal)];
      }
      gamma_[fs] = nu + sigma_nut;
    });
  };
  // grad: phi_field's gradient from step 1 (neither field changes before its own solve), for
  // the convection scheme and the non-orthogonal correction.
  const auto assemble = [&](fv::ScalarField& phi_field,
                            const std::array<std::vector<double>, 2>& old,
                            std::span<const Eigen::Vector3d> grad) {
    const auto convection = fv::div(mesh_, in.phi, phi_field, settings_.convection, grad);
    if (in.steady) {
      eq_ = convection - fv::Sp(mesh_, *div_phi) - fv::laplacian(mesh_, gamma_, phi_field, grad) +
            fv::Sp(mesh_, rate_);
    } else {
      eq_ = fv::ddt(mesh_, in.time, old[0], old[1]) + convection - fv::Sp(mesh_, *div_phi) -
            fv::laplacian(mesh_, gamma_, phi_field, grad) + fv::Sp(mesh_, rate_);
    }
    eq_.add_rhs(mesh_, source_);
  };
  const auto solve = [&](fv::ScalarField& phi_field, const char* name, double floor,
                         double& residual, int& iterations) {
    // A negative net explicit source is taken implicitly, as a rate -source / ref_c (Patankar),
    // with ref_c from positivity.hpp (step 1 there: phi_c, or more at a local minimum).
    sink_reference(mesh_, overset_, phi_field.cells, floor, ref_);
    parallel_for(mesh_.cells(), [&](int cell) {
      const auto s = static_cast<std::size_t>(cell);
      if (eq_.source[s] >= 0) return;
      eq_.diag[s] -= eq_.source[s] / ref_[s];
      eq_.source[s] = 0;
    });
    if (relax && settings_.relax < 1) eq_.relax(phi_field.cells, settings_.relax);
    // Overset (turbulence_model.hpp, hook 8): after the relaxation, which would otherwise draw a
    // fixed row towards its last value.
    const double own = std::numeric_limits<double>::quiet_NaN();
    if (overset_ != nullptr) {
      const fv::ScopedSeconds clock(report.seconds_overset);
      overset_->fixed_values(phi_field.cells, own, fixed_, fv::Overset::Bound::donors);
      eq_.fix_values(mesh_, overset_->fixed_cells(), fixed_);
    }
    // The solve stops at |b - A phi| <= tol |b|, and |b| is the wall cells' (omega of 1e6-1e7
    // 1/s there, 1-100 in the free stream; k likewise over six decades): unscaled, a solve would
    // stop before it has touched the free stream, which then stays frozen at whatever the start
    // left there (a converged-looking state 1.4 % low in Cf on the plate). Each row is divided by
    // diag_c ref_c, so a row's residual is its cell's error relative to its own level (or its
    // neighbours', where it lies below them) and the tolerance holds in every cell; the iterates
    // are those of the unscaled system.
    Scratch<double> scale(n);
    parallel_for(mesh_.cells(), [&](int cell) {
      const auto s = static_cast<std::size_t>(cell);
      scale[s] = 1 / (eq_.diag[s] * ref_[s]);
    });
    eq_.scale_rows(mesh_, *scale);
    const auto stats = fv::solve_named(mesh_, eq_, phi_field.cells, name, [&] {
      const double tol = !in.final && in.intermediate_tolerance > 0 ? in.intermediate_tolerance
                                                                    : settings_.tolerance;
      return in.solver->solve_asymmetric(eq_, phi_field.cells, settings_.solver, tol);
    });
    residual = stats.initial_residual;
    iterations = stats.iterations;
    report.bounded_cells += bound(mesh_, overset_, phi_field.cells, floor, ref_);
    if (overset_ != nullptr) {  // the donors' new values
      const fv::ScopedSeconds clock(report.seconds_overset);
      overset_->apply(phi_field.cells, own, fv::Overset::Bound::donors);
    }
    phi_field.update_boundary(mesh_);
  };
  rate_.resize(n);
  source_.resize(n);
  const bool ambient = settings_.ambient_sources;
  const double ambient_w2 = ambient ? settings_.freestream.omega * settings_.freestream.omega : 0;
  const double ambient_k =
      ambient ? c.beta_star * settings_.freestream.omega * settings_.freestream.k : 0;
  // 3. omega.
  // The blended sigmas per cell once (blend() evaluates gamma1, gamma2 with their square roots;
  // the face loop would do it twice per face and equation).
  Scratch<double> sigma_k(n), sigma_w(n);
  parallel_for(mesh_.cells(), [&](int cell) {
    const auto s = static_cast<std::size_t>(cell);
    const auto b = blend(c, F1_[s]);
    sigma_k[s] = b.sigma_k;
    sigma_w[s] = b.sigma_w;
  });
  diffusivity([&](std::size_t s) { return sigma_w[s]; });
  parallel_for(mesh_.cells(), [&](int cell) {
    const auto s = static_cast<std::size_t>(cell);
    const auto b = blend(c, F1_[s]);
    const double w = omega.cells[s];
    const double cd = (1 - F1_[s]) * 2 * c.sigma_w2 * cross[s] / w;  // 1/s^2
    rate_[s] = b.beta * w + (cd < 0 ? -cd / w : 0.0);
    source_[s] = b.gamma * S2_[s] + (cd > 0 ? cd : 0.0) + b.beta * ambient_w2;
  });
  assemble(omega, omega_old_, *gw);
  if (settings_.wall == WallTreatment::wall_function)
    eq_.fix_values(mesh_, wall_cells_, wall_omega_);
  else if (settings_.wall == WallTreatment::any_y_plus) {
    eq_.pull_values(wall_cells_, wall_omega_, wall_weight_);
    eq_.fix_values(mesh_, rough_cells_, rough_omega_);
  }
  solve(omega, "omega equation", settings_.floor * settings_.freestream.omega,
        report.omega_residual, report.omega_iterations);
  // 4. k, with the production of the old nu_t (limited) and the wall cells' from step 2.
  diffusivity([&](std::size_t s) { return sigma_k[s]; });
  const auto limited =
      fv::parallel_sum<1>(mesh_.cells(), [&](int b, int e, std::array<double, 1>& count) {
        for (auto s = static_cast<std::size_t>(b); s < static_cast<std::size_t>(e); ++s) {
          bool capped = false;
          source_[s] =
              production(c, nu_t.cells[s], std::sqrt(S2_[s]), k.cells[s], omega.cells[s], &capped);
          count[0] += capped ? 1 : 0;
          rate_[s] = c.beta_star * omega.cells[s];
          source_[s] += ambient_k;
        }
      });
  if (settings_.wall != WallTreatment::resolved)
    for (std::size_t j = 0; j < wall_cells_.size(); ++j)
      source_[static_cast<std::size_t>(wall_cells_[j])] = wall_G_[j];
  report.limited_cells = static_cast<long>(limited[0]);
  assemble(k, k_old_, *gk);
  solve(k, "k equation", settings_.floor * settings_.freestream.k, report.k_residual,
        report.k_iterations);
  // 5. nu_t and the effective viscosity.
  update_nu_t();
  return report;
}

// The last good state is what a checkpoint stores (state()): one definition of what a step reads.
void SstModel::save() {
  const auto arrays = state();
  good_.resize(arrays.size());
  for (std::size_t i = 0; i < arrays.size(); ++i) good_[i] = *arrays[i];
}

void SstModel::restore() {
  const auto arrays = state();
  for (std::size_t i = 0; i < arrays.size(); ++i) *arrays[i] = good_[i];
}

void SstModel::check() const {
  const auto finite = [&](std::size_t s) {
    return std::isfinite(k.cells[s]) && std::isfinite(omega.cells[s]) &&
           std::isfinite(nu_t.cells[s]);
  };
  const auto bad = fv::parallel_sum<1>(mesh_.cells(), [&](int b, int e, auto& count) {
    for (auto s = static_cast<std::size_t>(b); s < static_cast<std::size_t>(e); ++s)
      count[0] += finite(s) ? 0 : 1;
  });
  if (bad[0] == 0) return;
  for (int cell = 0; cell < mesh_.cells(); ++cell) {  // the first one, to name it
    const auto s = static_cast<std::size_t>(cell);
    if (!finite(s))
      throw std::runtime_error(
          fmt::format("non-finite k, omega or nu_t (k = {:.3g}, omega = {:.3g}) in {}", k.cells[s],
                      omega.cells[s], fv::cell_at(mesh_, cell)));
  }
}

bool SstModel::in_flow(const WallFace& w) const {
  return overset_ == nullptr || overset_->in_flow(mesh_.owner(w.face));
}

std::vector<WallYPlus> SstModel::y_plus() const {
  std::vector<WallYPlus> out;
  const auto& patches = mesh_.grid().patches;
  std::vector<double> area_sum;
  for (const auto& w : walls_) {
    if (!in_flow(w)) continue;
    const auto& name = patches[static_cast<std::size_t>(w.patch)].name;
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& r) { return r.patch == name; });
    if (it == out.end()) {
      out.push_back({name, 0, w.y_plus, 0, w.y_plus});
      area_sum.push_back(0);
      it = out.end() - 1;
    }
    const auto at = static_cast<std::size_t>(it - out.begin());
    const double a = mesh_.area(w.face).norm();
    ++it->faces;
    it->min = std::min(it->min, w.y_plus);
    it->max = std::max(it->max, w.y_plus);
    it->mean += a * w.y_plus;
    area_sum[at] += a;
  }
  for (std::size_t i = 0; i < out.size(); ++i) out[i].mean /= area_sum[i];
  return out;
}

}  // namespace auvloop::engine::turbulence
