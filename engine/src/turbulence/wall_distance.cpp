// SPDX-License-Identifier: GPL-3.0-or-later
// Wall distance: the algorithm (steps 1-4) is stated in
// auvloop/engine/turbulence/wall_distance.hpp.
#include "auvloop/engine/turbulence/wall_distance.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "auvloop/mesher/wall_triangles.hpp"

namespace auvloop::engine::turbulence {

namespace {
// Each bound is lowered by this share of the magnitudes it is computed from, so that round-off
// never lifts a bound above the exact value a query returns (the minimum found is then the exact
// one, and the same whatever entries were bounds).
constexpr double kSlack = 1e-12;

// Relative placements equal to round-off (those of a whole-system motion composed into every
// grid's placement): rotation entries within 1e-12, the translation within 1e-12 of its size.
bool same(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const double scale = 1 + std::max(a.translation().norm(), b.translation().norm());
  return (a.linear() - b.linear()).cwiseAbs().maxCoeff() <= 1e-12 &&
         (a.translation() - b.translation()).cwiseAbs().maxCoeff() <= 1e-12 * scale;
}
}  // namespace

namespace {
// The bounding sphere of a wall group's triangles.
std::pair<Eigen::Vector3d, double> sphere(const std::vector<geometry::Triangle>& triangles) {
  Eigen::AlignedBox3d box;
  for (const auto& t : triangles)
    for (const auto& p : t) box.extend(p);
  const Eigen::Vector3d centre = box.center();
  double radius = 0;
  for (const auto& t : triangles)
    for (const auto& p : t) radius = std::max(radius, (p - centre).norm());
  return {centre, radius};
}
}  // namespace

WallDistances::WallDistances(std::span<const fv::Mesh* const> meshes) {
  // 1.
  std::string names;
  for (std::size_t g = 0; g < meshes.size(); ++g) {
    const mesher::Grid& grid = meshes[g]->source_grid();
    parts_.push_back({meshes[g], 0, meshes[g]->cells()});
    names += (names.empty() ? "'" : ", '") + grid.name + "'";
    const auto triangles = mesher::wall_triangles(grid, Eigen::Isometry3d::Identity());
    if (triangles.empty()) continue;
    const auto [centre, radius] = sphere(triangles);
    groups_.push_back({static_cast<int>(g), geometry::TriangleDistance(triangles), centre, radius});
  }
  if (groups_.empty())
    throw std::invalid_argument("wall distance: no wall patch face in the grids " + names);
  start();
}

WallDistances::WallDistances(const fv::Mesh& composite, std::span<const int> cell_offset) {
  const mesher::Grid& grid = composite.source_grid();
  for (std::size_t k = 0; k < cell_offset.size(); ++k) {
    const int first = cell_offset[k];
    const int end = k + 1 < cell_offset.size() ? cell_offset[k + 1] : composite.cells();
    if (first < 0 || end < first || end > composite.cells() || (k == 0 && first != 0))
      throw std::invalid_argument(
          fmt::format("wall distance: the component offsets {} do not split the {} cells of '{}'",
                      fmt::join(cell_offset, ", "), composite.cells(), grid.name));
    parts_.push_back({&composite, first, end - first});
    const auto triangles = mesher::wall_triangles(grid, Eigen::Isometry3d::Identity(), first, end);
    if (triangles.empty()) continue;
    const auto [centre, radius] = sphere(triangles);
    groups_.push_back({static_cast<int>(k), geometry::TriangleDistance(triangles), centre, radius});
  }
  if (parts_.empty())
    throw std::invalid_argument("wall distance: a composite of '" + grid.name +
                                "' needs at least one component");
  if (groups_.empty())
    throw std::invalid_argument("wall distance: no wall patch face in '" + grid.name + "'");
  axes_.assign(parts_.size(), Eigen::Isometry3d::Identity());
  start();
}

void WallDistances::start() {
  const std::size_t H = groups_.size();
  taken_at_.resize(parts_.size());
  entries_.resize(parts_.size());
  distance_.resize(parts_.size());
  for (std::size_t g = 0; g < parts_.size(); ++g) {
    const auto n = static_cast<std::size_t>(parts_[g].cells);
    taken_at_[g].assign(H, Eigen::Isometry3d::Identity());
    entries_[g].assign(n * H, Entry{});
    distance_[g].assign(n, 0.0);
  }
  pending_.assign(parts_.size(), false);
  // 2 and 3 with every pair new.
  initial_ = refresh(true, {});
}

std::span<const double> WallDistances::of(int grid) const {
  return distance_.at(static_cast<std::size_t>(grid));
}

std::vector<double> WallDistances::composite() const {
  std::vector<double> out;
  for (const auto& d : distance_) out.insert(out.end(), d.begin(), d.end());
  return out;
}

const Eigen::Isometry3d& WallDistances::placement(std::size_t g) const {
  return axes_.empty() ? parts_[g].mesh->source_grid().placement : axes_[g];
}

void WallDistances::check_masks(std::span<const std::vector<char>> needed) const {
  if (needed.empty()) return;
  if (needed.size() != parts_.size())
    throw std::invalid_argument("wall distance: " + std::to_string(needed.size()) +
                                " cell masks for " + std::to_string(parts_.size()) + " grids");
  for (std::size_t g = 0; g < parts_.size(); ++g)
    if (needed[g].size() != static_cast<std::size_t>(parts_[g].cells))
      throw std::invalid_argument(
          fmt::format("wall distance: the cell mask of grid {} ('{}') has {} entries for {} cells",
                      g, parts_[g].mesh->source_grid().name, needed[g].size(), parts_[g].cells));
}

WallDistances::Work WallDistances::update(std::span<const std::vector<char>> needed) {
  if (!axes_.empty())
    throw std::invalid_argument("wall distance: a composite's update needs its components' axes");
  check_masks(needed);
  return refresh(false, needed);
}

WallDistances::Work WallDistances::update(std::span<const Eigen::Isometry3d> axes,
                                          std::span<const std::vector<char>> needed) {
  if (axes_.empty())
    throw std::invalid_argument("wall distance: axes are for a composite mesh's components");
  if (axes.size() != axes_.size())
    throw std::invalid_argument(
        fmt::format("wall distance: {} axes for {} components", axes.size(), axes_.size()));
  check_masks(needed);
  axes_.assign(axes.begin(), axes.end());
  return refresh(false, needed);
}

WallDistances::Work WallDistances::refresh(bool all, std::span<const std::vector<char>> needed) {
  Work work;
  const std::size_t H = groups_.size();
  for (std::size_t g = 0; g < parts_.size(); ++g) {
    const Part& part = parts_[g];
    const Eigen::Isometry3d& P_g = placement(g);
    // The relative placements now, and which of them changed.
    std::vector<Eigen::Isometry3d> T(H);
    std::vector<char> changed(H, 0);
    bool any = false;
    for (std::size_t h = 0; h < H; ++h) {
      const auto& P_h = placement(static_cast<std::size_t>(groups_[h].grid));
      T[h] = P_h.inverse() * P_g;
      changed[h] = all || !same(T[h], taken_at_[g][h]) ? 1 : 0;
      any = any || changed[h] != 0;
      work.pairs += changed[h];
    }
    // Unmoved and every cell needed: nothing to do. With a mask, a cell needed now may not have
    // been before (a hole turned active): step 3 runs for every needed cell.
    if (!any && needed.empty() && !pending_[g]) continue;
    pending_[g] = !needed.empty();
    const char* need = needed.empty() ? nullptr : needed[g].data();
    const auto& old = taken_at_[g];
    auto& entries = entries_[g];
    auto& distance = distance_[g];
    // Shared out dynamically (work stealing), since the exact queries cluster round the moved
    // walls: each cell's entries depend on that cell alone, and the counts are sums of integers,
    // so neither depends on who ran what.
    std::atomic<long> bounds{0}, queries{0};
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, static_cast<std::size_t>(part.cells), 64),
        [&](const tbb::blocked_range<std::size_t>& range) {
          std::array<long, 2> count{0, 0};
          for (std::size_t c = range.begin(); c < range.end(); ++c) {
            const Eigen::Vector3d& x = part.mesh->centre(part.first + static_cast<int>(c));
            Entry* row = &entries[c * H];
            // Step 4: the new bounds of the changed pairs.
            for (std::size_t h = 0; h < H; ++h) {
              if (!changed[h]) continue;
              const Group& G = groups_[h];
              const Eigen::Vector3d y = T[h] * x;
              const double r = (y - G.centre).norm();
              double bound = r - G.radius - kSlack * (r + G.radius);
              if (!all) {
                const double moved = (y - old[h] * x).norm();
                const double was = row[h].value;
                bound = std::max(bound, was - moved - kSlack * (was + moved + y.norm()));
              }
              row[h] = {std::max(0.0, bound), false};
              count[0] += 1;
            }
            // Step 3: the least entry exact (needed cells only).
            if (need && !need[c]) continue;
            for (;;) {
              std::size_t least = 0;
              for (std::size_t h = 1; h < H; ++h)
                if (row[h].value < row[least].value) least = h;
              if (row[least].exact) {
                distance[c] = row[least].value;
                break;
              }
              row[least] = {groups_[least].walls.distance(T[least] * x), true};
              count[1] += 1;
            }
          }
          bounds += count[0];
          queries += count[1];
        });
    work.bounds += bounds.load();
    work.queries += queries.load();
    for (std::size_t h = 0; h < H; ++h)
      if (changed[h]) taken_at_[g][h] = T[h];
  }
  return work;
}

