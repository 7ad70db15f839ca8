// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/fin_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/mesher/cell_assembly.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::mesher {

namespace {
using Vec2 = Eigen::Vector2d;  // (chord, normal) coordinates of a unit-chord section

void check(bool ok, const std::string& fin, const char* setting, const std::string& why) {
  if (!ok) throw std::invalid_argument(fmt::format("fin grid {}: {} {}", fin, setting, why));
}

void check_spec(const geometry::FinGeometry& fin, const FinGridSpec& s) {
  const auto& n = fin.name();
  check(s.chordwise_cells >= 2, n, "chordwise_cells", "must be at least 2");
  check(s.trailing_edge_fan >= 1, n, "trailing_edge_fan", "must be at least 1");
  check(s.normal_cells >= 0, n, "normal_cells", "must not be negative (0: derive from growth)");
  check(s.cap_cells >= 0, n, "cap_cells", "must not be negative (0: derive from growth)");
  check(s.embedded_cells >= 1, n, "embedded_cells", "must be at least 1");
  check(s.span_cells >= 1, n, "span_cells", "must be at least 1");
  check(s.growth >= 1, n, "growth", "must be at least 1");
  check(s.extent > 0, n, "extent", "must be positive");
  check(s.cap_height > 0, n, "cap_height", "must be positive");
  check(s.first_cell > 0, n, "first_cell", "must be positive");
  const double limit = std::min({s.extent, s.cap_height, fin.set().span});
  check(s.first_cell < limit, n, "first_cell",
        fmt::format("({:.4g} m) must be smaller than extent, cap_height and the span ({:.4g} m)",
                    s.first_cell, limit));
}

// The section loop for unit chord, leading edge first, along the upper side to the trailing
// edge and back along the lower side. Each entry is one outward grid line: its wall point
// (chord fraction, side; `wall` is the entry that owns the point) and its direction in the
// section plane. A sharp trailing edge emits a fan of lines from one wall point, turning from the
// upper to the lower surface normal: the cells there are prisms on the trailing-edge line, and
// the wall cells beside it stay orthogonal (a single bisector line would meet the wall at 82 deg
// for NACA 0012). A blunt trailing edge is two points joined by the base.
struct SectionLoop {
  std::vector<double> x;
  std::vector<int> side;
  std::vector<int> wall;
  std::vector<Vec2> dir;
  int m = 0;    // chordwise cells per side
  int fan = 0;  // cells in the trailing-edge fan (sharp edges)
  [[nodiscard]] int size() const { return static_cast<int>(x.size()); }
  [[nodiscard]] int upper(int k) const { return k; }  // entry of chord node k, upper side
  [[nodiscard]] int lower(int k) const {
    if (k == 0) return 0;
    if (fan == 0) return (size() - k) % size();
    return k == m ? m : 2 * m + fan - k;
  }
};

Vec2 outward(const Vec2& a, const Vec2& b) {
  const Vec2 t = (b - a).normalized();
  return {-t.y(), t.x()};  // clockwise loop: outward is the left-hand normal
}

SectionLoop section_loop(const geometry::NacaSection& sec, int m, int fan) {
  SectionLoop loop;
  loop.m = m;
  loop.fan = sec.sharp_trailing_edge ? fan : 0;
  const auto add = [&](double x, int side, int wall) {
    loop.x.push_back(x);
    loop.side.push_back(side);
    loop.wall.push_back(wall < 0 ? loop.size() - 1 : wall);
  };
  std::vector<double> xs;
  for (int k = 0; k <= m; ++k) xs.push_back(0.5 * (1 - std::cos(std::numbers::pi * k / m)));
  for (int k = 0; k <= m; ++k) add(xs[static_cast<std::size_t>(k)], 1, -1);
  for (int t = 1; t <= loop.fan; ++t) add(1.0, 1, m);  // the fan shares the trailing-edge point
  for (int k = loop.fan > 0 ? m - 1 : m; k >= 1; --k) add(xs[static_cast<std::size_t>(k)], -1, -1);
  // Directions: wall normals at each point (the average of its two segments' normals), and the
  // fan's directions evenly spaced in angle between its two segments' normals.
  const int n = loop.size();
  const auto q = [&](int p) {
    const auto pu = static_cast<std::size_t>((p + n) % n);
    return sec.surface(loop.x[pu], loop.side[pu]);
  };
  const auto wall_of = [&](int p) { return loop.wall[static_cast<std::size_t>((p + n) % n)]; };
  loop.dir.resize(static_cast<std::size_t>(n));
  for (int p = 0; p < n; ++p) {
    int prev = p - 1, next = p + 1;  // neighbouring distinct wall points
    while (wall_of(prev) == wall_of(p)) --prev;
    while (wall_of(next) == wall_of(p)) ++next;
    const Vec2 before = outward(q(prev), q(p)), after = outward(q(p), q(next));
    auto& d = loop.dir[static_cast<std::size_t>(p)];
    if (loop.fan == 0 || wall_of(p) != m) {
      d = (before + after).normalized();
      continue;
    }
    const double t = static_cast<double>(p - m) / loop.fan;
    const double a = std::atan2(before.y(), before.x()), b = std::atan2(after.y(), after.x());
    d = Vec2(std::cos(a + t * (b - a)), std::sin(a + t * (b - a)));
  }
  return loop;
}

// Stations along the post (rho, m from the hull axis): uniform inside the hull, clustered at
// the tip from both sides. Returns the stations and the index of the tip.
std::pair<std::vector<double>, int> span_stations(const geometry::FinGeometry& fin,
                                                  const FinGridSpec& s) {
  const double inner = fin.inner_radius(), root = fin.set().root_radius();
  const double tip = fin.set().tip_radius;
  auto rho = graded_nodes(inner, root, s.embedded_cells);
  // Down from the tip: from the tip's first cell, growing by `growth` until the cells reach the
  // uniform size (tip - root) / span_cells, then uniform to the root. (Stretching span_cells
  // cells from a y+ first cell alone would leave cells of several centimetres at the root.)
  const double uniform = (tip - root) / s.span_cells;
  std::vector<double> down{0.0};
  for (double h = s.first_cell; h < uniform && down.back() + h < 0.5 * (tip - root); h *= s.growth)
    down.push_back(down.back() + h);
  const double rest = (tip - root) - down.back();
  const int n_rest = std::max(1, static_cast<int>(std::ceil(rest / uniform - 1e-9)));
  const double from = down.back();
  for (int k = 1; k <= n_rest; ++k) down.push_back(from + rest * k / n_rest);
  for (auto it = down.rbegin() + 1; it != down.rend(); ++it) rho.push_back(tip - *it);
  const int k_tip = static_cast<int>(rho.size()) - 1;
  const auto up = s.cap_cells > 0 ? stretched_nodes(0, s.cap_height, s.first_cell, s.cap_cells)
                                  : grown_nodes(0, s.cap_height, s.first_cell, s.growth);
  for (std::size_t k = 1; k < up.size(); ++k) rho.push_back(tip + up[k]);
  return {rho, k_tip};
}
}  // namespace

