// SPDX-License-Identifier: GPL-3.0-or-later
// The cylinder in a channel as an overset pair (cylinder_grid.hpp, cylinder_overset):
//   1. the O-grid: nodes (r_j, theta_i) with r graded from the wall, one layer of hexahedra
//      between z = 0 and the thickness, the angle wrapping round (node i = around is node 0);
//   2. the background: a Cartesian channel, uniform to near_end and stretched from there to the
//      outlet with its first cell the uniform spacing;
//   3. the solid: the cylinder as a closed prism through both grids' thickness and beyond.
// The unconfined variant: the same O-grid at the origin over a square box whose uniform core
// grows geometrically to the sides (cored_nodes).
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/geometry/surface.hpp"
#include "auvloop/mesher/cylinder_grid.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::mesher {

namespace {
// Patch index by face centre, z first (the empty sides).
int side(const Eigen::Vector3d& f, double thickness) {
  const double tol = 1e-9;
  if (std::abs(f.z()) < tol) return 0;
  if (std::abs(f.z() - thickness) < tol) return 1;
  return -1;
}

Grid o_grid(const CylinderOversetSpec& s) {
  const int n = s.around, nr = s.radial_cells;
  const auto radial = graded_nodes(s.radius, s.outer_radius, nr,
                                   std::pow(s.radial_ratio, 1.0 / std::max(1, nr - 1)));
  std::vector<Eigen::Vector3d> points;
  const auto id = [&](int i, int j, int k) { return ((i % n) + n * j) + n * (nr + 1) * k; };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j <= nr; ++j)
      for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n, r = radial[static_cast<std::size_t>(j)];
        points.emplace_back(s.cx + r * std::cos(a), s.cy + r * std::sin(a), k * s.thickness);
      }
  std::vector<std::array<int, 8>> hexes;
  for (int j = 0; j < nr; ++j)
    for (int i = 0; i < n; ++i)  // (i, j) -> (i, j + 1) -> (i + 1, j + 1): counter-clockwise
      hexes.push_back({id(i, j, 0), id(i, j + 1, 0), id(i + 1, j + 1, 0), id(i + 1, j, 0),
                       id(i, j, 1), id(i, j + 1, 1), id(i + 1, j + 1, 1), id(i + 1, j, 1)});
  std::vector<Patch> patches{{"cylinder", PatchType::wall, 0, 0, -1},
                             {"outer", PatchType::overset, 0, 0, -1},
                             {"front", PatchType::empty, 0, 0, -1},
                             {"back", PatchType::empty, 0, 0, -1}};
  const double mid = 0.5 * (s.radius + s.outer_radius);
  return hex_grid(
      std::move(points), hexes, std::move(patches),
      [&](const Eigen::Vector3d& f) {
        if (const int z = side(f, s.thickness); z >= 0) return 2 + z;
        return std::hypot(f.x() - s.cx, f.y() - s.cy) < mid ? 0 : 1;
      },
      "cylinder");
}

Grid background(const CylinderOversetSpec& s) {
  const double h = s.spacing > 0 ? s.spacing : 2 * std::numbers::pi * s.outer_radius / s.around;
  const int nx = std::max(1, static_cast<int>(std::lround(s.near_end / h)));
  const int ny = std::max(1, static_cast<int>(std::lround(s.height / h)));
  std::vector<double> x = graded_nodes(0, s.near_end, nx);
  const auto down = stretched_nodes(s.near_end, s.length, s.near_end / nx, s.downstream_cells);
  x.insert(x.end(), down.begin() + 1, down.end());
  const auto y = graded_nodes(0, s.height, ny);
  BoxPatches names;
  names.names = {"inlet", "outlet", "bottom", "top", "front", "back"};
  names.types = {PatchType::inlet, PatchType::outlet, PatchType::wall,
                 PatchType::wall,  PatchType::empty,  PatchType::empty};
  Grid g = cartesian_box(x, y, {0.0, s.thickness}, names);
  g.name = "background";
  return g;
}
}  // namespace

CylinderOverset unconfined_cylinder_overset(const UnconfinedCylinderSpec& u) {
  const double D = u.diameter, half = 0.5 * u.extent * D;
  const double R = u.outer_radius * D;
  if (!(D > 0) || !(u.outer_radius > 0.5) || !(u.growth > 1) ||
      !(std::min({u.core_upstream, u.core_downstream, u.core_side}) * D > R) ||
      !(std::max({u.core_upstream, u.core_downstream, u.core_side}) * D < half))
    throw std::invalid_argument(fmt::format(
        "unconfined_cylinder_overset: the O-grid (to {} D) must fit inside the uniform core "
        "(-{} .. {} D by +-{} D) and the core inside the box ({} D across), growth above 1",
        u.outer_radius, u.core_upstream, u.core_downstream, u.core_side, u.extent));
  CylinderOversetSpec s;  // the O-grid's part of the channel spec
  s.cx = 0;
  s.cy = 0;
  s.radius = 0.5 * D;
  s.outer_radius = R;
  s.around = u.around;
  s.radial_cells = u.radial_cells;
  s.radial_ratio = u.radial_ratio;
  s.thickness = u.thickness * D;
  CylinderOverset out;
  out.cylinder = o_grid(s);
  const double h = 2 * std::numbers::pi * R / u.around;
  const auto x = cored_nodes(half, -u.core_upstream * D, u.core_downstream * D, h, u.growth);
  const auto y = cored_nodes(half, -u.core_side * D, u.core_side * D, h, u.growth);
  BoxPatches names;
  names.names = {"west", "east", "south", "north", "front", "back"};
  names.types = {PatchType::inlet, PatchType::outlet, PatchType::inlet,
                 PatchType::inlet, PatchType::empty,  PatchType::empty};
  out.background = cartesian_box(x, y, {0.0, s.thickness}, names);
  out.background.name = "background";
  out.solid = std::make_shared<const geometry::SurfaceMesh>(geometry::cylinder_surface(
      0, 0, s.radius, -s.thickness, 2 * s.thickness, std::max(512, 8 * s.around)));
  return out;
}

CylinderOverset cylinder_overset(const CylinderOversetSpec& s) {
  const double gap = std::min({s.cx, s.cy, s.height - s.cy, s.near_end - s.cx}) - s.outer_radius;
  if (!(s.radius > 0) || !(s.outer_radius > s.radius) || !(gap > 0) || s.around < 8 ||
      s.radial_cells < 2)
    throw std::invalid_argument(fmt::format(
        "cylinder_overset: the O-grid (radius {} to {}, {} x {} cells) must fit in the channel's "
        "uniform part with room to spare",
        s.radius, s.outer_radius, s.around, s.radial_cells));
  CylinderOverset out;
  out.cylinder = o_grid(s);
  out.background = background(s);
  out.solid = std::make_shared<const geometry::SurfaceMesh>(geometry::cylinder_surface(
      s.cx, s.cy, s.radius, -s.thickness, 2 * s.thickness, std::max(512, 8 * s.around)));
  return out;
}

}  // namespace auvloop::mesher
