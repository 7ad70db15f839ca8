// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/grid_system.hpp"

#include <stdexcept>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/fin_grid.hpp"
#include "auvloop/mesher/generators.hpp"
#include "auvloop/mesher/hull_grid.hpp"

namespace auvloop::mesher {

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
  sys.hull = hull_grid(geometry::MyringProfile(v.hull), v.mass.cb_station, s.hull);
  for (const auto& placement : v.fin_set.fins) {
    sys.fin_geometry.emplace_back(v.fin_set, placement, v.mass.cb_station);
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