void WallDistances::save(StateWriter& out) const {
  out.tag("wall distances");
  out.put(static_cast<std::int64_t>(parts_.size()));
  out.put(static_cast<std::int64_t>(groups_.size()));
  for (const auto& a : axes_) out.put(a.matrix());
  for (std::size_t g = 0; g < parts_.size(); ++g) {
    out.put(static_cast<std::int64_t>(parts_[g].cells));
    for (const auto& t : taken_at_[g]) out.put(t.matrix());
    std::vector<double> value;
    std::vector<char> exact;
    for (const auto& e : entries_[g]) {
      value.push_back(e.value);
      exact.push_back(e.exact ? 1 : 0);
    }
    out.put(value);
    out.put(exact);
    out.put(distance_[g]);
    out.put(static_cast<bool>(pending_[g]));
  }
}

void WallDistances::load(StateReader& in) {
  in.expect_tag("wall distances");
  const auto parts = in.get<std::int64_t>(), groups = in.get<std::int64_t>();
  if (parts != static_cast<std::int64_t>(parts_.size()) ||
      groups != static_cast<std::int64_t>(groups_.size()))
    in.fail(fmt::format("wall distances of {} grids and {} wall groups, these have {} and {}",
                        parts, groups, parts_.size(), groups_.size()));
  auto axes = axes_;
  for (auto& a : axes) {
    Eigen::Matrix4d m;
    in.get(m);
    a.matrix() = m;
  }
  auto taken_at = taken_at_;
  auto entries = entries_;
  auto distance = distance_;
  auto pending = pending_;
  for (std::size_t g = 0; g < parts_.size(); ++g) {
    if (const auto cells = in.get<std::int64_t>(); cells != parts_[g].cells)
      in.fail(fmt::format("grid {}: {} cells stored, this one has {}", g, cells, parts_[g].cells));
    for (auto& t : taken_at[g]) {
      Eigen::Matrix4d m;
      in.get(m);
      t.matrix() = m;
    }
    const auto value = in.get_vector<double>();
    const auto exact = in.get_vector<char>();
    distance[g] = in.get_vector<double>();
    pending[g] = in.get<bool>();
    if (value.size() != entries[g].size() || exact.size() != value.size() ||
        distance[g].size() != distance_[g].size())
      in.fail(fmt::format("grid {}: the entries do not match its cells and groups", g));
    for (std::size_t i = 0; i < value.size(); ++i) entries[g][i] = {value[i], exact[i] != 0};
  }
  axes_ = std::move(axes);
  taken_at_ = std::move(taken_at);
  entries_ = std::move(entries);
  distance_ = std::move(distance);
  pending_ = std::move(pending);
}

}  // namespace auvloop::engine::turbulence
