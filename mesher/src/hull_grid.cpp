// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/hull_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/mesher/cell_assembly.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::mesher {

namespace {
using Vec2 = Eigen::Vector2d;  // (station, radius) in the meridional half-plane

void check(bool ok, const char* setting, const std::string& why) {
  if (!ok) throw std::invalid_argument(fmt::format("hull grid: {} {}", setting, why));
}

void check_spec(const geometry::MyringProfile& profile, const HullGridSpec& s) {
  check(s.nose_face_cells >= 1, "nose_face_cells", "must be at least 1");
  check(s.tail_face_cells >= 1, "tail_face_cells", "must be at least 1");
  check(s.body_cells >= 2, "body_cells", "must be at least 2");
  check(s.circumferential >= 4 && s.circumferential % 4 == 0, "circumferential",
        fmt::format("must be a positive multiple of 4 (got {})", s.circumferential));
  check(s.normal_cells >= 0, "normal_cells", "must not be negative (0: derive from growth)");
  check(s.growth >= 1, "growth", fmt::format("must be at least 1 (got {})", s.growth));
  check(s.rim_clustering >= 1, "rim_clustering", "must be at least 1");
  check(s.rim_fan >= 1, "rim_fan", "must be at least 1");
  check(s.rim_radius >= 0, "rim_radius", "must not be negative (0: sharp rims)");
  check(s.fin_clustering >= 0 && s.fin_clustering < 1, "fin_clustering", "must be in [0, 1)");
  check(s.fins == 0 || s.circumferential % s.fins == 0, "circumferential",
        fmt::format("must be a multiple of the number of fins ({})", s.fins));
  check(s.fin_zone_share >= 0 && s.fin_zone_share < 1, "fin_zone_share", "must be in [0, 1)");
  check(s.fin_zone_ramp > 0, "fin_zone_ramp", "must be positive");
  check(s.extent > 0, "extent", "must be positive");
  check(s.first_cell > 0, "first_cell", "must be positive");
  check(s.first_cell < profile.max_radius(), "first_cell",
        fmt::format("({:.4g} m) must be smaller than the hull radius ({:.4g} m)", s.first_cell,
                    profile.max_radius()));
  check(s.first_cell < s.extent, "first_cell",
        fmt::format("({:.4g} m) must be smaller than extent ({:.4g} m)", s.first_cell, s.extent));
}

// Stations at equal steps of arc length along the curved profile, by inverting a fine table of
// the cumulative chord length (its own error, ~(step)^2 curvature, is far below any grid spacing).
class ArcLength {
 public:
  explicit ArcLength(const geometry::MyringProfile& p) {
    constexpr int kSamples = 20000;
    for (int k = 0; k <= kSamples; ++k) {
      const double s = p.length() * k / kSamples;
      const Vec2 q(s, p.radius(s));
      arc_.push_back(k == 0 ? 0.0 : arc_.back() + (q - last_).norm());
      station_.push_back(s);
      last_ = q;
    }
  }
  [[nodiscard]] double total() const { return arc_.back(); }
  [[nodiscard]] double station(double arc) const { return lookup(arc_, station_, arc); }
  [[nodiscard]] double arc(double station) const { return lookup(station_, arc_, station); }

 private:
  // Linear interpolation of `to` at `x` in the increasing table `from`.
  static double lookup(const std::vector<double>& from, const std::vector<double>& to, double x) {
    const auto it = std::upper_bound(from.begin(), from.end(), x);
    if (it == from.end()) return to.back();
    const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - from.begin()));
    const double t = (x - from[k - 1]) / (from[k] - from[k - 1]);
    return to[k - 1] + t * (to[k] - to[k - 1]);
  }

  std::vector<double> arc_, station_;
  Vec2 last_ = Vec2::Zero();
};

bool has_fin_zone(const HullGridSpec& s) {
  return s.fin_zone_end > s.fin_zone_begin;
}

// 1 over the stern zone, fading to 0 over the ramp either side (cos^2, so sizes and the
// clustering change smoothly along the hull).
double fin_zone_weight(const HullGridSpec& s, double station) {
  if (!has_fin_zone(s)) return 1;
  const double out = std::max(s.fin_zone_begin - station, station - s.fin_zone_end);
  if (out <= 0) return 1;
  if (out >= s.fin_zone_ramp) return 0;
  const double c = std::cos(0.5 * std::numbers::pi * out / s.fin_zone_ramp);
  return c * c;
}

