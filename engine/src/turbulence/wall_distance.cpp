// SPDX-License-Identifier: GPL-3.0-or-later
// Wall distance: the algorithm is stated in auvloop/engine/turbulence/wall_distance.hpp.
#include "auvloop/engine/turbulence/wall_distance.hpp"

#include <stdexcept>
#include <string>

#include "../fv/parallel.hpp"

namespace auvloop::engine::turbulence {

geometry::TriangleDistance wall_surface(std::span<const mesher::Grid* const> grids) {
  std::vector<geometry::Triangle> triangles;
  std::string names;
  for (const mesher::Grid* g : grids) {
    const auto t = mesher::wall_triangles(*g);
    triangles.insert(triangles.end(), t.begin(), t.end());
    names += (names.empty() ? "'" : ", '") + g->name + "'";
  }
  if (triangles.empty())
    throw std::invalid_argument("wall distance: no wall patch face in the grids " + names);
  return geometry::TriangleDistance(triangles);
}

std::vector<double> wall_distance(const fv::Mesh& mesh, const geometry::TriangleDistance& walls) {
  const Eigen::Isometry3d& placement = mesh.source_grid().placement;
  std::vector<double> d(static_cast<std::size_t>(mesh.cells()));
  fv::parallel_for(
      mesh.cells(),
      [&](int c) { d[static_cast<std::size_t>(c)] = walls.distance(placement * mesh.centre(c)); },
      64);
  return d;
}

}  // namespace auvloop::engine::turbulence
