// SPDX-License-Identifier: GPL-3.0-or-later
// The name of a surface (geometry::SurfaceMesh) without CGAL's headers: for interfaces that pass
// surfaces by pointer or reference. Parsing CGAL's kernel costs about 6 s of compile time per
// translation unit, so headers below the mesher's and the engine's public ones include this and
// leave auvloop/geometry/surface.hpp (which checks that the two names agree) to the sources that
// build or query surfaces.
#pragma once

#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>

namespace CGAL {
class Epick;  // Exact_predicates_inexact_constructions_kernel
template <class R>
class Point_3;
}  // namespace CGAL

namespace auvloop::geometry {
using SurfaceMesh = CGAL::Surface_mesh<CGAL::Point_3<CGAL::Epick>>;
}  // namespace auvloop::geometry
