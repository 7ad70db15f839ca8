// SPDX-License-Identifier: GPL-3.0-or-later
// The 2D foil grids (foil_grid.hpp states the construction, steps 1 to 4).
#include "auvloop/mesher/foil_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/geometry/surface.hpp"
#include "auvloop/mesher/cell_assembly.hpp"
#include "auvloop/mesher/generators.hpp"
#include "section_loop.hpp"

namespace auvloop::mesher {

namespace {
using detail::Vec2;

void check(bool ok, const char* setting, const std::string& why) {
  if (!ok) throw std::invalid_argument(fmt::format("foil grids: {} {}", setting, why));
}

// The points of every line: lines[p][j], j = 0 the wall; the O-grid's layers to nj, then the
// far rings (none for the O-grid alone).
struct Lines {
  std::vector<std::vector<Vec2>> points;
  std::vector<int> wall;  // per line: the line owning its wall point (a fan shares one)
  int layers = 0;         // the O-grid's: points[p][layers] lies on the circle
};

Lines lines(const FoilOversetSpec& s) {
  const auto loop = detail::section_loop(s.section, s.chordwise_cells, s.trailing_edge_fan);
  const int np = loop.size();
  const double c = s.chord, R = s.outer_radius * c;
  std::vector<Vec2> w(static_cast<std::size_t>(np));
  for (int p = 0; p < np; ++p) {
    const auto pu = static_cast<std::size_t>(p);
    w[pu] = c * (s.section.surface(loop.x[pu], loop.side[pu]) - Vec2(s.pivot, 0));
  }
  // 1. the circle points: the angle advances with arc length plus half the normal's turning
  std::vector<double> t(static_cast<std::size_t>(np) + 1, 0.0);
  double perimeter = 0;
  for (int p = 0; p < np; ++p)
    perimeter +=
        (w[static_cast<std::size_t>((p + 1) % np)] - w[static_cast<std::size_t>(p)]).norm();
  for (int p = 1; p <= np; ++p) {
    const auto a = static_cast<std::size_t>(p - 1), b = static_cast<std::size_t>(p % np);
    const double turn = std::acos(std::clamp(loop.dir[a].dot(loop.dir[b]), -1.0, 1.0));
    t[static_cast<std::size_t>(p)] =
        t[a] + (w[b] - w[a]).norm() / perimeter + 0.5 * turn / (2 * std::numbers::pi);
  }
  std::vector<Vec2> circle(static_cast<std::size_t>(np));
  double mean_length = 0;
  for (int p = 0; p < np; ++p) {
    const auto pu = static_cast<std::size_t>(p);
    // Half by that measure, half by the line's index: the lines the cosine spacing crowds at
    // the edges spread out over the circle.
    const double u = 0.5 * (t[pu] / t.back() + static_cast<double>(p) / np);
    const double theta = std::numbers::pi * (1 - 2 * u);  // the leading edge at pi, upper first
    circle[pu] = R * Vec2(std::cos(theta), std::sin(theta));
    mean_length += (circle[pu] - w[pu]).norm() / np;
  }
  const auto sn = stretched_nodes(0, 1, s.first_cell * c / mean_length, s.normal_cells);
  Lines out;
  out.layers = s.normal_cells;
  out.wall = loop.wall;
  out.points.resize(static_cast<std::size_t>(np));
  for (int p = 0; p < np; ++p) {
    const auto pu = static_cast<std::size_t>(p);
    const double L = (circle[pu] - w[pu]).norm();
    const Vec2 radial = circle[pu] / R;
    for (double x : sn) {  // cubic Hermite: leaves the wall along n, meets the circle radially
      const double h0 = (2 * x - 3) * x * x + 1, h1 = 1 - h0, h2 = ((x - 2) * x + 1) * x,
                   h3 = (x - 1) * x * x;
      out.points[pu].push_back(h0 * w[pu] + h1 * circle[pu] +
                               L * (h2 * loop.dir[pu] + h3 * radial));
    }
  }
  return out;
}

// 2. the far rings: radial from the circle, growing from the O-grid's mean last cell
void add_far_rings(Lines& l, const FoilOversetSpec& s) {
  const double R = s.outer_radius * s.chord;
  double last = 0;
  for (const auto& line : l.points) last += (line.back() - line[line.size() - 2]).norm();
  last /= static_cast<double>(l.points.size());
  const auto r = grown_nodes(R, s.far_radius * s.chord, last, s.growth);
  for (auto& line : l.points) {
    const Vec2 e = line.back() / R;
    for (std::size_t j = 1; j < r.size(); ++j) line.push_back(r[j] * e);
  }
}

Grid build(const Lines& l, const FoilOversetSpec& s, const std::string& name,
           const std::string& outer, PatchType outer_type) {
  const int np = static_cast<int>(l.points.size());
  const int nj = static_cast<int>(l.points.front().size()) - 1;
  const double dz = s.thickness * s.chord;
  CellAssembler a;
  std::vector<int> index;  // point of line p, layer j, level k
  std::vector<int> layer;  // per point: its j
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= nj; ++j)
      for (int p = 0; p < np; ++p) {
        const auto pu = static_cast<std::size_t>(p);
        if (j == 0 && l.wall[pu] != p) {  // a fan line: its wall point exists already
          index.push_back(index[index.size() - pu + static_cast<std::size_t>(l.wall[pu])]);
          continue;
        }
        const Vec2& q = l.points[pu][static_cast<std::size_t>(j)];
        index.push_back(a.add_point({q.x(), q.y(), k * dz}));
        layer.push_back(j);
      }
  const auto P = [&](int p, int j, int k) {
    return index[static_cast<std::size_t>((p % np) + np * (j + (nj + 1) * k))];
  };
  const auto corners = [&](int p, int j) {
    return HexCorners{P(p, j, 0), P(p + 1, j, 0), P(p + 1, j + 1, 0), P(p, j + 1, 0),
                      P(p, j, 1), P(p + 1, j, 1), P(p + 1, j + 1, 1), P(p, j + 1, 1)};
  };
  const bool flip = !(a.signed_volume(corners(s.chordwise_cells / 2, 0)) > 0);
  for (int j = 0; j < nj; ++j)
    for (int p = 0; p < np; ++p) {
      auto h = corners(p, j);
      if (flip) std::swap_ranges(h.begin(), h.begin() + 4, h.begin() + 4);
      a.add_hex(h);
    }
  const auto& pts = a.points();
  return a.build(name,
                 {{"foil", PatchType::wall},
                  {outer, outer_type},
                  {"front", PatchType::empty},
                  {"back", PatchType::empty}},
                 [&](std::span<const int> f) {
                   const auto all = [&](auto pred) {
                     return std::all_of(f.begin(), f.end(), pred);
                   };
                   const auto z = [&](int q) { return pts[static_cast<std::size_t>(q)].z(); };
                   if (all([&](int q) { return z(q) < 0.5 * dz; })) return 2;
                   if (all([&](int q) { return z(q) > 0.5 * dz; })) return 3;
                   if (all([&](int q) { return layer[static_cast<std::size_t>(q)] == 0; }))
                     return 0;
                   if (all([&](int q) { return layer[static_cast<std::size_t>(q)] == nj; }))
                     return 1;
                   return -1;
                 });
}
}  // namespace