// Cumulative distribution, sampled at `at`, of a node distribution: the fraction of its cells
// below each point (piecewise linear in the node index).
std::vector<double> node_fractions(const std::vector<double>& nodes,
                                   const std::vector<double>& at) {
  const double n = static_cast<double>(nodes.size() - 1);
  std::vector<double> f;
  std::size_t j = 1;
  for (double x : at) {
    while (j + 1 < nodes.size() && nodes[j] < x) ++j;
    const double t = (x - nodes[j - 1]) / (nodes[j] - nodes[j - 1]);
    f.push_back(std::clamp((static_cast<double>(j - 1) + t) / n, 0.0, 1.0));
  }
  return f;
}

// The same for a density proportional to the stern-zone weight along the arc.
std::vector<double> zone_fractions(const ArcLength& arc, const HullGridSpec& s,
                                   const std::vector<double>& at) {
  std::vector<double> f{0.0};
  for (std::size_t k = 1; k < at.size(); ++k)  // trapezoidal rule
    f.push_back(f.back() + 0.5 * (at[k] - at[k - 1]) *
                               (fin_zone_weight(s, arc.station(at[k - 1])) +
                                fin_zone_weight(s, arc.station(at[k]))));
  for (double& v : f) v /= f.back();
  return f;
}

// Arc-length nodes along the curved profile from arc length `begin` to `end` (the rims, or the
// fillets' tangent points): rim-clustered (by rim_clustering; with fillets, two-sided to the end
// sizes `first` and `last` when both are finer than uniform, else uniform), and with a stern zone
// a share `fin_zone_share` of them spread by the zone weight instead (the nodes of the mixture of
// the two distributions, found by inverting it on a fine table). Where the zone weight vanishes
// the mixture's end cells are the rim distribution's over 1 - share, so its ends are scaled down
// by that factor; at the tail the zone's ramp reaches the rim (weight about 0.5 on the REMUS), and
// the end cells there come out a few per cent smaller than `last` (the tests allow 25 %).
std::vector<double> body_nodes(const ArcLength& arc, const HullGridSpec& s, double begin,
                               double end, double first = 0, double last = 0) {
  const bool zone = has_fin_zone(s) && s.fin_zone_share > 0;
  const double keep = zone ? 1 - s.fin_zone_share : 1;
  const double uniform = (end - begin) / s.body_cells;
  auto sigma = first > 0 && s.body_cells >= 3 && keep * first < uniform && keep * last < uniform
                   ? two_sided_nodes(begin, end, s.body_cells, keep * first, keep * last)
               : first > 0 ? graded_nodes(begin, end, s.body_cells)
                           : graded_nodes(begin, end, s.body_cells, s.rim_clustering, true);
  if (!zone) return sigma;
  constexpr int kSamples = 8000;
  std::vector<double> at;
  for (int k = 0; k <= kSamples; ++k) at.push_back(begin + (end - begin) * k / kSamples);
  const auto rim = node_fractions(sigma, at), zone_f = zone_fractions(arc, s, at);
  std::vector<double> mixed;
  for (std::size_t k = 0; k < at.size(); ++k)
    mixed.push_back((1 - s.fin_zone_share) * rim[k] + s.fin_zone_share * zone_f[k]);
  for (int k = 1; k < s.body_cells; ++k) {
    const double target = k / static_cast<double>(s.body_cells);
    const auto it = std::lower_bound(mixed.begin(), mixed.end(), target);
    const auto m = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - mixed.begin()));
    const double t = (target - mixed[m - 1]) / (mixed[m] - mixed[m - 1]);
    sigma[static_cast<std::size_t>(k)] = at[m - 1] + t * (at[m] - at[m - 1]);
  }
  return sigma;
}

