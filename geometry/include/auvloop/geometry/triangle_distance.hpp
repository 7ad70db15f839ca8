// SPDX-License-Identifier: GPL-3.0-or-later
// Distance from points to a set of triangles: any set, open or closed, of one body or several (the
// wall faces of a whole overset grid system, for the turbulence model's wall distance), through a
// CGAL AABB tree whose distance accelerator is built up front, so queries are const and may run
// on several threads at once. The distance is exact for the triangles given (up to round-off):
// to the wall as the grid discretises it, not to the smooth surface it approximates.
#pragma once

#include <array>
#include <memory>
#include <span>

#include <Eigen/Core>

namespace auvloop::geometry {

using Triangle = std::array<Eigen::Vector3d, 3>;

class TriangleDistance {
 public:
  // Throws GeometryError when `triangles` is empty or holds a non-finite point. Degenerate
  // (zero-area) triangles are skipped. The triangles are copied.
  explicit TriangleDistance(std::span<const Triangle> triangles);
  TriangleDistance(TriangleDistance&&) noexcept;
  TriangleDistance& operator=(TriangleDistance&&) noexcept;
  ~TriangleDistance();

  [[nodiscard]] double distance(const Eigen::Vector3d& p) const;  // m
  [[nodiscard]] Eigen::Vector3d closest_point(const Eigen::Vector3d& p) const;
  [[nodiscard]] int triangles() const;  // those kept (non-degenerate)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace auvloop::geometry
