// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/grid.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace auvloop::mesher {

const char* to_string(PatchType t) {
  switch (t) {
    case PatchType::wall:
      return "wall";
    case PatchType::inlet:
      return "inlet";
    case PatchType::outlet:
      return "outlet";
    case PatchType::symmetry:
      return "symmetry";
    case PatchType::empty:
      return "empty";
    case PatchType::periodic:
      return "periodic";
    case PatchType::overset:
      return "overset";
  }
  return "unknown";
}

void Grid::add_face(std::initializer_list<int> pts, int owner_cell) {
  face_points.insert(face_points.end(), pts.begin(), pts.end());
  face_offsets.push_back(static_cast<int>(face_points.size()));
  owner.push_back(owner_cell);
}

void Grid::add_face(const std::vector<int>& pts, int owner_cell) {
  face_points.insert(face_points.end(), pts.begin(), pts.end());
  face_offsets.push_back(static_cast<int>(face_points.size()));
  owner.push_back(owner_cell);
}

GridGeometry compute_geometry(const Grid& g) {
  GridGeometry geo;
  const auto nf = static_cast<std::size_t>(g.faces());
  geo.face_centre.resize(nf);
  geo.face_area.resize(nf);
  for (int f = 0; f < g.faces(); ++f) {
    const int n = g.face_size(f);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) mean += g.points[static_cast<std::size_t>(g.face_point(f, k))];
    mean /= n;
    // Triangles about the point average; centre weighted by triangle area.
    Eigen::Vector3d sum_n = Eigen::Vector3d::Zero(), sum_ac = Eigen::Vector3d::Zero();
    double sum_a = 0;
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d& a = g.points[static_cast<std::size_t>(g.face_point(f, k))];
      const Eigen::Vector3d& b = g.points[static_cast<std::size_t>(g.face_point(f, (k + 1) % n))];
      const Eigen::Vector3d tn = (b - a).cross(mean - a);
      const double ta = tn.norm();
      sum_n += tn;
      sum_a += ta;
      sum_ac += ta * (a + b + mean) / 3;
    }
    geo.face_centre[static_cast<std::size_t>(f)] =
        sum_a > 0 ? Eigen::Vector3d(sum_ac / sum_a) : mean;
    geo.face_area[static_cast<std::size_t>(f)] = 0.5 * sum_n;
  }
  // Cells: pyramids on each face about the average of the cell's face centres.
  const auto nc = static_cast<std::size_t>(g.cells);
  std::vector<Eigen::Vector3d> estimate(nc, Eigen::Vector3d::Zero());
  std::vector<int> count(nc, 0);
  auto each_side = [&](auto&& fn) {
    for (int f = 0; f < g.faces(); ++f) {
      fn(f, g.owner[static_cast<std::size_t>(f)], 1.0);
      if (f < g.internal_faces()) fn(f, g.neighbour[static_cast<std::size_t>(f)], -1.0);
    }
  };
  each_side([&](int f, int c, double) {
    estimate[static_cast<std::size_t>(c)] += geo.face_centre[static_cast<std::size_t>(f)];
    ++count[static_cast<std::size_t>(c)];
  });
  for (std::size_t c = 0; c < nc; ++c) estimate[c] /= std::max(count[c], 1);
  geo.cell_volume.assign(nc, 0.0);
  std::vector<Eigen::Vector3d> moment(nc, Eigen::Vector3d::Zero());
  each_side([&](int f, int c, double sign) {
    const auto fc = static_cast<std::size_t>(f), cc = static_cast<std::size_t>(c);
    const double v3 =
        sign * geo.face_area[fc].dot(geo.face_centre[fc] - estimate[cc]);  // 3 x pyramid volume
    geo.cell_volume[cc] += v3;
    moment[cc] += v3 * (0.75 * geo.face_centre[fc] + 0.25 * estimate[cc]);
  });
  geo.cell_centre.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    geo.cell_centre[c] = std::abs(geo.cell_volume[c]) > 0
                             ? Eigen::Vector3d(moment[c] / geo.cell_volume[c])
                             : estimate[c];
    geo.cell_volume[c] /= 3;
  }
  return geo;
}