FoilGrids foil_grids(const FoilOversetSpec& s) {
  check(s.chord > 0, "chord", "must be positive");
  check(s.pivot >= 0 && s.pivot <= 1, "pivot", "must be a chord fraction in [0, 1]");
  check(s.chordwise_cells >= 4, "chordwise_cells", "must be at least 4");
  check(s.trailing_edge_fan >= 1, "trailing_edge_fan", "must be at least 1");
  check(s.normal_cells >= 2, "normal_cells", "must be at least 2");
  check(s.outer_radius > 1.2 * std::max(s.pivot, 1 - s.pivot), "outer_radius",
        "must exceed the farthest edge's distance from the pivot by a fifth");
  check(s.first_cell > 0 && s.first_cell < 0.1 * (s.outer_radius - std::max(s.pivot, 1 - s.pivot)),
        "first_cell", "must be positive and a small part of the gap to the circle");
  check(s.far_radius > 2 * s.outer_radius, "far_radius", "must be beyond twice outer_radius");
  check(s.growth > 1, "growth", "must exceed 1");
  check(std::min({s.core_upstream, s.core_downstream, s.core_side}) > s.outer_radius &&
            std::max({s.core_upstream, s.core_downstream, s.core_side}) < 0.5 * s.extent,
        "core", "must contain the O-grid's circle and lie inside the background");
  check(s.thickness > 0, "thickness", "must be positive");
  check(s.spacing >= 0 && s.spacing < s.outer_radius, "spacing",
        "must be 0 (the O-grid's outer cell size) or positive and below outer_radius");
  FoilGrids out;
  auto l = lines(s);
  out.foil = build(l, s, "foil", "outer", PatchType::overset);  // 1.
  const double h = s.spacing > 0 ? s.spacing * s.chord
                                 : 2 * std::numbers::pi * s.outer_radius * s.chord /
                                       static_cast<double>(l.points.size());
  add_far_rings(l, s);  // 2.
  out.single = build(l, s, "single", "far", PatchType::inlet);
  const double c = s.chord, half = 0.5 * s.extent * c;  // 3.
  BoxPatches names;
  names.names = {"west", "east", "south", "north", "front", "back"};
  names.types = {PatchType::inlet, PatchType::outlet, PatchType::inlet,
                 PatchType::inlet, PatchType::empty,  PatchType::empty};
  out.background =
      cartesian_box(cored_nodes(half, -s.core_upstream * c, s.core_downstream * c, h, s.growth),
                    cored_nodes(half, -s.core_side * c, s.core_side * c, h, s.growth),
                    {0.0, s.thickness * c}, names, "background");
  std::vector<Eigen::Vector2d> section;  // 4. counter-clockwise: lower side forward, upper back
  const int n = 400;
  const auto at = [&](int k, int side) {
    const double x = 0.5 * (1 - std::cos(std::numbers::pi * k / n));
    return Eigen::Vector2d(c * (s.section.surface(x, side) - Vec2(s.pivot, 0)));
  };
  for (int k = 0; k <= n; ++k) section.push_back(at(k, -1));
  // A sharp trailing edge is one point; a blunt one closes with its base.
  for (int k = s.section.sharp_trailing_edge ? n - 1 : n; k > 0; --k) section.push_back(at(k, 1));
  out.solid = std::make_shared<const geometry::SurfaceMesh>(geometry::prism_surface(
      section, {(0.3 - s.pivot) * c, 0.0}, -s.thickness * c, 2 * s.thickness * c, "foil"));
  return out;
}

}  // namespace auvloop::mesher
