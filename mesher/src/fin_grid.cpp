// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/fin_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/mesher/cell_assembly.hpp"
#include "auvloop/mesher/generators.hpp"
#include "section_loop.hpp"

namespace auvloop::mesher {

namespace {
using detail::section_loop;
using detail::SectionLoop;
using detail::Vec2;

void check(bool ok, const std::string& fin, const char* setting, const std::string& why) {
  if (!ok) throw std::invalid_argument(fmt::format("fin grid {}: {} {}", fin, setting, why));
}

void check_spec(const geometry::FinGeometry& fin, const FinGridSpec& s) {
  const auto& n = fin.name();
  check(s.chordwise_cells >= 2, n, "chordwise_cells", "must be at least 2");
  check(s.trailing_edge_fan >= 1, n, "trailing_edge_fan", "must be at least 1");
  check(s.normal_cells >= 0, n, "normal_cells", "must not be negative (0: derive from growth)");
  check(s.cap_cells >= 0, n, "cap_cells", "must not be negative (0: derive from growth)");
  check(s.gap_cells >= 1, n, "gap_cells", "must be at least 1");
  check(s.root_depth > 1.5 * fin.set().root_gap, n, "root_depth",
        fmt::format("({:.4g} m) must exceed one and a half root gaps ({:.4g} m): the grid must "
                    "reach through the gap into the hull",
                    s.root_depth, 1.5 * fin.set().root_gap));
  check(s.span_cells >= 1, n, "span_cells", "must be at least 1");
  check(s.growth >= 1, n, "growth", "must be at least 1");
  check(s.extent > 0, n, "extent", "must be positive");
  check(s.cap_height > 0, n, "cap_height", "must be positive");
  check(s.first_cell > 0, n, "first_cell", "must be positive");
  const double limit = std::min({s.extent, s.cap_height, s.root_depth, fin.set().span});
  check(s.first_cell < limit, n, "first_cell",
        fmt::format("({:.4g} m) must be smaller than extent, cap_height, root_depth and the span "
                    "({:.4g} m)",
                    s.first_cell, limit));
}

// Distances from one wall, `first` growing by `growth` until the cells reach `uniform`, then
// uniform, to the middle of a span of `length` (the other half is the mirror image).
std::vector<double> two_sided_span(double length, double first, double growth, int cells) {
  const double uniform = length / cells;
  std::vector<double> half{0.0};
  for (double h = first; h < uniform && half.back() + h < 0.5 * length; h *= growth)
    half.push_back(half.back() + h);
  const double rest = 0.5 * length - half.back();
  const int n_rest = std::max(1, static_cast<int>(std::ceil(rest / uniform - 1e-9)));
  const double from = half.back();
  for (int k = 1; k <= n_rest; ++k) half.push_back(from + rest * k / n_rest);
  std::vector<double> all = half;
  for (auto it = half.rbegin() + 1; it != half.rend(); ++it) all.push_back(length - *it);
  return all;
}

// Levels along the post, as offsets: depths below the root face (m), fractions of the span
// from the root face to the tip (0 to 1), above the tip (m). Each column of the grid places them
// over its own root point, since the root face follows the hull.
struct Levels {
  std::vector<double> below;  // root_depth .. 0 (descending depths below the root face)
  std::vector<double> span;   // 0 .. 1
  std::vector<double> above;  // 0 .. cap_height
  [[nodiscard]] int root() const { return static_cast<int>(below.size()) - 1; }
  [[nodiscard]] int tip() const { return root() + static_cast<int>(span.size()) - 1; }
  [[nodiscard]] int last() const { return tip() + static_cast<int>(above.size()) - 1; }
};

// Depths below the root face: wall cells from first_cell, growing to gap / gap_cells, uniform
// across the gap and half a gap beyond (the hull lies one gap down under the chord line at zero
// deflection, lower beside it, and 0.8 gap down at 35 deg), then growing to root_depth. The hull
// grid's fringe round its cells inside the fin reaches two of its layers down from the root face,
// and this grid's fringe two levels up from the hull; fine uniform levels keep both bands thin so
// that each finds active donors in the other grid's part of the gap.
std::vector<double> depths_below_root(const FinGridSpec& s, double gap) {
  return banded_nodes(s.root_depth, s.first_cell, s.growth, gap / s.gap_cells, 1.5 * gap);
}

Levels span_levels(const geometry::FinGeometry& fin, const FinGridSpec& s, double longest) {
  Levels l;
  const auto down = depths_below_root(s, fin.set().root_gap);
  l.below.assign(down.rbegin(), down.rend());
  // Graded on the longest column (the trailing edge's) so that no column's wall cells exceed
  // first_cell. (Stretching span_cells cells from a y+ first cell alone would leave cells of
  // several centimetres mid-span.)
  for (double d : two_sided_span(longest, s.first_cell, s.growth, s.span_cells))
    l.span.push_back(d / longest);
  l.above = s.cap_cells > 0 ? stretched_nodes(0, s.cap_height, s.first_cell, s.cap_cells)
                            : grown_nodes(0, s.cap_height, s.first_cell, s.growth);
  return l;
}
}  // namespace

Grid fin_grid(const geometry::FinGeometry& fin, const FinGridSpec& s) {
  check_spec(fin, s);
  const auto& sec = fin.set().section;
  const SectionLoop loop = section_loop(sec, s.chordwise_cells, s.trailing_edge_fan);
  const auto dist = s.normal_cells > 0 ? stretched_nodes(0, s.extent, s.first_cell, s.normal_cells)
                                       : grown_nodes(0, s.extent, s.first_cell, s.growth);
  const int np = loop.size(), nj = static_cast<int>(dist.size()) - 1;
  std::vector<double> root(static_cast<std::size_t>(np));
  for (int p = 0; p < np; ++p)
    root[static_cast<std::size_t>(p)] = fin.root_rho(loop.x[static_cast<std::size_t>(p)]);
  const double tip = fin.set().tip_radius;
  const Levels levels = span_levels(fin, s, tip - *std::min_element(root.begin(), root.end()));
  const int k_root = levels.root(), k_tip = levels.tip(), nk = levels.last();
  // Wall point of line p at level k: the root face's point lowered, a point of the fin, or the
  // tip's point lifted (the columns below the root and above the tip are prisms).
  const auto wall_point = [&](int p, int k) -> Eigen::Vector3d {
    const auto pu = static_cast<std::size_t>(p);
    const auto on_fin = [&](double rho) { return fin.point(rho, loop.x[pu], loop.side[pu], 0.0); };
    if (k <= k_root)
      return on_fin(root[pu]) - levels.below[static_cast<std::size_t>(k)] * fin.span_axis();
    if (k <= k_tip)
      return on_fin(root[pu] +
                    levels.span[static_cast<std::size_t>(k - k_root)] * (tip - root[pu]));
    return on_fin(tip) + levels.above[static_cast<std::size_t>(k - k_tip)] * fin.span_axis();
  };

  CellAssembler a;
  std::vector<std::pair<int, int>> tag;  // (j, k) of every point, for the patch classifier
  std::vector<int> index;                // point of line p, layer j, level k
  for (int k = 0; k <= nk; ++k) {
    for (int j = 0; j <= nj; ++j) {
      for (int p = 0; p < np; ++p) {
        const auto pu = static_cast<std::size_t>(p);
        if (j == 0 && loop.wall[pu] != p) {  // a fan line: its wall point exists already
          index.push_back(index[index.size() - pu + static_cast<std::size_t>(loop.wall[pu])]);
          continue;
        }
        const Vec2& d = loop.dir[pu];
        const Eigen::Vector3d out = d.x() * fin.chord_axis() + d.y() * fin.normal_axis();
        index.push_back(a.add_point(wall_point(p, k) + dist[static_cast<std::size_t>(j)] * out));
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
  for (int k = 0; k < nk; ++k) {
    if (k >= k_root && k < k_tip) continue;  // the fin itself
    for (int m = 0; m < loop.m; ++m) a.add_hex(column_hex(m, k));
  }

  const auto& name = fin.name();
  return a.build(
      name, {{name, PatchType::wall}, {name + "_overset", PatchType::overset}},
      [&](std::span<const int> f) {
        const auto all = [&](auto pred) {
          return std::all_of(f.begin(), f.end(),
                             [&](int q) { return pred(tag[static_cast<std::size_t>(q)]); });
        };
        if (all([&](auto t) { return t.first == 0 && t.second >= k_root && t.second <= k_tip; }))
          return 0;
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