GridQuality measure_quality(const Grid& g, const GridGeometry& geo) {
  GridQuality q;
  q.cells = g.cells;
  q.faces = g.faces();
  q.internal_faces = g.internal_faces();
  q.points = static_cast<int>(g.points.size());
  const auto nc = static_cast<std::size_t>(g.cells);
  std::vector<Eigen::Vector3d> closure(nc, Eigen::Vector3d::Zero());
  std::vector<double> area_sum(nc, 0.0), area_min(nc, 1e300), area_max(nc, 0.0);
  for (int f = 0; f < g.faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    const Eigen::Vector3d& S = geo.face_area[fs];
    const double a = S.norm();
    const auto P = static_cast<std::size_t>(g.owner[fs]);
    closure[P] += S;
    area_sum[P] += a;
    area_min[P] = std::min(area_min[P], a);
    area_max[P] = std::max(area_max[P], a);
    Eigen::Vector3d d;
    if (f < g.internal_faces()) {
      const auto N = static_cast<std::size_t>(g.neighbour[fs]);
      closure[N] -= S;
      area_sum[N] += a;
      area_min[N] = std::min(area_min[N], a);
      area_max[N] = std::max(area_max[N], a);
      d = geo.cell_centre[N] - geo.cell_centre[P];
      // Skewness: distance from the face centre to where the centre line crosses the face.
      const Eigen::Vector3d cross =
          geo.cell_centre[P] + d * (S.dot(geo.face_centre[fs] - geo.cell_centre[P]) / S.dot(d));
      const double skew = (geo.face_centre[fs] - cross).norm() / d.norm();
      if (skew > q.max_skewness) {
        q.max_skewness = skew;
        q.worst_skewed_face = f;
      }
    } else {
      d = geo.face_centre[fs] - geo.cell_centre[P];
    }
    const double c = std::clamp(S.dot(d) / (a * d.norm()), -1.0, 1.0);
    const double angle = std::acos(c) * 180 / std::numbers::pi;
    if (angle > q.max_non_orthogonality) {
      q.max_non_orthogonality = angle;
      q.worst_non_orthogonal_face = f;
    }
  }
  q.min_volume = 1e300;
  for (std::size_t c = 0; c < nc; ++c) {
    q.total_volume += geo.cell_volume[c];
    if (geo.cell_volume[c] < q.min_volume) {
      q.min_volume = geo.cell_volume[c];
      q.worst_cell = static_cast<int>(c);
    }
    q.max_closure_error = std::max(q.max_closure_error, closure[c].norm() / area_sum[c]);
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, area_max[c] / area_min[c]);
  }
  return q;
}

std::string quality_table(const Grid& g, const GridQuality& q) {
  return fmt::format(
      "grid {}: {} cells, {} faces ({} internal), {} points\n"
      "  volume {:.6g} m^3, smallest cell {:.3e} m^3 (cell {})\n"
      "  max non-orthogonality {:.2f} deg, max skewness {:.3f}, max aspect ratio {:.2f}, max "
      "closure error {:.1e}\n",
      g.name, q.cells, q.faces, q.internal_faces, q.points, q.total_volume, q.min_volume,
      q.worst_cell, q.max_non_orthogonality, q.max_skewness, q.max_aspect_ratio,
      q.max_closure_error);
}

void validate(const Grid& g, const GridGeometry& geo, double closure_tolerance) {
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("grid \"" + g.name + "\": " + what);
  };
  if (g.face_offsets.size() != g.owner.size() + 1) fail("face offsets do not match the faces");
  for (int f = 0; f < g.faces(); ++f) {
    if (g.face_size(f) < 3) fail(fmt::format("face {} has {} points", f, g.face_size(f)));
    const int P = g.owner[static_cast<std::size_t>(f)];
    if (P < 0 || P >= g.cells)
      fail(fmt::format("face {} has owner {} outside [0, {})", f, P, g.cells));
    if (f < g.internal_faces() && !(g.neighbour[static_cast<std::size_t>(f)] > P &&
                                    g.neighbour[static_cast<std::size_t>(f)] < g.cells)) {
      fail(fmt::format("internal face {} needs owner {} < neighbour {} < {}", f, P,
                       g.neighbour[static_cast<std::size_t>(f)], g.cells));
    }
  }
  int next = g.internal_faces();
  for (const auto& p : g.patches) {
    if (p.start != next)
      fail(fmt::format("patch \"{}\" starts at face {}, expected {}", p.name, p.start, next));
    next += p.size;
  }
  if (next != g.faces())
    fail(fmt::format("patches cover {} of {} faces", next - g.internal_faces(),
                     g.faces() - g.internal_faces()));
  const GridQuality q = measure_quality(g, geo);
  if (q.min_volume <= 0)
    fail(fmt::format("cell {} has volume {:.3e} m^3", q.worst_cell, q.min_volume));
  if (q.max_closure_error > closure_tolerance)
    fail(fmt::format("a cell is not closed: relative closure error {:.3e}", q.max_closure_error));
}

}  // namespace auvloop::mesher
