// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/cylinder_grid.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "auvloop/mesher/generators.hpp"

namespace auvloop::mesher {

Grid hex_grid(std::vector<Eigen::Vector3d> points, const std::vector<std::array<int, 8>>& hexes,
              std::vector<Patch> patches,
              const std::function<int(const Eigen::Vector3d&)>& patch_of, const std::string& name) {
  // The six faces of a hexahedron, each ordered so that its right-hand normal points outward.
  static constexpr int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                       {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  struct Half {
    int cell;
    std::array<int, 4> pts;
  };
  std::map<std::array<int, 4>, std::vector<Half>> by_key;
  for (std::size_t c = 0; c < hexes.size(); ++c) {
    for (const auto& f : kFaces) {
      std::array<int, 4> pts{};
      for (int k = 0; k < 4; ++k)
        pts[static_cast<std::size_t>(k)] = hexes[c][static_cast<std::size_t>(f[k])];
      auto key = pts;
      std::sort(key.begin(), key.end());
      by_key[key].push_back({static_cast<int>(c), pts});
    }
  }
  struct Internal {
    int owner, neighbour;
    std::array<int, 4> pts;
  };
  std::vector<Internal> internal;
  std::vector<std::vector<Half>> boundary(patches.size());
  for (auto& [key, halves] : by_key) {
    if (halves.size() == 2) {
      const auto& a = halves[0].cell < halves[1].cell ? halves[0] : halves[1];
      const auto& b = halves[0].cell < halves[1].cell ? halves[1] : halves[0];
      internal.push_back({a.cell, b.cell, a.pts});
    } else if (halves.size() == 1) {
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int p : halves[0].pts) centre += points[static_cast<std::size_t>(p)] / 4;
      const int patch = patch_of(centre);
      if (patch < 0 || patch >= static_cast<int>(patches.size()))
        throw std::logic_error("hex_grid: a boundary face belongs to no patch");
      boundary[static_cast<std::size_t>(patch)].push_back(halves[0]);
    } else {
      throw std::logic_error("hex_grid: a face is shared by more than two cells");
    }
  }
  std::sort(internal.begin(), internal.end(), [](const Internal& a, const Internal& b) {
    return a.owner != b.owner ? a.owner < b.owner : a.neighbour < b.neighbour;
  });
  Grid g;
  g.name = name;
  g.points = std::move(points);
  g.cells = static_cast<int>(hexes.size());
  for (const auto& f : internal) {
    g.add_face({f.pts[0], f.pts[1], f.pts[2], f.pts[3]}, f.owner);
    g.neighbour.push_back(f.neighbour);
  }
  for (std::size_t p = 0; p < patches.size(); ++p) {
    patches[p].start = g.faces();
    for (const auto& h : boundary[p]) g.add_face({h.pts[0], h.pts[1], h.pts[2], h.pts[3]}, h.cell);
    patches[p].size = g.faces() - patches[p].start;
  }
  g.patches = std::move(patches);
  return g;
}

namespace {
// Index of a point in the deduplicated list (exact match of coordinates rounded to 1e-12 m).
class PointSet {
 public:
  int add(const Eigen::Vector3d& p) {
    const std::array<long long, 3> key{std::llround(p.x() * 1e12), std::llround(p.y() * 1e12),
                                       std::llround(p.z() * 1e12)};
    const auto [it, inserted] = index_.try_emplace(key, static_cast<int>(points.size()));
    if (inserted) points.push_back(p);
    return it->second;
  }
  std::vector<Eigen::Vector3d> points;

 private:
  std::map<std::array<long long, 3>, int> index_;
};

// One-layer hexahedra from a structured block of 2D nodes xy(i, j), i < ni, j < nj.
template <class F>
void add_block(PointSet& ps, std::vector<std::array<int, 8>>& hexes, int ni, int nj, F&& xy,
               double dz) {
  auto id = [&](int i, int j, int k) {
    const Eigen::Vector2d p = xy(i, j);
    return ps.add({p.x(), p.y(), k * dz});
  };
  for (int j = 0; j + 1 < nj; ++j)
    for (int i = 0; i + 1 < ni; ++i) {
      std::array<int, 8> h{id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0),
                           id(i, j, 1), id(i + 1, j, 1), id(i + 1, j + 1, 1), id(i, j + 1, 1)};
      // Counter-clockwise seen from +z, or the hexahedron is inside out: flip it.
      const Eigen::Vector2d a = xy(i + 1, j) - xy(i, j), b = xy(i, j + 1) - xy(i, j);
      if (a.x() * b.y() - a.y() * b.x() < 0) {
        std::swap(h[1], h[3]);
        std::swap(h[5], h[7]);
      }
      hexes.push_back(h);
    }
}

// Uniform nodes from a to b with about `h` spacing (at least one cell).
std::vector<double> uniform_nodes(double a, double b, double h) {
  const int n = std::max(1, static_cast<int>(std::lround((b - a) / h)));
  return graded_nodes(a, b, n);
}

// A Cartesian block on the given x and y nodes.
void add_cartesian(PointSet& ps, std::vector<std::array<int, 8>>& hexes,
                   const std::vector<double>& x, const std::vector<double>& y, double dz) {
  add_block(
      ps, hexes, static_cast<int>(x.size()), static_cast<int>(y.size()),
      [&](int i, int j) -> Eigen::Vector2d {
        return {x[static_cast<std::size_t>(i)], y[static_cast<std::size_t>(j)]};
      },
      dz);
}

std::vector<double> concat(std::vector<double> a, const std::vector<double>& b) {
  a.insert(a.end(), b.begin() + 1, b.end());  // b starts where a ends
  return a;
}
}  // namespace

