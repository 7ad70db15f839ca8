// SPDX-License-Identifier: GPL-3.0-or-later
#include "section_loop.hpp"

#include <cmath>
#include <numbers>

namespace auvloop::mesher::detail {

namespace {
Vec2 outward(const Vec2& a, const Vec2& b) {
  const Vec2 t = (b - a).normalized();
  return {-t.y(), t.x()};  // clockwise loop: outward is the left-hand normal
}

}  // namespace

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

}  // namespace auvloop::mesher::detail
