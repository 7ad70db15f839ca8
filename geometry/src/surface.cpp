// SPDX-License-Identifier: GPL-3.0-or-later
// Triangulation of the hull and fins, boolean union of the parts, and surface measures.
#include "auvloop/geometry/surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <fmt/format.h>

#include "auvloop/geometry/error.hpp"

namespace auvloop::geometry {
namespace PMP = CGAL::Polygon_mesh_processing;
namespace {

constexpr double kPi = std::numbers::pi;
using Loop = std::vector<Eigen::Vector3d>;

// Indexed triangle list, converted to a Surface_mesh once complete.
class TriangleBuilder {
 public:
  int add(const Eigen::Vector3d& p) {
    points_.push_back(p);
    return static_cast<int>(points_.size()) - 1;
  }
  void triangle(int a, int b, int c) { triangles_.push_back({a, b, c}); }
  // Adds (a, b, c) wound so that its normal points along `outward`; used on planar caps, where
  // every triangle is non-degenerate and the outward direction is known.
  void oriented(int a, int b, int c, const Eigen::Vector3d& outward) {
    const Eigen::Vector3d n =
        (points_[static_cast<std::size_t>(b)] - points_[static_cast<std::size_t>(a)])
            .cross(points_[static_cast<std::size_t>(c)] - points_[static_cast<std::size_t>(a)]);
    if (n.dot(outward) >= 0) {
      triangle(a, b, c);
    } else {
      triangle(a, c, b);
    }
  }
  [[nodiscard]] const Eigen::Vector3d& point(int i) const {
    return points_[static_cast<std::size_t>(i)];
  }

  SurfaceMesh mesh(const std::string& what) const {
    SurfaceMesh m;
    std::vector<SurfaceMesh::Vertex_index> v;
    v.reserve(points_.size());
    for (const auto& p : points_) v.push_back(m.add_vertex(Point3(p.x(), p.y(), p.z())));
    for (const auto& t : triangles_) {
      const auto f =
          m.add_face(v[static_cast<std::size_t>(t[0])], v[static_cast<std::size_t>(t[1])],
                     v[static_cast<std::size_t>(t[2])]);
      if (f == SurfaceMesh::null_face()) {
        throw GeometryError(
            fmt::format("internal error: non-manifold triangle in the {} surface", what));
      }
    }
    return m;
  }

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<int, 3>> triangles_;
};

Eigen::Vector3d newell_area(const Loop& loop) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) a += loop[i].cross(loop[(i + 1) % loop.size()]);
  return 0.5 * a;
}

Eigen::Vector3d centre(const Loop& loop) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : loop) c += p;
  return c / static_cast<double>(loop.size());
}

// Side surface through closed loops of equal size. With a = (k, j), b = (k, j+1), c = (k+1, j+1),
// d = (k+1, j) the triangles (a, d, c), (a, c, b) have normal t_progression x t_loop, which points
// outward exactly when the loop's area vector points against the progression; otherwise the
// winding is reversed. Returns the vertex ids of each loop.
std::vector<std::vector<int>> loft(TriangleBuilder& tb, const std::vector<Loop>& loops) {
  std::vector<std::vector<int>> ids;
  for (const auto& loop : loops) {
    std::vector<int> row;
    for (const auto& p : loop) row.push_back(tb.add(p));
    ids.push_back(std::move(row));
  }
  const Eigen::Vector3d progression = centre(loops.back()) - centre(loops.front());
  const bool reverse = newell_area(loops.front()).dot(progression) > 0;
  const std::size_t n = loops.front().size();
  for (std::size_t k = 0; k + 1 < loops.size(); ++k) {
    for (std::size_t j = 0; j < n; ++j) {
      const int a = ids[k][j], b = ids[k][(j + 1) % n], c = ids[k + 1][(j + 1) % n],
                d = ids[k + 1][j];
      if (!reverse) {
        tb.triangle(a, d, c);
        tb.triangle(a, c, b);
      } else {
        tb.triangle(a, c, d);
        tb.triangle(a, b, c);
      }
    }
  }
  return ids;
}

