// SPDX-License-Identifier: GPL-3.0-or-later
// Propeller open-water curves and the Hough-Ordway disk: steps 1-2 of propeller.hpp.
#include "auvloop/engine/propeller.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace auvloop::engine {

namespace {
// One term C J^s (P/D)^t (AE/A0)^u Z^v of the B-series polynomials.
struct Term {
  double c;
  int s, t, u, v;
};
// Oosterveld and van Oossanen (1975), Re = 2e6, as carried by Fossen's MSS toolbox
// (propeller.md, section 2): the data of the fit, not code.
constexpr std::array<Term, 39> kKT{{
    {0.00880496, 0, 0, 0, 0},   {-0.204554, 1, 0, 0, 0},    {0.166351, 0, 1, 0, 0},
    {0.158114, 0, 2, 0, 0},     {-0.147581, 2, 0, 1, 0},    {-0.481497, 1, 1, 1, 0},
    {0.415437, 0, 2, 1, 0},     {0.0144043, 0, 0, 0, 1},    {-0.0530054, 2, 0, 0, 1},
    {0.0143481, 0, 1, 0, 1},    {0.0606826, 1, 1, 0, 1},    {-0.0125894, 0, 0, 1, 1},
    {0.0109689, 1, 0, 1, 1},    {-0.133698, 0, 3, 0, 0},    {0.00638407, 0, 6, 0, 0},
    {-0.00132718, 2, 6, 0, 0},  {0.168496, 3, 0, 1, 0},     {-0.0507214, 0, 0, 2, 0},
    {0.0854559, 2, 0, 2, 0},    {-0.0504475, 3, 0, 2, 0},   {0.010465, 1, 6, 2, 0},
    {-0.00648272, 2, 6, 2, 0},  {-0.00841728, 0, 3, 0, 1},  {0.0168424, 1, 3, 0, 1},
    {-0.00102296, 3, 3, 0, 1},  {-0.0317791, 0, 3, 1, 1},   {0.018604, 1, 0, 2, 1},
    {-0.00410798, 0, 2, 2, 1},  {-0.000606848, 0, 0, 0, 2}, {-0.0049819, 1, 0, 0, 2},
    {0.0025983, 2, 0, 0, 2},    {-0.000560528, 3, 0, 0, 2}, {-0.00163652, 1, 2, 0, 2},
    {-0.000328787, 1, 6, 0, 2}, {0.000116502, 2, 6, 0, 2},  {0.000690904, 0, 0, 1, 2},
    {0.00421749, 0, 3, 1, 2},   {5.65229e-05, 3, 6, 1, 2},  {-0.00146564, 0, 3, 2, 2},
}};
constexpr std::array<Term, 47> kKQ{{
    {0.00379368, 0, 0, 0, 0},  {0.00886523, 2, 0, 0, 0},   {-0.032241, 1, 1, 0, 0},
    {0.00344778, 0, 2, 0, 0},  {-0.0408811, 0, 1, 1, 0},   {-0.108009, 1, 1, 1, 0},
    {-0.0885381, 2, 1, 1, 0},  {0.188561, 0, 2, 1, 0},     {-0.00370871, 1, 0, 0, 1},
    {0.00513696, 0, 1, 0, 1},  {0.0209449, 1, 1, 0, 1},    {0.00474319, 2, 1, 0, 1},
    {-0.00723408, 2, 0, 1, 1}, {0.00438388, 1, 1, 1, 1},   {-0.0269403, 0, 2, 1, 1},
    {0.0558082, 3, 0, 1, 0},   {0.0161886, 0, 3, 1, 0},    {0.00318086, 1, 3, 1, 0},
    {0.015896, 0, 0, 2, 0},    {0.0471729, 1, 0, 2, 0},    {0.0196283, 3, 0, 2, 0},
    {-0.0502782, 0, 1, 2, 0},  {-0.030055, 3, 1, 2, 0},    {0.0417122, 2, 2, 2, 0},
    {-0.0397722, 0, 3, 2, 0},  {-0.00350024, 0, 6, 2, 0},  {-0.0106854, 3, 0, 0, 1},
    {0.00110903, 3, 3, 0, 1},  {-0.000313912, 0, 6, 0, 1}, {0.0035985, 3, 0, 1, 1},
    {-0.00142121, 0, 6, 1, 1}, {-0.00383637, 1, 0, 2, 1},  {0.0126803, 0, 2, 2, 1},
    {-0.00318278, 2, 3, 2, 1}, {0.00334268, 0, 6, 2, 1},   {-0.00183491, 1, 1, 0, 2},
    {0.000112451, 3, 2, 0, 2}, {-2.97228e-05, 3, 6, 0, 2}, {0.000269551, 1, 0, 1, 2},
    {0.00083265, 2, 0, 1, 2},  {0.00155334, 0, 2, 1, 2},   {0.000302683, 0, 6, 1, 2},
    {-0.0001843, 0, 0, 2, 2},  {-0.000425399, 0, 3, 2, 2}, {8.69243e-05, 3, 3, 2, 2},
    {-0.0004659, 0, 6, 2, 2},  {5.54194e-05, 1, 6, 2, 2},
}};

template <std::size_t N>
double polynomial(const std::array<Term, N>& terms, const BSeries& p, double J) {
  double sum = 0;
  for (const auto& term : terms)
    sum += term.c * std::pow(J, term.s) * std::pow(p.pitch_ratio, term.t) *
           std::pow(p.area_ratio, term.u) * std::pow(static_cast<double>(p.blades), term.v);
  return sum;
}
}  // namespace

