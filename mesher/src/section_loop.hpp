// SPDX-License-Identifier: GPL-3.0-or-later
// The outward grid lines round a NACA section, shared by the fin grids (fin_grid.cpp) and the 2D
// foil grids (foil_grid.cpp). Internal to the mesher.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "auvloop/geometry/naca.hpp"

namespace auvloop::mesher::detail {

using Vec2 = Eigen::Vector2d;  // (chord, normal) coordinates of a unit-chord section

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

// The loop of 2 m chordwise cells with a fan of `fan` cells at a sharp trailing edge.
SectionLoop section_loop(const geometry::NacaSection& sec, int m, int fan);

}  // namespace auvloop::mesher::detail
