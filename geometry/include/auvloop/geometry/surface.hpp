// SPDX-License-Identifier: GPL-3.0-or-later
// Triangulated, watertight, outward-oriented surfaces of the hull and fins (CGAL Surface_mesh),
// in the body frame (origin at CB, x forward, y starboard, z down; metres).
#pragma once

#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <Eigen/Core>

#include "auvloop/geometry/fin.hpp"
#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/surface_fwd.hpp"
#include "auvloop/geometry/vehicle.hpp"

namespace auvloop::geometry {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
static_assert(std::is_same_v<SurfaceMesh, CGAL::Surface_mesh<Point3>>,
              "surface_fwd.hpp names another type than CGAL's kernel gives");

struct SurfaceResolution {
  // Target edge length (m). Counts along every direction scale with 1 / edge_length, so halving it
  // doubles the resolution everywhere (the convergence test relies on that).
  double edge_length = 0.005;
};

struct SurfacePart {
  std::string name;  // "hull" or the fin's name
  SurfaceMesh mesh;
};

SurfaceMesh hull_surface(const MyringProfile& profile, double cb_station, SurfaceResolution res);
// A closed circular cylinder along z through (cx, cy), z from z0 to z1 > z0: the solid of a 2D
// body (a cylinder in a one-cell-thick grid), its side a prism of `segments` >= 3 faces whose
// vertices lie on the circle (the chord lies inside it by radius (1 - cos(pi / segments))).
// Throws GeometryError on a non-positive radius or length or too few segments.
SurfaceMesh cylinder_surface(double cx, double cy, double radius, double z0, double z1,
                             int segments);
// A closed prism along z: the polygon (x, y; counter-clockwise, star-shaped about `centre`,
// whose fan closes the ends) from z0 to z1 > z0: the solid of a 2D body (a foil section in a
// one-cell-thick grid). Throws GeometryError on fewer than 3 points, z1 <= z0 or a clockwise
// polygon.
SurfaceMesh prism_surface(std::span<const Eigen::Vector2d> polygon, const Eigen::Vector2d& centre,
                          double z0, double z1, const std::string& name);
SurfaceMesh fin_surface(const FinGeometry& fin, double deflection, SurfaceResolution res);

// Hull followed by every fin (file order), each a closed surface; fins deflected by
// `fin_deflections` (rad, one per fin, or empty for all zero). Throws GeometryError when a
// deflection exceeds the fin set's max_deflection or a fin root would leave the hull.
std::vector<SurfacePart> vehicle_parts(const Vehicle& vehicle,
                                       std::span<const double> fin_deflections,
                                       SurfaceResolution res);
// The boolean union of closed parts: one closed, manifold, outward-oriented surface (CGAL
// corefinement). Throws GeometryError if CGAL cannot produce it.
SurfaceMesh merge_parts(std::span<const SurfacePart> parts);

struct SurfaceMeasures {
  std::size_t vertices = 0;
  std::size_t faces = 0;
  double area = 0;    // m^2
  double volume = 0;  // m^3 (enclosed; meaningful for closed surfaces)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // volume centroid, body frame
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
};
SurfaceMeasures measure(const SurfaceMesh& mesh);

// Topological and geometric soundness of a surface; every field false means "no problem found".
struct SurfaceDefects {
  std::size_t boundary_edges = 0;     // open surface
  std::size_t non_manifold = 0;       // edges used by more than two faces, pinched vertices
  std::size_t misoriented_edges = 0;  // an edge traversed twice in the same direction
  std::size_t degenerate_faces = 0;   // zero area
  bool inward = false;                // consistently oriented, but normals point inside
  bool self_intersecting = false;
  [[nodiscard]] bool ok() const;
  [[nodiscard]] std::string describe() const;  // one line per defect
};
SurfaceDefects inspect(const SurfaceMesh& mesh);

}  // namespace auvloop::geometry