std::optional<std::string> b_series_range_problem(const BSeries& p) {
  if (p.blades < 2 || p.blades > 7)
    return fmt::format("{} blades: the B-series is fitted for 2 to 7", p.blades);
  if (!(p.area_ratio >= 0.30 && p.area_ratio <= 1.05))
    return fmt::format("AE/A0 {}: the B-series is fitted for 0.30 to 1.05", p.area_ratio);
  if (!(p.pitch_ratio >= 0.5 && p.pitch_ratio <= 1.4))
    return fmt::format("P/D {}: the B-series is fitted for 0.5 to 1.4", p.pitch_ratio);
  return std::nullopt;
}

OpenWaterPoint b_series(const BSeries& p, double J) {
  return {J, polynomial(kKT, p, J), polynomial(kKQ, p, J)};
}

OpenWaterTable::OpenWaterTable(std::vector<OpenWaterPoint> points) : points_(std::move(points)) {
  if (points_.size() < 2)
    throw std::invalid_argument(
        fmt::format("open-water table: {} point(s), at least 2 needed", points_.size()));
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const auto& q = points_[i];
    if (!std::isfinite(q.J) || !std::isfinite(q.KT) || !std::isfinite(q.KQ))
      throw std::invalid_argument(fmt::format("open-water table: point {} is not finite", i + 1));
    if (i > 0 && !(q.J > points_[i - 1].J))
      throw std::invalid_argument(
          fmt::format("open-water table: J must increase, point {} has J {} after {}", i + 1, q.J,
                      points_[i - 1].J));
  }
}

OpenWaterPoint OpenWaterTable::at(double J, bool* clamped) const {
  const bool below = J <= points_.front().J, above = J >= points_.back().J;
  if (clamped != nullptr)
    *clamped = (below && J < points_.front().J) || (above && J > points_.back().J);
  if (below) return {J, points_.front().KT, points_.front().KQ};
  if (above) return {J, points_.back().KT, points_.back().KQ};
  const auto hi = std::upper_bound(points_.begin(), points_.end(), J,
                                   [](double j, const OpenWaterPoint& q) { return j < q.J; });
  const auto& b = *hi;
  const auto& a = *(hi - 1);
  const double w = (J - a.J) / (b.J - a.J);
  return {J, a.KT + w * (b.KT - a.KT), a.KQ + w * (b.KQ - a.KQ)};
}

OperatingPoint operating_point(const std::function<OpenWaterPoint(double)>& curve, double n,
                               double D, double disk_speed) {
  if (!(D > 0) || !std::isfinite(n) || !std::isfinite(disk_speed))
    throw std::invalid_argument(
        fmt::format("propeller operating point: diameter {} m, {} rev/s and disk speed {} m/s", D,
                    n, disk_speed));
  OperatingPoint op;
  const double nd = std::abs(n) * D;
  if (nd == 0) return op;
  double J = 0;
  if (disk_speed > 0) {
    const double J0 = disk_speed / nd;
    const double T0 = curve(J0).KT * nd * nd * D * D;
    const double induced = T0 / (2 * disk_speed * 0.25 * std::numbers::pi * D * D);
    J = std::max(0.0, (disk_speed - induced) / nd);
  }
  const auto k = curve(J);
  op.J = J;
  op.KT = k.KT;
  op.KQ = k.KQ;
  op.thrust = k.KT * nd * nd * D * D;
  op.torque = k.KQ * nd * nd * D * D * D;
  return op;
}

Eigen::Vector3d hough_ordway(const PropellerDisk& disk, double T, double Q,
                             const Eigen::Vector3d& x) {
  const double RP = disk.radius, RH = disk.hub_radius, delta = disk.thickness;
  if (!(RH >= 0 && RH < RP && delta > 0 && std::abs(disk.axis.norm() - 1) < 1e-12 &&
        (disk.sense == 1 || disk.sense == -1)))
    throw std::invalid_argument(fmt::format(
        "propeller disk: needs 0 <= hub radius ({}) < radius ({}), thickness ({}) > 0, a unit "
        "axis (|axis| = {}) and sense +1 or -1 ({})",
        RH, RP, delta, disk.axis.norm(), disk.sense));
  const Eigen::Vector3d d = x - disk.centre;
  const double axial = d.dot(disk.axis);
  const Eigen::Vector3d radial = d - axial * disk.axis;
  const double r = radial.norm();
  if (std::abs(axial) > 0.5 * delta || r < RH || r > RP || r == 0) return Eigen::Vector3d::Zero();
  const double rh = RH / RP;
  const double rs = std::min((r / RP - rh) / (1 - rh), 1.0);
  const double shape = rs * std::sqrt(1 - rs);
  const double denominator = 8 * std::numbers::pi * delta * (RP - RH) * (3 * RH + 4 * RP);
  const double Ax = 105 * T / denominator, At = 105 * Q / (denominator * RP);
  const Eigen::Vector3d tangential = disk.axis.cross(radial / r);  // right-handed about axis
  return -Ax * shape * disk.axis + disk.sense * At * shape / (rs * (1 - rh) + rh) * tangential;
}

}  // namespace auvloop::engine