// Hull rings put their vertices half a step off the cardinal angles: a cruciform fin's mid-plane
// then never contains a hull vertex, which would make the union's intersection curve run through
// vertices and edges and leave degenerate triangles behind.
constexpr double kRingOffset = 0.5;

// Triangulates the annulus between two concentric rings (vertex j at angle 2 pi (j + offset) / n),
// advancing along whichever ring has the nearer next vertex (a "zipper").
void zipper(TriangleBuilder& tb, const std::vector<int>& inner, const std::vector<int>& outer,
            const Eigen::Vector3d& outward) {
  const std::size_t na = inner.size(), nb = outer.size();
  std::size_t i = 0, j = 0;
  while (i < na || j < nb) {
    const double next_a = (static_cast<double>(i + 1) + kRingOffset) / static_cast<double>(na);
    const double next_b = (static_cast<double>(j + 1) + kRingOffset) / static_cast<double>(nb);
    if (j < nb && (i >= na || next_b <= next_a)) {
      tb.oriented(inner[i % na], outer[j], outer[(j + 1) % nb], outward);
      ++j;
    } else {
      tb.oriented(inner[i], outer[j % nb], inner[(i + 1) % na], outward);
      ++i;
    }
  }
}

Loop ring(double x, double radius, std::size_t count) {
  Loop loop;
  for (std::size_t j = 0; j < count; ++j) {
    const double th = 2 * kPi * (static_cast<double>(j) + kRingOffset) / static_cast<double>(count);
    loop.emplace_back(x, radius * std::sin(th), -radius * std::cos(th));
  }
  return loop;
}

// Flat circular end face bounded by `rim` (a ring of radius `radius` at body x = `x`), filled with
// concentric rings about edge_length apart whose vertex counts shrink with their radius.
void disk_cap(TriangleBuilder& tb, const std::vector<int>& rim, double x, double radius,
              double edge_length, const Eigen::Vector3d& outward) {
  const auto rings = static_cast<std::size_t>(std::max(1.0, std::round(radius / edge_length)));
  std::vector<int> outer = rim;
  for (std::size_t i = rings - 1; i >= 1; --i) {
    const double fraction = static_cast<double>(i) / static_cast<double>(rings);
    const auto count = std::max<std::size_t>(
        6, static_cast<std::size_t>(std::lround(static_cast<double>(rim.size()) * fraction)));
    std::vector<int> inner;
    for (const auto& p : ring(x, radius * fraction, count)) inner.push_back(tb.add(p));
    zipper(tb, inner, outer, outward);
    outer = std::move(inner);
  }
  const int centre_id = tb.add(Eigen::Vector3d(x, 0, 0));
  for (std::size_t j = 0; j < outer.size(); ++j) {
    tb.oriented(centre_id, outer[j], outer[(j + 1) % outer.size()], outward);
  }
}

// Stations equally spaced in arc length along the meridian curve (station, r(station)), so that the
// steep nose gets as many stations per metre of surface as the parallel body.
std::vector<double> meridian_stations(const MyringProfile& profile, double edge_length) {
  constexpr int samples = 20000;
  std::vector<double> x(samples + 1), s(samples + 1, 0.0);
  for (int i = 0; i <= samples; ++i)
    x[static_cast<std::size_t>(i)] = profile.length() * i / samples;
  for (std::size_t i = 1; i < x.size(); ++i) {
    s[i] = s[i - 1] + std::hypot(x[i] - x[i - 1], profile.radius(x[i]) - profile.radius(x[i - 1]));
  }
  const auto n = static_cast<std::size_t>(std::max(16.0, std::ceil(s.back() / edge_length)));
  std::vector<double> stations;
  std::size_t k = 0;
  for (std::size_t i = 0; i <= n; ++i) {
    const double target = s.back() * static_cast<double>(i) / static_cast<double>(n);
    while (k + 1 < s.size() - 1 && s[k + 1] < target) ++k;
    const double w = std::clamp((target - s[k]) / (s[k + 1] - s[k]), 0.0, 1.0);
    stations.push_back(x[k] + w * (x[k + 1] - x[k]));
  }
  stations.front() = 0.0;
  stations.back() = profile.length();
  return stations;
}