// Polar angle of ring point k (of nt) at `station`: half a step off the fin planes (no ring point
// in a fin's mid-plane), the sectors narrowed at the fins by the clustering there.
double ring_angle(const HullGridSpec& s, int k, int nt, double station) {
  const double xi = s.fin_angle + 2 * std::numbers::pi * (k + 0.5) / nt;
  if (s.fins == 0) return xi;
  const double c = s.fin_clustering * fin_zone_weight(s, station);
  return xi - c * std::sin(s.fins * (xi - s.fin_angle)) / s.fins;
}

// The wall-normal lines of the meridional grid: wall point (station, radius), the line that owns
// that point (itself, or the rim line for a fan line), and the direction. Every wall point lies on
// the exact profile; every direction is the wall normal there (the average of the two segment
// normals), so the first cells are orthogonal to the wall. At each rim, where the flat end face
// meets the curved hull at a convex corner (42 deg at the REMUS nose, 68 deg at the tail), a fan of
// `rim_fan` lines turns from one face's normal to the other's: the fan cells are prisms on the rim
// circle. For a convex profile the directions turn monotonically, so the lines never cross.
struct WallLines {
  std::vector<Vec2> point, dir;
  std::vector<int> owner;
  [[nodiscard]] int size() const { return static_cast<int>(point.size()); }
};

// A rim rounded by a circular arc of radius R, tangent to the end face and to the curved hull:
// the centre lies R inside both, so for the nose it solves c.x = R with c = P(x) - R n(x) (P the
// profile point at station x, n its outward unit normal), and for the tail c.x = L - R; x is
// found by bisection (c.x rises with x wherever R is below the profile's radius of curvature, and
// c.x - goal changes sign over the bracket [0, R] or [L - R, L] wherever the profile rises from
// the nose and falls to the tail, as every Myring profile does). The arc runs
// between the polar angles `from` (the end face's normal: pi at the nose, 0 at the tail) and
// `to` (the hull's normal at the tangent station `station`).
struct Fillet {
  Vec2 centre = Vec2::Zero();
  double from = 0, to = 0, station = 0;
};

Fillet fillet(const geometry::MyringProfile& p, double radius, bool nose) {
  const auto normal = [&](double x) -> Vec2 {
    const double m = p.slope(x);
    return Vec2(-m, 1.0) / std::sqrt(1 + m * m);
  };
  const auto centre = [&](double x) -> Vec2 { return Vec2(x, p.radius(x)) - radius * normal(x); };
  const double length = p.length(), goal = nose ? radius : length - radius;
  double lo = nose ? 0.0 : length - radius, hi = nose ? radius : length;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (centre(mid).x() < goal ? lo : hi) = mid;
  }
  Fillet f;
  f.station = 0.5 * (lo + hi);
  f.centre = centre(f.station);
  f.from = nose ? std::numbers::pi : 0.0;
  const Vec2 n = normal(f.station);
  f.to = std::atan2(n.y(), n.x());
  check(f.centre.y() > 0, "rim_radius",
        fmt::format("({:.4g} m) rounds away the whole {} face: it must be smaller", radius,
                    nose ? "nose" : "tail"));
  return f;
}

// Distances from a filleted rim towards the axis along its end face (length `face`): n cells, the
// one at the rim `h` (the arc's cell) unless uniform cells are finer.
std::vector<double> face_distances(double face, int n, double h) {
  if (n == 1 || h >= face / n) return graded_nodes(0, face, n);
  return stretched_nodes(0, face, h, n);
}

// The outward unit normal of the wall segment from w[a] to w[b] (the body lies on the right of the
// traversal, nose to tail), and at an inner wall point the average of its two segments' normals.
Vec2 segment_normal(const std::vector<Vec2>& w, std::size_t a, std::size_t b) {
  const Vec2 t = (w[b] - w[a]).normalized();
  return Vec2(-t.y(), t.x());
}
Vec2 vertex_normal(const std::vector<Vec2>& w, std::size_t i) {
  return (segment_normal(w, i - 1, i) + segment_normal(w, i, i + 1)).normalized();
}
// The wall's first and last points lie on the axis; their lines run along it, ahead of the nose
// and behind the tail.
bool on_axis(const std::vector<Vec2>& w, std::size_t i) {
  return i == 0 || i + 1 == w.size();
}
Vec2 axis_direction(std::size_t i) {
  return Vec2(i == 0 ? -1.0 : 1.0, 0.0);
}

