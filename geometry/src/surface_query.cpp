// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/surface_query.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include "auvloop/geometry/error.hpp"

namespace auvloop::geometry {
namespace {
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Traits = CGAL::AABB_traits<Kernel, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;
using SideOf = CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>;

Point3 to_cgal(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}
Eigen::Vector3d to_eigen(const Point3& p) {
  return {p.x(), p.y(), p.z()};
}
}  // namespace

struct SurfaceQuery::Impl {
  explicit Impl(const SurfaceMesh& m) : mesh(m), tree(faces(mesh).first, faces(mesh).second, mesh) {
    tree.build();
    // Built now rather than lazily on the first query, so that queries never mutate the tree and
    // can run concurrently.
    tree.accelerate_distance_queries();
    side = std::make_unique<SideOf>(tree);
  }
  SurfaceMesh mesh;
  Tree tree;
  std::unique_ptr<SideOf> side;
};

SurfaceQuery::SurfaceQuery(const SurfaceMesh& closed_surface) {
  if (!CGAL::is_closed(closed_surface) || closed_surface.number_of_faces() == 0) {
    throw GeometryError("inside/outside queries need a closed surface");
  }
  impl_ = std::make_unique<Impl>(closed_surface);
}

SurfaceQuery::SurfaceQuery(SurfaceQuery&&) noexcept = default;
SurfaceQuery& SurfaceQuery::operator=(SurfaceQuery&&) noexcept = default;
SurfaceQuery::~SurfaceQuery() = default;

bool SurfaceQuery::inside(const Eigen::Vector3d& p) const {
  return (*impl_->side)(to_cgal(p)) != CGAL::ON_UNBOUNDED_SIDE;
}

double SurfaceQuery::signed_distance(const Eigen::Vector3d& p) const {
  const double d = std::sqrt(impl_->tree.squared_distance(to_cgal(p)));
  return inside(p) ? -d : d;
}

Eigen::Vector3d SurfaceQuery::closest_point(const Eigen::Vector3d& p) const {
  return to_eigen(impl_->tree.closest_point(to_cgal(p)));
}

std::optional<RayHit> SurfaceQuery::first_hit(const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d u = direction.normalized();
  const Kernel::Ray_3 ray(to_cgal(origin), Kernel::Vector_3(u.x(), u.y(), u.z()));
  const auto hit = impl_->tree.first_intersection(ray);
  if (!hit) return std::nullopt;
  const Point3* p = boost::get<Point3>(&hit->first);
  if (p == nullptr) return std::nullopt;  // the ray runs inside a face: no single crossing point
  const auto n = CGAL::Polygon_mesh_processing::compute_face_normal(hit->second, impl_->mesh);
  RayHit out;
  out.point = to_eigen(*p);
  out.distance = (out.point - origin).norm();
  out.normal = Eigen::Vector3d(n.x(), n.y(), n.z());
  return out;
}

}  // namespace auvloop::geometry