// Closes an end of the loft: a flat disk for a truncated end, an apex fan for a pointed one.
void close_hull_end(TriangleBuilder& tb, const std::vector<int>& rim, double x, double radius,
                    double edge_length, const Eigen::Vector3d& outward, double scale) {
  if (radius > 1e-9 * scale) {
    disk_cap(tb, rim, x, radius, edge_length, outward);
    return;
  }
  // A pointed end: the rim collapsed to the axis, so fan its vertices to one apex instead.
  const int apex = tb.add(Eigen::Vector3d(x, 0, 0));
  for (std::size_t j = 0; j < rim.size(); ++j) {
    tb.oriented(apex, rim[j], rim[(j + 1) % rim.size()], outward);
  }
}

}  // namespace

SurfaceMesh prism_surface(std::span<const Eigen::Vector2d> polygon, const Eigen::Vector2d& centre,
                          double z0, double z1, const std::string& name) {
  double area = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const auto& a = polygon[k];
    const auto& b = polygon[(k + 1) % polygon.size()];
    area += 0.5 * (a.x() * b.y() - b.x() * a.y());
  }
  if (polygon.size() < 3 || !(z1 > z0) || !(area > 0))
    throw GeometryError(fmt::format(
        "prism_surface {}: need at least 3 points counter-clockwise and z1 > z0, got {} points "
        "(area {:.3g}), z {} .. {}",
        name, polygon.size(), area, z0, z1));
  TriangleBuilder b;
  std::vector<int> lo, hi;
  for (const auto& q : polygon) {
    lo.push_back(b.add({q.x(), q.y(), z0}));
    hi.push_back(b.add({q.x(), q.y(), z1}));
  }
  const int c0 = b.add({centre.x(), centre.y(), z0}), c1 = b.add({centre.x(), centre.y(), z1});
  for (std::size_t k = 0; k < lo.size(); ++k) {
    const std::size_t n = (k + 1) % lo.size();
    b.triangle(lo[k], lo[n], hi[n]);  // counter-clockwise seen from outside: outward normals
    b.triangle(lo[k], hi[n], hi[k]);
    b.triangle(c0, lo[n], lo[k]);
    b.triangle(c1, hi[k], hi[n]);
  }
  return b.mesh(name);
}

SurfaceMesh cylinder_surface(double cx, double cy, double radius, double z0, double z1,
                             int segments) {
  if (!(radius > 0) || !(z1 > z0) || segments < 3)
    throw GeometryError(fmt::format(
        "cylinder_surface: need radius > 0, z1 > z0 and at least 3 segments, got {}, {} .. {}, {}",
        radius, z0, z1, segments));
  std::vector<Eigen::Vector2d> circle;
  for (int k = 0; k < segments; ++k) {
    const double a = 2 * kPi * k / segments;
    circle.emplace_back(cx + radius * std::cos(a), cy + radius * std::sin(a));
  }
  return prism_surface(circle, {cx, cy}, z0, z1, "cylinder");
}

SurfaceMesh hull_surface(const MyringProfile& profile, double cb_station, SurfaceResolution res) {
  const double h = res.edge_length;
  if (!(h > 0)) throw GeometryError("surface resolution: edge length must be positive");
  const double d = 2 * profile.max_radius();
  const auto n_theta = static_cast<std::size_t>(
      4 * std::max(4.0, std::ceil(2 * kPi * profile.max_radius() / h / 4)));
  auto stations = meridian_stations(profile, h);
  const double eps = 1e-9 * d;
  // Pointed ends have no ring: drop their station and close with an apex instead.
  const bool pointed_nose = profile.radius(0) <= eps;
  const bool pointed_tail = profile.radius(profile.length()) <= eps;
  std::vector<Loop> loops;
  for (std::size_t k = pointed_nose ? 1 : 0; k < stations.size() - (pointed_tail ? 1 : 0); ++k) {
    loops.push_back(ring(cb_station - stations[k], profile.radius(stations[k]), n_theta));
  }
  TriangleBuilder tb;
  const auto ids = loft(tb, loops);
  close_hull_end(tb, ids.front(), cb_station, profile.radius(0), h, Eigen::Vector3d::UnitX(), d);
  close_hull_end(tb, ids.back(), cb_station - profile.length(), profile.radius(profile.length()), h,
                 -Eigen::Vector3d::UnitX(), d);
  return tb.mesh("hull");
}

