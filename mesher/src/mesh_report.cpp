// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/mesh_report.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "auvloop/geometry/myring.hpp"

namespace auvloop::mesher {

long long MeshReport::total_cells() const {
  long long n = 0;
  for (const auto& g : grids) n += g.quality.cells;
  return n;
}

namespace {
GridReport grid_report(const Grid& g, double ref_length, const MeshSettings& s) {
  const GridGeometry geo = compute_geometry(g);
  GridReport r;
  r.name = g.name;
  r.quality = measure_quality(g, geo);
  r.first_cell_min = 1e300;
  for (const auto& p : g.patches) {
    if (p.type != PatchType::wall) continue;
    for (int f = p.start; f < p.start + p.size; ++f) {
      const auto fs = static_cast<std::size_t>(f);
      const Eigen::Vector3d& S = geo.face_area[fs];
      const auto c = static_cast<std::size_t>(g.owner[fs]);
      // A wall cell's centre sits halfway up it (exactly for prisms on a flat wall).
      const double h = 2 * std::abs(S.dot(geo.face_centre[fs] - geo.cell_centre[c])) / S.norm();
      r.first_cell_min = std::min(r.first_cell_min, h);
      r.first_cell_max = std::max(r.first_cell_max, h);
      ++r.wall_faces;
    }
  }
  if (r.wall_faces == 0) {
    r.first_cell_min = 0;
    return r;
  }
  const auto yplus = [&](double h) {
    return flat_plate_yplus(h, s.design_speed, s.kinematic_viscosity, ref_length);
  };
  r.yplus_min = yplus(r.first_cell_min);
  r.yplus_max = yplus(r.first_cell_max);
  return r;
}
}  // namespace

MeshReport mesh_report(const GridSystem& sys, const MeshSettings& s, const geometry::Vehicle& v) {
  MeshReport r;
  r.preset = s.preset;
  r.design_speed = s.design_speed;
  r.kinematic_viscosity = s.kinematic_viscosity;
  r.fin_deflections = sys.fin_deflections;
  const double chord = 0.5 * (v.fin_set.root_chord + v.fin_set.tip_chord);
  r.grids.push_back(grid_report(sys.hull, geometry::MyringProfile(v.hull).length(), s));
  for (const auto& f : sys.fins) r.grids.push_back(grid_report(f, chord, s));
  r.grids.push_back(grid_report(sys.background, 1.0, s));
  return r;
}

std::vector<double> cell_non_orthogonality(const Grid& g, const GridGeometry& geo) {
  std::vector<double> worst(static_cast<std::size_t>(g.cells), 0.0);
  for (int f = 0; f < g.internal_faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const auto P = static_cast<std::size_t>(g.owner[fs]),
               N = static_cast<std::size_t>(g.neighbour[fs]);
    const Eigen::Vector3d d = geo.cell_centre[N] - geo.cell_centre[P];
    const Eigen::Vector3d& S = geo.face_area[fs];
    const double angle =
        std::acos(std::clamp(S.dot(d) / (S.norm() * d.norm()), -1.0, 1.0)) * 180 / std::numbers::pi;
    worst[P] = std::max(worst[P], angle);
    worst[N] = std::max(worst[N], angle);
  }
  return worst;
}

std::string report_table(const MeshReport& r) {
  std::string out = fmt::format(
      "mesh report (preset {}, y+ estimated at {:.3g} m/s, nu {:.3g} m^2/s)\n"
      "{:<24} {:>9} {:>11} {:>9} {:>7} {:>8} {:>13} {:>8} {:>8} {:>8} {:>8}\n",
      r.preset, r.design_speed, r.kinematic_viscosity, "grid", "cells", "min vol m3", "non-orth",
      "skew", "aspect", "y+ first cell", "active", "fringe", "fallback", "orphan");
  for (const auto& g : r.grids) {
    const std::string yplus =
        g.wall_faces > 0 ? fmt::format("{:.2g}-{:.2g}", g.yplus_min, g.yplus_max) : "-";
    const auto count = [&](int n) { return g.assembled ? fmt::format("{}", n) : std::string("-"); };
    out += fmt::format(
        "{:<24} {:>9} {:>11.3e} {:>9.1f} {:>7.2f} {:>8.0f} {:>13} {:>8} {:>8} {:>8} {:>8}\n",
        g.name, g.quality.cells, g.quality.min_volume, g.quality.max_non_orthogonality,
        g.quality.max_skewness, g.quality.max_aspect_ratio, yplus, count(g.overset.active),
        count(g.overset.fringe), count(g.overset.fallback), count(g.overset.orphan));
  }
  out += fmt::format("total {} cells\n", r.total_cells());
  return out;
}

std::string report_json(const MeshReport& r) {
  using nlohmann::json;
  json grids = json::array();
  for (const auto& g : r.grids) {
    const auto& q = g.quality;
    json j = {{"name", g.name},
              {"cells", q.cells},
              {"faces", q.faces},
              {"points", q.points},
              {"volume_m3", q.total_volume},
              {"min_volume_m3", q.min_volume},
              {"min_volume_cell", q.worst_cell},
              {"max_non_orthogonality_deg", q.max_non_orthogonality},
              {"max_non_orthogonality_face", q.worst_non_orthogonal_face},
              {"max_skewness", q.max_skewness},
              {"max_skewness_face", q.worst_skewed_face},
              {"max_aspect_ratio", q.max_aspect_ratio},
              {"max_closure_error", q.max_closure_error},
              {"wall_faces", g.wall_faces}};
    if (g.wall_faces > 0) {
      j["first_cell_height_m"] = {g.first_cell_min, g.first_cell_max};
      j["yplus_estimate"] = {g.yplus_min, g.yplus_max};
    }
    j["overset"] = g.assembled ? json{{"active", g.overset.active},
                                      {"fringe", g.overset.fringe},
                                      {"fallback", g.overset.fallback},
                                      {"hole", g.overset.hole},
                                      {"orphan", g.overset.orphan}}
                               : json(nullptr);
    grids.push_back(std::move(j));
  }
  json deflections = json::array();
  for (double d : r.fin_deflections) deflections.push_back(d * 180 / std::numbers::pi);
  const json doc = {{"preset", r.preset},
                    {"design_speed_m_s", r.design_speed},
                    {"kinematic_viscosity_m2_s", r.kinematic_viscosity},
                    {"fin_deflections_deg", deflections},
                    {"total_cells", r.total_cells()},
                    {"grids", grids}};
  return doc.dump(2) + "\n";
}

}  // namespace auvloop::mesher
