// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/triangle_distance.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <vector>

#include "auvloop/geometry/error.hpp"

namespace auvloop::geometry {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Cgal_triangle = Kernel::Triangle_3;
using Iterator = std::vector<Cgal_triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_cgal(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}
}  // namespace

struct TriangleDistance::Impl {
  std::vector<Cgal_triangle> triangles;
  Tree tree;
};

TriangleDistance::TriangleDistance(std::span<const Triangle> triangles)
    : impl_(std::make_unique<Impl>()) {
  auto& kept = impl_->triangles;
  kept.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    for (const auto& p : t)
      if (!p.allFinite()) throw GeometryError("wall distance: a triangle has a non-finite point");
    const Cgal_triangle c(to_cgal(t[0]), to_cgal(t[1]), to_cgal(t[2]));
    if (!c.is_degenerate()) kept.push_back(c);
  }
  if (kept.empty()) throw GeometryError("wall distance: no (non-degenerate) wall triangles");
  // The tree holds iterators into `kept`, which does not change from here on.
  impl_->tree.insert(kept.cbegin(), kept.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

TriangleDistance::TriangleDistance(TriangleDistance&&) noexcept = default;
TriangleDistance& TriangleDistance::operator=(TriangleDistance&&) noexcept = default;
TriangleDistance::~TriangleDistance() = default;

double TriangleDistance::distance(const Eigen::Vector3d& p) const {
  return std::sqrt(impl_->tree.squared_distance(to_cgal(p)));
}

Eigen::Vector3d TriangleDistance::closest_point(const Eigen::Vector3d& p) const {
  const Point c = impl_->tree.closest_point(to_cgal(p));
  return {c.x(), c.y(), c.z()};
}

int TriangleDistance::triangles() const {
  return static_cast<int>(impl_->triangles.size());
}

}  // namespace auvloop::geometry
