// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/prestero.hpp"

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Cholesky>

namespace auvloop::engine {

const std::vector<PresteroCoefficients::Field>& PresteroCoefficients::fields() {
  using P = PresteroCoefficients;
  static const std::vector<Field> f{
      {"X_uu", "kg/m", &P::X_uu},
      {"X_udot", "kg", &P::X_udot},
      {"X_wq", "kg/rad", &P::X_wq},
      {"X_qq", "kg m/rad", &P::X_qq},
      {"X_vr", "kg/rad", &P::X_vr},
      {"X_rr", "kg m/rad", &P::X_rr},
      {"Y_vv", "kg/m", &P::Y_vv},
      {"Y_rr", "kg m/rad^2", &P::Y_rr},
      {"Y_uv", "kg/m", &P::Y_uv},
      {"Y_vdot", "kg", &P::Y_vdot},
      {"Y_rdot", "kg m/rad", &P::Y_rdot},
      {"Y_ur", "kg/rad", &P::Y_ur},
      {"Y_wp", "kg/rad", &P::Y_wp},
      {"Y_pq", "kg m/rad", &P::Y_pq},
      {"Y_uudr", "kg/(m rad)", &P::Y_uudr},
      {"Z_ww", "kg/m", &P::Z_ww},
      {"Z_qq", "kg m/rad^2", &P::Z_qq},
      {"Z_uw", "kg/m", &P::Z_uw},
      {"Z_wdot", "kg", &P::Z_wdot},
      {"Z_qdot", "kg m/rad", &P::Z_qdot},
      {"Z_uq", "kg/rad", &P::Z_uq},
      {"Z_vp", "kg/rad", &P::Z_vp},
      {"Z_rp", "kg/rad", &P::Z_rp},
      {"Z_uuds", "kg/(m rad)", &P::Z_uuds},
      {"K_pp", "kg m^2/rad^2", &P::K_pp},
      {"K_pdot", "kg m^2/rad", &P::K_pdot},
      {"M_ww", "kg", &P::M_ww},
      {"M_qq", "kg m^2/rad^2", &P::M_qq},
      {"M_uw", "kg", &P::M_uw},
      {"M_wdot", "kg m", &P::M_wdot},
      {"M_qdot", "kg m^2/rad", &P::M_qdot},
      {"M_uq", "kg m/rad", &P::M_uq},
      {"M_vp", "kg m/rad", &P::M_vp},
      {"M_rp", "kg m^2/rad^2", &P::M_rp},
      {"M_uuds", "kg/rad", &P::M_uuds},
      {"N_vv", "kg", &P::N_vv},
      {"N_rr", "kg m^2/rad^2", &P::N_rr},
      {"N_uv", "kg", &P::N_uv},
      {"N_vdot", "kg m", &P::N_vdot},
      {"N_rdot", "kg m^2/rad", &P::N_rdot},
      {"N_ur", "kg m/rad", &P::N_ur},
      {"N_wp", "kg m/rad", &P::N_wp},
      {"N_pq", "kg m^2/rad^2", &P::N_pq},
      {"N_uudr", "kg/rad", &P::N_uudr},
  };
  return f;
}

PresteroCoefficients read_prestero(input::Table h) {
  using input::Range;
  PresteroCoefficients c;
  h.choice("model", {"prestero2001"});
  c.source = h.text_or("source", "");
  const std::string fins = h.choice_or("fin_coefficients", "pair", {"pair", "one-fin"});
  c.fin_pair_factor = fins == "pair" ? 1.0 : 2.0;
  auto coefficients = h.table("coefficients");
  for (const auto& f : PresteroCoefficients::fields()) {
    // A coefficient is a number, or { value = ..., source = "..." } to record its provenance.
    if (coefficients.is_table(f.name)) {
      auto entry = coefficients.table(f.name);
      c.*f.member = entry.number("value", Range::any(), f.unit);
      c.notes[std::string(f.name)] = entry.text_or("source", "");
      entry.finish();
    } else {
      c.*f.member = coefficients.number(f.name, Range::any(), f.unit);
    }
  }
  coefficients.finish();
  auto prop = h.table("propeller");
  c.X_prop = prop.number("thrust", Range::positive(), "N");
  c.K_prop = prop.number("torque", Range::any(), "N m");
  c.reference_rpm = prop.number("reference_rpm", Range::positive(), "rpm");
  prop.finish();
  h.finish();
  // Drag and damping must oppose motion; a sign slip in a transcription shows up here.
  for (const auto& [name, value] : {std::pair{"X_uu", c.X_uu},
                                    {"Y_vv", c.Y_vv},
                                    {"Z_ww", c.Z_ww},
                                    {"K_pp", c.K_pp},
                                    {"M_qq", c.M_qq},
                                    {"N_rr", c.N_rr}}) {
    if (value > 0) {
      coefficients.fail(name, fmt::format("{} = {:g} would feed energy into the motion: quadratic "
                                          "damping must be negative",
                                          name, value));
    }
  }
  return c;
}

PresteroModel::PresteroModel(const geometry::Vehicle& vehicle, const PresteroCoefficients& c,
                             Buoyancy buoyancy)
    : c_(c),
      m_(vehicle.mass.mass),
      W_(vehicle.mass.weight()),
      B_(buoyancy == Buoyancy::neutral ? vehicle.mass.weight() : vehicle.mass.buoyancy),
      rg_(vehicle.mass.cg_from_cb),
      inertia_(vehicle.mass.inertia.diagonal()) {
  const double xg = rg_.x(), yg = rg_.y(), zg = rg_.z();
  // Prestero's mass matrix (rigid body about CB plus added mass), row by row.
  mass_ << m_ - c.X_udot, 0, 0, 0, m_ * zg, -m_ * yg,                  //
      0, m_ - c.Y_vdot, 0, -m_ * zg, 0, m_ * xg - c.Y_rdot,            //
      0, 0, m_ - c.Z_wdot, m_ * yg, -m_ * xg - c.Z_qdot, 0,            //
      0, -m_ * zg, m_ * yg, inertia_.x() - c.K_pdot, 0, 0,             //
      m_ * zg, 0, -m_ * xg - c.M_wdot, 0, inertia_.y() - c.M_qdot, 0,  //
      -m_ * yg, m_ * xg - c.N_vdot, 0, 0, 0, inertia_.z() - c.N_rdot;
  mass_lu_.compute(mass_);
}

double PresteroModel::equilibrium_speed(double rpm) const {
  const double thrust = c_.X_prop * std::pow(rpm / c_.reference_rpm, 2);
  return std::sqrt(thrust / -c_.X_uu);
}

Vector6d PresteroModel::forces(const Vector6d& nu, double phi, double theta, double delta_r,
                               double delta_s, double rpm) const {
  const double u = nu[0], v = nu[1], w = nu[2], p = nu[3], q = nu[4], r = nu[5];
  const double xg = rg_.x(), yg = rg_.y(), zg = rg_.z();
  const double m = m_, W = W_, B = B_;
  const double Ixx = inertia_.x(), Iyy = inertia_.y(), Izz = inertia_.z();
  const double sth = std::sin(theta), cth = std::cos(theta), sph = std::sin(phi),
               cph = std::cos(phi);
  const double n2 = std::pow(rpm / c_.reference_rpm, 2);
  const double fin = c_.fin_pair_factor;
  const auto& c = c_;
  // Prestero's listing with the buoyancy centre at the origin (x_b = y_b = z_b = 0).
  Vector6d f;
  f[0] = -(W - B) * sth + c.X_uu * u * std::abs(u) + (c.X_wq - m) * w * q +
         (c.X_qq + m * xg) * q * q + (c.X_vr + m) * v * r + (c.X_rr + m * xg) * r * r -
         m * yg * p * q - m * zg * p * r + c.X_prop * n2;
  f[1] = (W - B) * cth * sph + c.Y_vv * v * std::abs(v) + c.Y_rr * r * std::abs(r) +
         c.Y_uv * u * v + (c.Y_wp + m) * w * p + (c.Y_ur - m) * u * r - m * zg * q * r +
         (c.Y_pq - m * xg) * p * q + fin * c.Y_uudr * u * u * delta_r;
  f[2] = (W - B) * cth * cph + c.Z_ww * w * std::abs(w) + c.Z_qq * q * std::abs(q) +
         c.Z_uw * u * w + (c.Z_uq + m) * u * q + (c.Z_vp - m) * v * p + m * zg * p * p +
         m * zg * q * q + (c.Z_rp - m * xg) * r * p + fin * c.Z_uuds * u * u * delta_s;
  f[3] = -(yg * W) * cth * cph - (zg * W) * cth * sph + c.K_pp * p * std::abs(p) -
         (Izz - Iyy) * q * r - m * zg * w * p + m * zg * u * r + c.K_prop * n2;
  f[4] = -(zg * W) * sth - (xg * W) * cth * cph + c.M_ww * w * std::abs(w) +
         c.M_qq * q * std::abs(q) + (c.M_rp - (Ixx - Izz)) * r * p + m * zg * v * r -
         m * zg * w * q + (c.M_uq - m * xg) * u * q + c.M_uw * u * w + (c.M_vp + m * xg) * v * p +
         fin * c.M_uuds * u * u * delta_s;
  f[5] = -(xg * W) * cth * sph - (yg * W) * sth + c.N_vv * v * std::abs(v) +
         c.N_rr * r * std::abs(r) + c.N_uv * u * v + (c.N_pq - (Iyy - Ixx)) * p * q +
         (c.N_wp - m * xg) * w * p + (c.N_ur + m * xg) * u * r + fin * c.N_uudr * u * u * delta_r;
  return f;
}

Vector6d PresteroModel::acceleration(const Vector6d& nu, double phi, double theta, double delta_r,
                                     double delta_s, double rpm) const {
  return mass_lu_.solve(forces(nu, phi, theta, delta_r, delta_s, rpm));
}

Matrix6d prestero_added_mass(const PresteroCoefficients& c) {
  Matrix6d A = Matrix6d::Zero();
  A.diagonal() << -c.X_udot, -c.Y_vdot, -c.Z_wdot, -c.K_pdot, -c.M_qdot, -c.N_rdot;
  A(1, 5) = -c.Y_rdot;
  A(5, 1) = -c.N_vdot;
  A(2, 4) = -c.Z_qdot;
  A(4, 2) = -c.M_wdot;
  return 0.5 * (A + A.transpose());
}

}  // namespace auvloop::engine