SurfaceMesh fin_surface(const FinGeometry& fin, double deflection, SurfaceResolution res) {
  const double h = res.edge_length;
  if (!(h > 0)) throw GeometryError("surface resolution: edge length must be positive");
  const auto& set = fin.set();
  const bool sharp = set.section.sharp_trailing_edge;
  // Cosine spacing along the chord clusters points at the leading edge (radius 1.1 t^2 c) and the
  // trailing edge, where curvature and flow gradients are largest.
  const auto m = static_cast<std::size_t>(std::max(10.0, std::ceil(1.5 * set.root_chord / h)));
  std::vector<double> xc(m + 1);
  for (std::size_t i = 0; i <= m; ++i) {
    xc[i] = 0.5 * (1 - std::cos(kPi * static_cast<double>(i) / static_cast<double>(m)));
  }
  // Span stations between the root face and the tip: per chord point, evenly from its root rho.
  std::vector<double> root(m + 1);
  for (std::size_t i = 0; i <= m; ++i) root[i] = fin.root_rho(xc[i]);
  const double tip = set.tip_radius, longest = tip - *std::min_element(root.begin(), root.end());
  const auto n_span = static_cast<std::size_t>(std::max(2.0, std::ceil(longest / h)));
  // Loop: leading edge, upper surface aft, trailing edge (one point if sharp), lower surface
  // forward.
  const std::size_t last_upper = sharp ? m - 1 : m;
  std::vector<Loop> loops;
  for (std::size_t k = 0; k <= n_span; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(n_span);
    const auto at = [&](std::size_t i, int side) {
      return fin.point(root[i] + t * (tip - root[i]), xc[i], side, deflection);
    };
    Loop loop{at(0, 1)};
    for (std::size_t i = 1; i <= last_upper; ++i) loop.push_back(at(i, 1));
    if (sharp) loop.push_back(at(m, 1));
    for (std::size_t i = last_upper; i >= 1; --i) loop.push_back(at(i, -1));
    loops.push_back(std::move(loop));
  }
  TriangleBuilder tb;
  const auto ids = loft(tb, loops);
  // Root face and flat tip: strips between matching upper and lower points.
  const std::size_t n = loops.front().size();
  auto upper = [&](const std::vector<int>& row, std::size_t i) { return row[i]; };
  auto lower = [&](const std::vector<int>& row, std::size_t i) { return row[n - i]; };
  const Eigen::Vector3d e = fin.span_axis();
  for (const auto& [row, outward] :
       {std::pair{ids.front(), Eigen::Vector3d(-e)}, std::pair{ids.back(), e}}) {
    tb.oriented(row[0], upper(row, 1), lower(row, 1), outward);
    for (std::size_t i = 1; i < last_upper; ++i) {
      tb.oriented(upper(row, i), upper(row, i + 1), lower(row, i + 1), outward);
      tb.oriented(upper(row, i), lower(row, i + 1), lower(row, i), outward);
    }
    if (sharp) {
      tb.oriented(upper(row, last_upper), row[last_upper + 1], lower(row, last_upper), outward);
    }
  }
  return tb.mesh("fin " + fin.name());
}

std::vector<SurfacePart> vehicle_parts(const Vehicle& vehicle,
                                       std::span<const double> fin_deflections,
                                       SurfaceResolution res) {
  const auto& set = vehicle.fin_set;
  if (!fin_deflections.empty() && fin_deflections.size() != set.fins.size()) {
    throw GeometryError(fmt::format("{} fin deflections given, but the vehicle has {} fins",
                                    fin_deflections.size(), set.fins.size()));
  }
  const MyringProfile profile(vehicle.hull);
  std::vector<SurfacePart> parts;
  parts.push_back({"hull", hull_surface(profile, vehicle.mass.cb_station, res)});
  for (std::size_t i = 0; i < set.fins.size(); ++i) {
    const double delta = fin_deflections.empty() ? 0.0 : fin_deflections[i];
    if (std::abs(delta) > set.max_deflection * (1 + 1e-12)) {
      throw GeometryError(
          fmt::format("fin \"{}\": deflection {:.3g} deg exceeds the vehicle's "
                      "max_deflection of {:.3g} deg",
                      set.fins[i].name, delta * 180 / kPi, set.max_deflection * 180 / kPi));
    }
    const FinGeometry fin(set, set.fins[i], profile, vehicle.mass.cb_station);
    parts.push_back({set.fins[i].name, fin_surface(fin, delta, res)});
  }
  return parts;
}