// Wall lines round filleted rims: the nose face from the axis, the nose arc, the curved hull
// between the tangent stations, the tail arc and the tail face to the axis. The arcs' lines are
// their radii (the exact normals); every other line is the average of its two segments' normals,
// as for sharp rims, and every line owns its wall point (no fan, no collapsed cells).
WallLines filleted_wall_lines(const geometry::MyringProfile& p, const HullGridSpec& s) {
  const double radius = s.rim_radius;
  const Fillet nose = fillet(p, radius, true), tail = fillet(p, radius, false);
  const double h_nose = radius * std::abs(nose.to - nose.from) / s.rim_fan;
  const double h_tail = radius * std::abs(tail.to - tail.from) / s.rim_fan;
  std::vector<Vec2> w, exact;  // wall points, and the exact normal where known (else zero)
  const auto add = [&](Vec2 point, Vec2 dir) {
    w.push_back(point);
    exact.push_back(dir);
  };
  const auto nose_face = face_distances(nose.centre.y(), s.nose_face_cells, h_nose);
  for (auto it = nose_face.rbegin(); it + 1 != nose_face.rend(); ++it)  // axis up, arc excluded
    add(Vec2(0.0, nose.centre.y() - *it), Vec2::Zero());
  const auto arc_points = [&](const Fillet& f) {
    for (int k = 0; k <= s.rim_fan; ++k) {
      const double phi = f.from + (f.to - f.from) * k / s.rim_fan;
      const Vec2 dir(std::cos(phi), std::sin(phi));
      Vec2 q = f.centre + radius * dir;
      if (phi == std::numbers::pi) q.x() = 0;  // on the end faces exactly (c.x -/+ R rounds)
      if (phi == 0) q.x() = p.length();
      add(q, dir);
    }
  };
  const auto reverse = [](Fillet f) {
    std::swap(f.from, f.to);
    return f;
  };
  arc_points(nose);
  const ArcLength arc(p);
  const auto sigma =
      body_nodes(arc, s, arc.arc(nose.station), arc.arc(tail.station), h_nose, h_tail);
  for (std::size_t k = 1; k + 1 < sigma.size(); ++k) {
    const double st = arc.station(sigma[k]);
    add(Vec2(st, p.radius(st)), Vec2::Zero());
  }
  arc_points(reverse(tail));
  const auto tail_face = face_distances(tail.centre.y(), s.tail_face_cells, h_tail);
  for (std::size_t k = 1; k < tail_face.size(); ++k)  // arc excluded, down to the axis
    add(Vec2(p.length(), tail.centre.y() - tail_face[k]), Vec2::Zero());
  w.front().y() = 0;
  w.back().y() = 0;

  WallLines lines;
  for (std::size_t i = 0; i < w.size(); ++i) {
    lines.point.push_back(w[i]);
    lines.owner.push_back(lines.size() - 1);
    lines.dir.push_back(on_axis(w, i)              ? axis_direction(i)
                        : exact[i] != Vec2::Zero() ? exact[i]
                                                   : vertex_normal(w, i));
  }
  return lines;
}

WallLines wall_lines(const geometry::MyringProfile& p, const HullGridSpec& s) {
  if (s.rim_radius > 0) return filleted_wall_lines(p, s);
  const double r_nose = p.radius(0), r_tail = p.radius(p.length());
  std::vector<Vec2> w;
  std::vector<std::size_t> rims;  // indices (in w) of the two rim points
  // Cells shrink towards the rims, where the meridian turns a corner.
  for (double r : graded_nodes(0, r_nose, s.nose_face_cells, 1 / s.rim_clustering))
    w.emplace_back(0.0, r);
  rims.push_back(w.size() - 1);
  const ArcLength arc(p);
  const auto sigma = body_nodes(arc, s, 0, arc.total());
  for (std::size_t k = 1; k + 1 < sigma.size(); ++k) {
    const double st = arc.station(sigma[k]);
    w.emplace_back(st, p.radius(st));
  }
  const auto tail = graded_nodes(0, r_tail, s.tail_face_cells, 1 / s.rim_clustering);
  rims.push_back(w.size());
  for (auto it = tail.rbegin(); it != tail.rend(); ++it) w.emplace_back(p.length(), *it);

  WallLines lines;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const int here = lines.size();
    const bool rim = i == rims[0] || i == rims[1];
    if (!rim) {
      lines.point.push_back(w[i]);
      lines.dir.push_back(on_axis(w, i) ? axis_direction(i) : vertex_normal(w, i));
      lines.owner.push_back(here);
      continue;
    }
    // A sharp rim's fan: its lines turn from the one segment's normal to the other's.
    const Vec2 before = segment_normal(w, i - 1, i), after = segment_normal(w, i, i + 1);
    const double a = std::atan2(before.y(), before.x()), b = std::atan2(after.y(), after.x());
    for (int t = 0; t <= s.rim_fan; ++t) {
      const double angle = a + (b - a) * t / s.rim_fan;
      lines.point.push_back(w[i]);
      lines.dir.emplace_back(std::cos(angle), std::sin(angle));
      lines.owner.push_back(here);
    }
  }
  return lines;
}

