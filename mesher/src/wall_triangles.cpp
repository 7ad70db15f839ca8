// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/wall_triangles.hpp"

namespace auvloop::mesher {

std::vector<geometry::Triangle> wall_triangles(const Grid& g, const Eigen::Isometry3d& to) {
  return wall_triangles(g, to, 0, g.cells);
}

std::vector<geometry::Triangle> wall_triangles(const Grid& g, const Eigen::Isometry3d& to,
                                               int first_cell, int end_cell) {
  std::vector<geometry::Triangle> out;
  const auto point = [&](int f, int k) -> Eigen::Vector3d {
    return to * g.points[static_cast<std::size_t>(g.face_point(f, k))];
  };
  for (const Patch& patch : g.patches) {
    if (patch.type != PatchType::wall) continue;
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const int owner = g.owner[static_cast<std::size_t>(f)];
      if (owner < first_cell || owner >= end_cell) continue;
      const int n = g.face_size(f);
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int k = 0; k < n; ++k) mean += g.points[static_cast<std::size_t>(g.face_point(f, k))];
      const Eigen::Vector3d centre = to * Eigen::Vector3d(mean / n);
      for (int k = 0; k < n; ++k) out.push_back({point(f, k), point(f, (k + 1) % n), centre});
    }
  }
  return out;
}

}  // namespace auvloop::mesher
