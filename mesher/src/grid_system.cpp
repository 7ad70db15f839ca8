// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/grid_system.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/fin_grid.hpp"
#include "auvloop/mesher/generators.hpp"
#include "auvloop/mesher/hull_grid.hpp"

namespace auvloop::mesher {
namespace {
bool equally_spaced(const std::vector<geometry::FinPlacement>& fins) {
  std::vector<double> roll;
  for (const auto& f : fins) roll.push_back(f.roll);
  std::sort(roll.begin(), roll.end());
  const double step = 2 * std::numbers::pi / static_cast<double>(roll.size());
  for (std::size_t i = 1; i < roll.size(); ++i)
    if (std::abs(roll[i] - roll[i - 1] - step) > 1e-9) return false;
  return true;
}
}  // namespace

std::vector<const Grid*> GridSystem::grids() const {
  std::vector<const Grid*> all{&hull};
  for (const auto& f : fins) all.push_back(&f);
  all.push_back(&background);
  return all;
}

long long GridSystem::total_cells() const {
  long long n = 0;
  for (const Grid* g : grids()) n += g->cells;
  return n;
}

GridSystem build_grid_system(const geometry::Vehicle& v, const MeshSettings& s) {
  check_mesh_settings(s, v);
  GridSystem sys;
  const geometry::MyringProfile profile(v.hull);
  HullGridSpec hull = s.hull;
  if (!v.fin_set.fins.empty() && equally_spaced(v.fin_set.fins)) {
    hull.fins = static_cast<int>(v.fin_set.fins.size());
    // Roll 0 points up (-z): polar angle -90 deg from +y towards +z.
    hull.fin_angle = v.fin_set.fins.front().roll - 0.5 * std::numbers::pi;
  }
  if (!v.fin_set.fins.empty() && hull.fin_zone_end <= hull.fin_zone_begin) {
    const auto& f = v.fin_set;  // the zone spans the fins' planform, root to tip
    const double tip_le = f.root_le_station + f.span * std::tan(f.sweep);
    hull.fin_zone_begin = std::min(f.root_le_station, tip_le);
    hull.fin_zone_end = std::max(f.root_le_station + f.root_chord, tip_le + f.tip_chord);
  }

  sys.hull = hull_grid(profile, v.mass.cb_station, hull);
  for (const auto& placement : v.fin_set.fins) {
    sys.fin_geometry.emplace_back(v.fin_set, placement, profile, v.mass.cb_station);
    sys.fins.push_back(fin_grid(sys.fin_geometry.back(), s.fin));
  }
  sys.background = background_box(s.background);
  set_fin_deflections(sys, s.fin_deflections.empty() ? std::vector<double>(sys.fins.size(), 0.0)
                                                     : s.fin_deflections);
  return sys;
}

void set_fin_deflections(GridSystem& sys, const std::vector<double>& deflections) {
  if (deflections.size() != sys.fins.size())
    throw std::invalid_argument("set_fin_deflections: one deflection per fin");
  sys.fin_deflections = deflections;
  for (std::size_t i = 0; i < sys.fins.size(); ++i)
    sys.fins[i].placement = fin_placement(sys.fin_geometry[i], deflections[i]);
}

}  // namespace auvloop::mesher
