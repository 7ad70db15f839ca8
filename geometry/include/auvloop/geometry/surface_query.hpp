// SPDX-License-Identifier: GPL-3.0-or-later
// Point and ray queries against a closed surface through a CGAL AABB tree.
// Construction builds the tree and its distance-query accelerator up front, so every query is
// const and may be called from several threads at once.
#pragma once

#include <memory>
#include <optional>

#include <Eigen/Core>

#include "auvloop/geometry/surface.hpp"

namespace auvloop::geometry {

struct RayHit {
  double distance = 0;     // m along the unit ray direction
  Eigen::Vector3d point;   // m, body frame
  Eigen::Vector3d normal;  // unit, outward normal of the face hit
};

class SurfaceQuery {
 public:
  // The surface must be closed; throws GeometryError otherwise. The mesh is copied.
  explicit SurfaceQuery(const SurfaceMesh& closed_surface);
  SurfaceQuery(SurfaceQuery&&) noexcept;
  SurfaceQuery& operator=(SurfaceQuery&&) noexcept;
  ~SurfaceQuery();

  // Points on the surface count as inside.
  [[nodiscard]] bool inside(const Eigen::Vector3d& p) const;
  // Euclidean distance to the surface, negative inside (m).
  [[nodiscard]] double signed_distance(const Eigen::Vector3d& p) const;
  [[nodiscard]] Eigen::Vector3d closest_point(const Eigen::Vector3d& p) const;
  // First intersection of the ray origin + t * direction, t > 0.
  [[nodiscard]] std::optional<RayHit> first_hit(const Eigen::Vector3d& origin,
                                                const Eigen::Vector3d& direction) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace auvloop::geometry