std::vector<double> normal_distances(const HullGridSpec& s) {
  return s.normal_cells > 0 ? stretched_nodes(0, s.extent, s.first_cell, s.normal_cells)
                            : grown_nodes(0, s.extent, s.first_cell, s.growth);
}
}  // namespace

Grid hull_grid(const geometry::MyringProfile& profile, double cb_station, const HullGridSpec& s) {
  check_spec(profile, s);
  const WallLines lines = wall_lines(profile, s);
  const auto dist = normal_distances(s);
  const int ni = lines.size() - 1, nj = static_cast<int>(dist.size()) - 1;
  const int nt = s.circumferential;

  CellAssembler a;
  std::vector<int> layer;  // j of every point, for the patch classifier
  // index[i][j]: first point of the ring (i, j); axis lines (i = 0, ni) have a single point, and
  // the fan lines of a rim share the rim's wall ring.
  std::vector<std::vector<int>> index(static_cast<std::size_t>(ni + 1));
  for (int i = 0; i <= ni; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    const bool axis = i == 0 || i == ni;
    for (int j = 0; j <= nj; ++j) {
      if (j == 0 && lines.owner[iu] != i) {
        index[iu].push_back(index[static_cast<std::size_t>(lines.owner[iu])][0]);
        continue;
      }
      const Vec2 q = lines.point[iu] + dist[static_cast<std::size_t>(j)] * lines.dir[iu];
      index[iu].push_back(static_cast<int>(a.points().size()));
      for (int k = 0; k < (axis ? 1 : nt); ++k) {
        const double th = ring_angle(s, k, nt, q.x());
        const double r = axis ? 0.0 : q.y();
        a.add_point(Eigen::Vector3d(cb_station - q.x(), r * std::cos(th), r * std::sin(th)));
        layer.push_back(j);
      }
    }
  }
  const auto P = [&](int i, int j, int k) {
    const int base = index[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    return (i == 0 || i == ni) ? base : base + k % nt;
  };
  // (i, j, theta) maps to (-x, r, theta), a left-handed triad: theta runs downward in the corner
  // order. Checked on a mid-body cell; validate() checks every cell.
  const auto hex = [&](int i, int j, int k) {
    return HexCorners{P(i, j, k + 1),     P(i + 1, j, k + 1), P(i + 1, j + 1, k + 1),
                      P(i, j + 1, k + 1), P(i, j, k),         P(i + 1, j, k),
                      P(i + 1, j + 1, k), P(i, j + 1, k)};
  };
  if (!(a.signed_volume(hex(ni / 2, 0, 0)) > 0))
    throw std::logic_error("hull grid: corner order gives a negative volume");
  for (int i = 0; i < ni; ++i)
    for (int j = 0; j < nj; ++j)
      for (int k = 0; k < nt; ++k) a.add_hex(hex(i, j, k));

  return a.build("hull", {{"hull", PatchType::wall}, {"hull_overset", PatchType::overset}},
                 [&](std::span<const int> f) {
                   const auto all = [&](int j) {
                     return std::all_of(f.begin(), f.end(), [&](int p) {
                       return layer[static_cast<std::size_t>(p)] == j;
                     });
                   };
                   return all(0) ? 0 : all(nj) ? 1 : -1;
                 });
}

}  // namespace auvloop::mesher