SurfaceMesh merge_parts(std::span<const SurfacePart> parts) {
  if (parts.empty()) throw GeometryError("merge_parts: no parts");
  SurfaceMesh result = parts.front().mesh;
  for (std::size_t i = 1; i < parts.size(); ++i) {
    SurfaceMesh next = parts[i].mesh;
    if (!PMP::corefine_and_compute_union(result, next, result)) {
      throw GeometryError(
          fmt::format("the union of \"{}\" with the parts before it is not a closed "
                      "manifold surface",
                      parts[i].name));
    }
  }
  // Corefinement can leave needle triangles whose vertices are collinear in double precision
  // where an intersection curve grazes existing vertices; collapse them.
  PMP::remove_degenerate_faces(result);
  result.collect_garbage();
  return result;
}

SurfaceMeasures measure(const SurfaceMesh& mesh) {
  SurfaceMeasures m;
  m.vertices = mesh.number_of_vertices();
  m.faces = mesh.number_of_faces();
  m.bbox_min.setConstant(std::numeric_limits<double>::infinity());
  m.bbox_max.setConstant(-std::numeric_limits<double>::infinity());
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    const Eigen::Vector3d q(p.x(), p.y(), p.z());
    m.bbox_min = m.bbox_min.cwiseMin(q);
    m.bbox_max = m.bbox_max.cwiseMax(q);
  }
  // Volume and centroid by the divergence theorem over tetrahedra (origin, a, b, c).
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> p;
    std::size_t k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      const auto& q = mesh.point(v);
      p[k++] = Eigen::Vector3d(q.x(), q.y(), q.z());
    }
    const double v6 = p[0].dot(p[1].cross(p[2]));
    m.volume += v6 / 6;
    moment += v6 / 24 * (p[0] + p[1] + p[2]);
    m.area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  }
  if (m.volume != 0) m.centroid = moment / m.volume;
  return m;
}

bool SurfaceDefects::ok() const {
  return boundary_edges == 0 && non_manifold == 0 && misoriented_edges == 0 &&
         degenerate_faces == 0 && !inward && !self_intersecting;
}

std::string SurfaceDefects::describe() const {
  std::vector<std::string> lines;
  if (boundary_edges > 0)
    lines.push_back(fmt::format("the surface is open: {} boundary edges", boundary_edges));
  if (non_manifold > 0)
    lines.push_back(fmt::format("the surface is not manifold: {} non-manifold edges or vertices",
                                non_manifold));
  if (misoriented_edges > 0)
    lines.push_back(fmt::format(
        "faces are inconsistently oriented: {} edges traversed twice in the same direction",
        misoriented_edges));
  if (degenerate_faces > 0)
    lines.push_back(fmt::format("{} degenerate (zero-area) faces", degenerate_faces));
  if (inward) lines.push_back("the surface is inside out: its normals point inward");
  if (self_intersecting) lines.push_back("the surface intersects itself");
  std::string s;
  for (const auto& l : lines) s += (s.empty() ? "" : "\n") + l;
  return s;
}

SurfaceDefects inspect(const SurfaceMesh& mesh) {
  SurfaceDefects d;
  for (auto h : mesh.halfedges()) {
    if (mesh.is_border(h)) ++d.boundary_edges;
  }
  for (auto v : mesh.vertices()) {
    if (PMP::is_non_manifold_vertex(v, mesh)) ++d.non_manifold;
  }
  for (auto f : mesh.faces()) {
    if (PMP::is_degenerate_triangle_face(f, mesh)) ++d.degenerate_faces;
  }
  if (d.boundary_edges == 0 && d.non_manifold == 0) {
    d.inward = !PMP::is_outward_oriented(mesh);
    d.self_intersecting = PMP::does_self_intersect(mesh);
  }
  return d;
}

}  // namespace auvloop::geometry
