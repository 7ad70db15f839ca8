// SPDX-License-Identifier: GPL-3.0-or-later
#include "periodic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_set>

#include <fmt/format.h>

namespace auvloop::engine::fv {

namespace {
using mesher::Grid;
using mesher::GridGeometry;
using mesher::Patch;
using mesher::PatchType;

std::string point(const Eigen::Vector3d& x) {
  return fmt::format("({:.6g}, {:.6g}, {:.6g})", x.x(), x.y(), x.z());
}

void check_pairing(const Grid& g, std::size_t p) {
  const Patch& a = g.patches[p];
  const int q = a.neighbour_patch;
  if (q < 0 || static_cast<std::size_t>(q) >= g.patches.size() || static_cast<std::size_t>(q) == p)
    throw std::invalid_argument(
        fmt::format("periodic patch '{}' of grid '{}' names no other patch", a.name, g.name));
  const Patch& b = g.patches[static_cast<std::size_t>(q)];
  if (b.type != PatchType::periodic || b.neighbour_patch != static_cast<int>(p))
    throw std::invalid_argument(fmt::format(
        "periodic patch '{}' of grid '{}': its neighbour '{}' is not a periodic patch paired "
        "with it",
        a.name, g.name, b.name));
  if (a.size != b.size)
    throw std::invalid_argument(
        fmt::format("periodic patches '{}' ({} faces) and '{}' ({} faces) of grid '{}' differ in "
                    "size",
                    a.name, a.size, b.name, b.size, g.name));
}

Eigen::Vector3d mean_centre(const Patch& patch, const GridGeometry& geo) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < patch.size; ++i)
    sum += geo.face_centre[static_cast<std::size_t>(patch.start + i)];
  return sum / std::max(1, patch.size);
}

// For each face of b, the face of a it covers once translated by s. Faces of a are sorted by
// their projection on a direction oblique to any grid line, so each search scans a narrow window.
std::vector<int> match_faces(const GridGeometry& geo, const Patch& a, const Patch& b,
                             const Eigen::Vector3d& s) {
  const Eigen::Vector3d e = Eigen::Vector3d(1.0, 0.7548776662, 0.5698402910).normalized();
  std::vector<std::pair<double, int>> keys;
  for (int i = 0; i < a.size; ++i)
    keys.emplace_back(e.dot(geo.face_centre[static_cast<std::size_t>(a.start + i)]), a.start + i);
  std::sort(keys.begin(), keys.end());
  std::vector<int> match(static_cast<std::size_t>(b.size), -1);
  std::vector<char> used(static_cast<std::size_t>(a.size), 0);
  for (int i = 0; i < b.size; ++i) {
    const auto fb = static_cast<std::size_t>(b.start + i);
    const Eigen::Vector3d target = geo.face_centre[fb] + s;
    // Matching tolerance: a millionth of the face's size, far below any cell but above round-off.
    const double tol = 1e-6 * std::sqrt(geo.face_area[fb].norm());
    const double key = e.dot(target);
    auto it = std::lower_bound(keys.begin(), keys.end(), std::pair{key - tol, -1});
    for (; it != keys.end() && it->first <= key + tol; ++it) {
      if ((geo.face_centre[static_cast<std::size_t>(it->second)] - target).norm() > tol) continue;
      match[static_cast<std::size_t>(i)] = it->second;
      break;
    }
    const int fa = match[static_cast<std::size_t>(i)];
    if (fa < 0 || used[static_cast<std::size_t>(fa - a.start)])
      throw std::invalid_argument(fmt::format(
          "periodic patch '{}': face {} at {} has no partner on '{}' at the translation {}", b.name,
          fb, point(geo.face_centre[fb]), a.name, point(s)));
    used[static_cast<std::size_t>(fa - a.start)] = 1;
    const Eigen::Vector3d& Sa = geo.face_area[static_cast<std::size_t>(fa)];
    if ((Sa + geo.face_area[fb]).norm() > 1e-6 * Sa.norm())
      throw std::invalid_argument(fmt::format(
          "periodic patches '{}' and '{}': faces {} and {} at {} are not translated copies "
          "(their area vectors differ)",
          a.name, b.name, fa, fb, point(geo.face_centre[fb])));
  }
  return match;
}