Grid cylinder_channel(const CylinderChannelSpec& s, const std::string& name) {
  const double b = s.box_half_width;
  const double x0 = s.cx - b, x1 = s.cx + b, y0 = s.cy - b, y1 = s.cy + b;
  if (b <= s.radius || x0 < -1e-12 || x1 >= s.length || y0 < -1e-12 || y1 > s.height + 1e-12)
    throw std::invalid_argument("cylinder_channel: the cylinder's box must fit in the channel");
  const int m = s.cells_per_side;
  // Box corners counter-clockwise from bottom-right; side q runs from corner q to q + 1.
  const std::array<Eigen::Vector2d, 4> corner{Eigen::Vector2d(x1, y0), Eigen::Vector2d(x1, y1),
                                              Eigen::Vector2d(x0, y1), Eigen::Vector2d(x0, y0)};
  const Eigen::Vector2d c(s.cx, s.cy);
  std::array<double, 4> angle{};
  for (std::size_t q = 0; q < 4; ++q)
    angle[q] = std::atan2(corner[q].y() - c.y(), corner[q].x() - c.x());
  const auto radial = graded_nodes(0, 1, s.radial_cells,
                                   std::pow(s.radial_ratio, 1.0 / std::max(1, s.radial_cells - 1)));
  PointSet ps;
  std::vector<std::array<int, 8>> hexes;
  for (std::size_t q = 0; q < 4; ++q) {
    const std::size_t q1 = (q + 1) % 4;
    double a0 = angle[q], a1 = angle[q1];
    if (a1 < a0) a1 += 2 * std::numbers::pi;
    add_block(
        ps, hexes, m + 1, s.radial_cells + 1,
        [&](int i, int j) -> Eigen::Vector2d {
          const double t = static_cast<double>(i) / m;
          const double a = a0 + t * (a1 - a0);
          const Eigen::Vector2d wall = c + s.radius * Eigen::Vector2d(std::cos(a), std::sin(a));
          const Eigen::Vector2d outer = corner[q] + t * (corner[q1] - corner[q]);
          const double r = radial[static_cast<std::size_t>(j)];
          return wall + r * (outer - wall);
        },
        s.thickness);
  }
  // Cartesian blocks around the box with about the box side's spacing (none where the box
  // touches the channel's side), so that no O-grid corner lies on the channel's boundary.
  const double h = 2 * b / m;
  const auto xb = graded_nodes(x0, x1, m), yb = graded_nodes(y0, y1, m);
  std::vector<std::vector<double>> xs{xb}, ys{yb};
  if (x0 > 1e-12) xs.push_back(uniform_nodes(0, x0, h));
  if (y0 > 1e-12) ys.push_back(uniform_nodes(0, y0, h));
  if (y1 < s.height - 1e-12) ys.push_back(uniform_nodes(y1, s.height, h));
  for (const auto& x : xs)
    for (const auto& y : ys)
      if (&x != &xs[0] || &y != &ys[0]) add_cartesian(ps, hexes, x, y, s.thickness);
  std::vector<double> y_all = yb;
  if (y0 > 1e-12) y_all = concat(uniform_nodes(0, y0, h), y_all);
  if (y1 < s.height - 1e-12) y_all = concat(y_all, uniform_nodes(y1, s.height, h));
  const auto xd =
      graded_nodes(x1, s.length, s.downstream_cells,
                   std::pow(s.downstream_ratio, 1.0 / std::max(1, s.downstream_cells - 1)));
  add_cartesian(ps, hexes, xd, y_all, s.thickness);
  std::vector<Patch> patches{
      {"inlet", PatchType::inlet, 0, 0, -1}, {"outlet", PatchType::outlet, 0, 0, -1},
      {"walls", PatchType::wall, 0, 0, -1},  {"cylinder", PatchType::wall, 0, 0, -1},
      {"front", PatchType::empty, 0, 0, -1}, {"back", PatchType::empty, 0, 0, -1}};
  const double tol = 1e-9;
  auto classify = [&](const Eigen::Vector3d& f) {
    if (std::abs(f.z()) < tol) return 4;
    if (std::abs(f.z() - s.thickness) < tol) return 5;
    if (std::abs(f.x()) < tol) return 0;
    if (std::abs(f.x() - s.length) < tol) return 1;
    if (std::abs(f.y()) < tol || std::abs(f.y() - s.height) < tol) return 2;
    return 3;  // the only other boundary is the cylinder
  };
  return hex_grid(std::move(ps.points), hexes, std::move(patches), classify, name);
}

}  // namespace auvloop::mesher