Grid fin_grid(const geometry::FinGeometry& fin, const FinGridSpec& s) {
  check_spec(fin, s);
  const auto& sec = fin.set().section;
  const SectionLoop loop = section_loop(sec, s.chordwise_cells, s.trailing_edge_fan);
  const auto dist = s.normal_cells > 0 ? stretched_nodes(0, s.extent, s.first_cell, s.normal_cells)
                                       : grown_nodes(0, s.extent, s.first_cell, s.growth);
  // (Named copies, not a structured binding: clang 14 cannot capture one in a lambda.)
  const auto stations = span_stations(fin, s);
  const auto& rho = std::get<0>(stations);
  const int k_tip = std::get<1>(stations);
  const int np = loop.size(), nj = static_cast<int>(dist.size()) - 1;
  const int nk = static_cast<int>(rho.size()) - 1;
  const double tip = fin.set().tip_radius;

  CellAssembler a;
  std::vector<std::pair<int, int>> tag;  // (j, k) of every point, for the patch classifier
  std::vector<int> index;                // point of line p, layer j, station k
  for (int k = 0; k <= nk; ++k) {
    const double r = std::min(rho[static_cast<std::size_t>(k)], tip);
    const Eigen::Vector3d lift = (rho[static_cast<std::size_t>(k)] - r) * fin.span_axis();
    for (int j = 0; j <= nj; ++j) {
      for (int p = 0; p < np; ++p) {
        const auto pu = static_cast<std::size_t>(p);
        if (j == 0 && loop.wall[pu] != p) {  // a fan line: its wall point exists already
          index.push_back(index[index.size() - pu + static_cast<std::size_t>(loop.wall[pu])]);
          continue;
        }
        const Eigen::Vector3d wall = fin.point(r, loop.x[pu], loop.side[pu], 0.0);
        const Vec2& d = loop.dir[pu];
        const Eigen::Vector3d out = d.x() * fin.chord_axis() + d.y() * fin.normal_axis();
        index.push_back(a.add_point(wall + lift + dist[static_cast<std::size_t>(j)] * out));
        tag.emplace_back(j, k);
      }
    }
  }
  const auto P = [&](int p, int j, int k) {
    return index[static_cast<std::size_t>((p % np) + np * (j + (nj + 1) * k))];
  };
  const auto block = [&](auto corners, auto sample) {
    // One corner order per block, chosen on a representative cell; validate() checks all.
    const bool flip = !(a.signed_volume(sample) > 0);
    return [corners, flip](auto... idx) {
      HexCorners c = corners(idx...);
      if (flip) std::swap_ranges(c.begin(), c.begin() + 4, c.begin() + 4);
      return c;
    };
  };
  const auto o_corners = [&](int p, int j, int k) {
    return HexCorners{
        P(p, j, k),     P(p + 1, j, k),     P(p + 1, j + 1, k),     P(p, j + 1, k),
        P(p, j, k + 1), P(p + 1, j, k + 1), P(p + 1, j + 1, k + 1), P(p, j + 1, k + 1)};
  };
  const auto column_corners = [&](int m, int k) {
    const int u0 = loop.upper(m), u1 = loop.upper(m + 1), l1 = loop.lower(m + 1),
              l0 = loop.lower(m);
    return HexCorners{P(u0, 0, k),     P(u1, 0, k),     P(l1, 0, k),     P(l0, 0, k),
                      P(u0, 0, k + 1), P(u1, 0, k + 1), P(l1, 0, k + 1), P(l0, 0, k + 1)};
  };
  const auto o_hex = block(o_corners, o_corners(loop.m / 2, 0, 0));
  const auto column_hex = block(column_corners, column_corners(loop.m / 2, nk - 1));
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < nj; ++j)
      for (int p = 0; p < np; ++p) a.add_hex(o_hex(p, j, k));
  for (int k = k_tip; k < nk; ++k)
    for (int m = 0; m < loop.m; ++m) a.add_hex(column_hex(m, k));

  const auto& name = fin.name();
  return a.build(name, {{name, PatchType::wall}, {name + "_overset", PatchType::overset}},
                 [&](std::span<const int> f) {
                   const auto all = [&](auto pred) {
                     return std::all_of(f.begin(), f.end(), [&](int q) {
                       return pred(tag[static_cast<std::size_t>(q)]);
                     });
                   };
                   if (all([&](auto t) { return t.first == 0 && t.second <= k_tip; })) return 0;
                   if (all([&](auto t) { return t.first == nj; }) ||
                       all([&](auto t) { return t.second == 0; }) ||
                       all([&](auto t) { return t.second == nk; }))
                     return 1;
                   return -1;
                 });
}

Eigen::Isometry3d fin_placement(const geometry::FinGeometry& fin, double deflection) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(fin.post_origin());
  t.rotate(fin.rotation(deflection));
  t.translate(-fin.post_origin());
  return t;
}

}  // namespace auvloop::mesher