struct InternalFace {
  int owner, neighbour, source;
  Eigen::Vector3d shift;
};

std::uint64_t key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// The coupled faces of one pair of patches (a: the lower patch index), appended to `faces`.
void couple_pair(const Grid& g, const GridGeometry& geo, const Patch& a, const Patch& b,
                 std::unordered_set<std::uint64_t>& existing, std::vector<InternalFace>& faces) {
  const Eigen::Vector3d s = mean_centre(a, geo) - mean_centre(b, geo);
  const auto match = match_faces(geo, a, b, s);
  for (int i = 0; i < b.size; ++i) {
    const int fb = b.start + i, fa = match[static_cast<std::size_t>(i)];
    const int Pa = g.owner[static_cast<std::size_t>(fa)],
              Pb = g.owner[static_cast<std::size_t>(fb)];
    if (Pa == Pb || existing.contains(key(std::min(Pa, Pb), std::max(Pa, Pb))))
      throw std::invalid_argument(fmt::format(
          "periodic patches '{}' and '{}' of grid '{}': cells {} and {} would be coupled twice; a "
          "periodic direction needs at least three cells",
          a.name, b.name, g.name, Pa, Pb));
    existing.insert(key(std::min(Pa, Pb), std::max(Pa, Pb)));
    // The cell behind b is seen through a at its centre + s, and vice versa.
    if (Pa < Pb)
      faces.push_back({Pa, Pb, fa, s});
    else
      faces.push_back({Pb, Pa, fb, -s});
  }
}

void copy_face(const Grid& g, const GridGeometry& geo, int f, int owner, CoupledGrid& out) {
  const auto fs = static_cast<std::size_t>(f);
  out.grid.add_face(std::vector<int>(g.face_points.begin() + g.face_offsets[fs],
                                     g.face_points.begin() + g.face_offsets[fs + 1]),
                    owner);
  out.geometry.face_centre.push_back(geo.face_centre[fs]);
  out.geometry.face_area.push_back(geo.face_area[fs]);
}
}  // namespace

std::optional<CoupledGrid> couple_periodic(const Grid& g, const GridGeometry& geo) {
  std::vector<InternalFace> internal;
  std::unordered_set<std::uint64_t> existing;
  for (int f = 0; f < g.internal_faces(); ++f) {
    const auto fs = static_cast<std::size_t>(f);
    internal.push_back({g.owner[fs], g.neighbour[fs], f, Eigen::Vector3d::Zero()});
    existing.insert(key(g.owner[fs], g.neighbour[fs]));
  }
  bool any = false;
  for (std::size_t p = 0; p < g.patches.size(); ++p) {
    if (g.patches[p].type != PatchType::periodic) continue;
    any = true;
    check_pairing(g, p);
    const auto q = static_cast<std::size_t>(g.patches[p].neighbour_patch);
    if (p < q) couple_pair(g, geo, g.patches[p], g.patches[q], existing, internal);
  }
  if (!any) return std::nullopt;
  // Upper-triangular order (by owner, then neighbour), as the DIC sweeps assume.
  std::stable_sort(internal.begin(), internal.end(), [](const auto& x, const auto& y) {
    return x.owner != y.owner ? x.owner < y.owner : x.neighbour < y.neighbour;
  });
  CoupledGrid out;
  out.grid.name = g.name;
  out.grid.points = g.points;
  out.grid.zones = g.zones;
  out.grid.cells = g.cells;
  out.grid.placement = g.placement;
  out.geometry.cell_centre = geo.cell_centre;
  out.geometry.cell_volume = geo.cell_volume;
  for (const auto& f : internal) {
    copy_face(g, geo, f.source, f.owner, out);
    out.grid.neighbour.push_back(f.neighbour);
    out.shift.push_back(f.shift);
  }
  for (const auto& patch : g.patches) {
    Patch coupled = patch;
    coupled.start = out.grid.faces();
    coupled.size = patch.type == PatchType::periodic ? 0 : patch.size;
    for (int i = 0; i < coupled.size; ++i)
      copy_face(g, geo, patch.start + i, g.owner[static_cast<std::size_t>(patch.start + i)], out);
    out.grid.patches.push_back(coupled);
  }
  return out;
}

}  // namespace auvloop::engine::fv
