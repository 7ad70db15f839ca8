// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/cell_assembly.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

namespace auvloop::mesher {

namespace {
// Outward faces of the VTK hexahedron (checked against the unit cube: each right-hand normal
// points away from the cube's centre).
constexpr std::array<std::array<int, 4>, 6> kHexFaces{{
    {0, 3, 2, 1},  // bottom
    {4, 5, 6, 7},  // top
    {0, 1, 5, 4},
    {3, 7, 6, 2},
    {0, 4, 7, 3},
    {1, 2, 6, 5},
}};

// Faces have at most four points after collapsing; sorted and padded with -1 they identify a face
// regardless of its orientation and starting point.
using FaceKey = std::array<int, 4>;

FaceKey key_of(const std::vector<int>& f) {
  FaceKey k{-1, -1, -1, -1};
  for (std::size_t i = 0; i < f.size() && i < k.size(); ++i) {
    // Insertion sort of at most four values.
    std::size_t j = i;
    for (; j > 0 && k[j - 1] > f[i]; --j) k[j] = k[j - 1];
    k[j] = f[i];
  }
  return k;
}

struct KeyHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = 1469598103934665603U;  // FNV-1a
    for (int v : k)
      h = (h ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(v))) * 1099511628211U;
    return static_cast<std::size_t>(h);
  }
};

// True when b runs through a's points in the opposite direction (as a shared face must, seen from
// its two cells).
bool reversed_cycle(const std::vector<int>& a, const std::vector<int>& b) {
  const std::size_t n = a.size();
  if (b.size() != n) return false;
  const auto it = std::find(b.begin(), b.end(), a[0]);
  if (it == b.end()) return false;
  const auto s = static_cast<std::size_t>(it - b.begin());
  for (std::size_t k = 0; k < n; ++k)
    if (a[k] != b[(s + n - k) % n]) return false;
  return true;
}

struct FaceRecord {
  int owner = 0, neighbour = -1;
  std::vector<int> points;
};
}  // namespace

std::vector<std::vector<int>> hex_faces(const HexCorners& c) {
  std::vector<std::vector<int>> faces;
  for (const auto& f : kHexFaces) {
    std::vector<int> pts;
    for (int k : f) {
      const int p = c[static_cast<std::size_t>(k)];
      if (pts.empty() || pts.back() != p) pts.push_back(p);
    }
    while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
    if (pts.size() >= 3) faces.push_back(std::move(pts));
  }
  return faces;
}

int CellAssembler::add_point(const Eigen::Vector3d& p) {
  points_.push_back(p);
  return static_cast<int>(points_.size()) - 1;
}

void CellAssembler::add_hex(const HexCorners& corners) {
  cells_.push_back(corners);
}

double CellAssembler::signed_volume(const HexCorners& corners) const {
  // Sum over faces of (area vector . point average) / 3; exact for planar faces, and a consistent
  // sign test for the warped faces of a real cell.
  double v = 0;
  for (const auto& f : hex_faces(corners)) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero(), area = Eigen::Vector3d::Zero();
    for (int p : f) mean += points_[static_cast<std::size_t>(p)];
    mean /= static_cast<double>(f.size());
    for (std::size_t k = 0; k < f.size(); ++k) {
      const auto& a = points_[static_cast<std::size_t>(f[k])];
      const auto& b = points_[static_cast<std::size_t>(f[(k + 1) % f.size()])];
      area += 0.5 * (a - mean).cross(b - mean);
    }
    v += area.dot(mean) / 3;
  }
  return v;
}

Grid CellAssembler::build(const std::string& name,
                          const std::vector<std::pair<std::string, PatchType>>& patches,
                          const std::function<int(std::span<const int>)>& classify) const {
  std::unordered_map<FaceKey, std::size_t, KeyHash> open;  // unmatched face -> record index
  std::vector<FaceRecord> records;
  records.reserve(cells_.size() * 4);
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    for (auto& f : hex_faces(cells_[c])) {
      const FaceKey key = key_of(f);
      const auto it = open.find(key);
      if (it == open.end()) {
        open.emplace(key, records.size());
        records.push_back({static_cast<int>(c), -1, std::move(f)});
        continue;
      }
      FaceRecord& r = records[it->second];
      if (!reversed_cycle(r.points, f)) {
        throw std::runtime_error(fmt::format(
            "grid \"{}\": cells {} and {} disagree about the orientation of their shared face",
            name, r.owner, c));
      }
      r.neighbour = static_cast<int>(c);
      open.erase(it);
    }
  }
  std::vector<const FaceRecord*> internal;
  std::vector<std::vector<const FaceRecord*>> boundary(patches.size());
  for (const auto& r : records) {
    if (r.neighbour >= 0) {
      internal.push_back(&r);
      continue;
    }
    const int p = classify(r.points);
    if (p < 0 || p >= static_cast<int>(patches.size())) {
      throw std::runtime_error(
          fmt::format("grid \"{}\": boundary face of cell {} (first point {}) belongs to no patch",
                      name, r.owner, r.points.front()));
    }
    boundary[static_cast<std::size_t>(p)].push_back(&r);
  }
  std::stable_sort(internal.begin(), internal.end(), [](const auto* a, const auto* b) {
    return std::pair(a->owner, a->neighbour) < std::pair(b->owner, b->neighbour);
  });
  Grid g;
  g.name = name;
  g.points = points_;
  g.cells = cells();
  for (const auto* r : internal) {
    g.add_face(r->points, r->owner);
    g.neighbour.push_back(r->neighbour);
  }
  for (std::size_t p = 0; p < patches.size(); ++p) {
    Patch patch{patches[p].first, patches[p].second, g.faces(), 0, -1};
    for (const auto* r : boundary[p]) g.add_face(r->points, r->owner);
    patch.size = g.faces() - patch.start;
    g.patches.push_back(patch);
  }
  return g;
}

}  // namespace auvloop::mesher
