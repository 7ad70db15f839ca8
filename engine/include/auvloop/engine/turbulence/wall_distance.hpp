// SPDX-License-Identifier: GPL-3.0-or-later
// Wall distance for the turbulence model (SST's blending functions F1 and F2, the wall
// treatment's y+): for every cell centre of every grid of a grid system, the distance to the
// nearest wall face of the whole system, so that the cells of a fin grid see the hull and the
// other fins as well as their own fin, and the background's cells every body; kept current as
// the grids move relative to each other, re-measuring only where a moved wall can be the nearest.
//   1. wall groups: per grid with wall faces, its wall faces split into triangles about each
//      face's point average (the decomposition of the face geometry), in the grid's own frame
//      (mesher::wall_triangles), in a CGAL AABB tree (geometry::TriangleDistance), and the
//      sphere (centre s_h, radius R_h) about their bounding box; built once, since a group moves
//      rigidly with its grid;
//   2. entries: per cell c of grid g and group h, either the exact distance from the centre x_c to
//      h's triangles, or a lower bound of it, both taken at the relative placement
//      T_hg = P_h^-1 P_g (P the grids' placements, grid frame -> body frame). The bound is the
//      sphere's, max(0, |T_hg x_c - s_h| - R_h), and after a motion also the old entry e less
//      the distance the centre moved relative to h, e - |T_hg x_c - T'_hg x_c| (T' the old
//      placement; a distance changes by at most the distance its point moves), whichever is
//      larger (each lowered by 1e-12 of the magnitudes it is made of, so that round-off never
//      lifts it above the exact value): a small turn leaves most entries close to their old,
//      exact values;
//   3. a cell's distance is its least entry, which must be exact: while the least entry (the
//      first of equal ones) is a bound, it is replaced by the exact distance. An exact value is
//      never below its bound, so a cell needs at most one query per group and the result is the
//      exact minimum over every group;
//   4. update(), after placements change: for each pair (g, h) whose T_hg changed since the
//      entries were taken (by more than 1e-12, the round-off of composing placements), the
//      entries of g's cells for h become the new bounds, then step 3 for every cell of g.
//      Unchanged pairs keep their entries, so a fin turning re-measures only the cells the fin may
//      now be nearest to, and a whole-system motion (every T unchanged) re-measures nothing.
// A composite mesh (the overset system merged into one mesh, fv::VehicleOverset and
// fv::MovingOverset) is taken component by component: component k's cells and the wall faces of
// those cells are a grid of their own, at their merged positions, whose placement is the
// component's axes relative to where it was merged (update(axes)), so the same steps apply.
// Every cell's entries depend on that cell alone, in parallel over cells (shared out dynamically:
// the queries cluster round a moved wall): the distances do not depend on the number of threads,
// and after any sequence of updates they are the ones a new WallDistances at the final placements
// computes (bit for bit, unless a relative placement moved by round-off only: then by round-off).
#pragma once

#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/state_archive.hpp"
#include "auvloop/geometry/triangle_distance.hpp"

namespace auvloop::engine::turbulence {

class WallDistances {
 public:
  // Steps 1-3 for `meshes` (one per grid of the system, at their grids' current placements). The
  // meshes must outlive this object; their grids' placements are read at every update().
  // Throws std::invalid_argument naming the grids when none of them has a wall patch face.
  explicit WallDistances(std::span<const fv::Mesh* const> meshes);
  // The composite mesh of an overset system, component k its cells [cell_offset[k],
  // cell_offset[k + 1]) (the last to the end), every component's axes the identity (as merged).
  // The mesh must outlive this object. Throws std::invalid_argument when the offsets do not
  // split the mesh or no component has a wall face.
  WallDistances(const fv::Mesh& composite, std::span<const int> cell_offset);

  // Per cell of meshes[grid] (m), or of component `grid` of a composite.
  [[nodiscard]] std::span<const double> of(int grid) const;
  // A composite's: per cell of the composite mesh (its components' in turn).
  [[nodiscard]] std::vector<double> composite() const;

  // What an update (or the construction) measured.
  struct Work {
    int pairs = 0;     // (grid, group) pairs whose relative placement changed
    long bounds = 0;   // entries replaced by a bound
    long queries = 0;  // exact distances measured (AABB-tree queries)
  };
  // Step 4 for the grids' current placements. `needed`, if given, has one mask per grid (one
  // entry per cell, nonzero: needed): step 3 runs for the needed cells only (the cells in the
  // equations; hole cells need no distance), every cell's entries stay valid bounds, and a cell
  // needed again later is measured then; the distance of a cell not needed is its last one.
  // Throws std::invalid_argument when the masks do not match the grids.
  Work update(std::span<const std::vector<char>> needed = {});
  // A composite's step 4: `axes` per component, its axes relative to where it was merged (the
  // identity for a component that has not moved: fv::MovingOverset::axes, or
  // fv::VehicleOverset::fin_axes and the body's identity); `needed` as above, one mask per
  // component. Throws std::invalid_argument on a wrong count, or when this is not a composite's.
  Work update(std::span<const Eigen::Isometry3d> axes,
              std::span<const std::vector<char>> needed = {});
  // The construction's work (every pair changed: one bound per entry).
  [[nodiscard]] const Work& initial_work() const { return initial_; }
  // Exact checkpoint of the entries, their placements and the distances. A cell not needed at an
  // update keeps its last distance, so those depend on the path of the placements; a restored
  // object continues as the saved one would (the placements are the caller's to restore).
  // load() throws std::runtime_error on a record of other grids, keeping the present state.
  void save(StateWriter& out) const;
  void load(StateReader& in);

 private:
  struct Group {
    int grid = 0;
    geometry::TriangleDistance walls;  // in the grid's own frame
    Eigen::Vector3d centre;            // of the bounding sphere, same frame
    double radius = 0;
  };
  struct Entry {
    double value = 0;
    bool exact = false;
  };
  void start();  // steps 2 and 3 for every part, after the groups
  Work refresh(bool all, std::span<const std::vector<char>> needed);
  void check_masks(std::span<const std::vector<char>> needed) const;
  // Grid g's placement: its mesh's grid's, or a composite's component axes.
  [[nodiscard]] const Eigen::Isometry3d& placement(std::size_t g) const;

  // Per grid: its mesh and its cells there (a composite's component: a range of one mesh).
  struct Part {
    const fv::Mesh* mesh = nullptr;
    int first = 0, cells = 0;
  };
  std::vector<Part> parts_;
  std::vector<Eigen::Isometry3d> axes_;  // a composite's; empty otherwise
  std::vector<Group> groups_;
  // Per grid g: T_hg per group h at which its entries were taken; entries cell-major, one per
  // group; the distances.
  std::vector<std::vector<Eigen::Isometry3d>> taken_at_;
  std::vector<std::vector<Entry>> entries_;
  std::vector<std::vector<double>> distance_;
  std::vector<bool> pending_;  // per grid: the last update skipped cells (a mask)
  Work initial_;
};

}  // namespace auvloop::engine::turbulence
