// SPDX-License-Identifier: GPL-3.0-or-later
// Overset assembly, the search stage (docs/mesher.md): what the assembly knows of one component
// grid, and how it finds things in it.
//   1. prepare: geometry in the grid's own frame, cell-to-face addressing, cell sizes and radii,
//      the cells on the outer (overset) boundary, a k-d tree of cell centres;
//   2. locate_cell: the cell containing a point, by a walk across the face the point lies furthest
//      beyond, from a seed or the nearest centre (k-d tree), with fallbacks for warped cells;
//   3. linear_weights: interpolation weights that reproduce linear fields (in the plane for
//      planar systems of one-cell-thick grids), the minimum weighted norm solution;
//      convex_weights: the same made non-negative (a convex combination) where the point lies in
//      the convex hull of the centres, the nearest to linear of the non-negative ones elsewhere.
// Internal to the mesher (mesher/src).
#pragma once

#include <limits>
#include <memory>
#include <span>
#include <vector>

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>
#include <Eigen/Core>
#include <boost/tuple/tuple.hpp>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher::overset_detail {

using SK = CGAL::Simple_cartesian<double>;
using KPoint = SK::Point_3;
using PointAndIndex = boost::tuple<KPoint, int>;
using KTraits =
    CGAL::Search_traits_adapter<PointAndIndex, CGAL::Nth_of_tuple_property_map<0, PointAndIndex>,
                                CGAL::Search_traits_3<SK>>;
using KSearch = CGAL::Orthogonal_k_neighbor_search<KTraits>;
using KTree = KSearch::Tree;

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = Eigen::Vector3d::Constant(-kInf);
  void add(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  [[nodiscard]] bool contains(const Eigen::Vector3d& p, double margin = 0) const {
    return (p.array() >= lo.array() - margin).all() && (p.array() <= hi.array() + margin).all();
  }
};

// One component grid with what the assembly needs: geometry in its own frame, cell-to-face
// addressing, cell sizes, a k-d tree of cell centres, and its place in the priority order.
struct GridData {
  const Grid* grid = nullptr;
  GridGeometry geo;
  std::vector<int> cell_face_offsets, cell_faces;
  // Per cell_faces entry: the face's plane as seen from that cell, {outward unit normal, its
  // offset n . face centre}, next to the cell's other faces (a walk step reads one cell's planes
  // from consecutive memory).
  std::vector<Eigen::Vector4d> planes;
  std::vector<double> size;  // cube root of the cell volume (3D), sqrt(volume / thickness) (planar)
  std::vector<char> outer;   // owns a face of an overset patch
  std::vector<int> ids;
  std::vector<KPoint> centres;
  std::unique_ptr<KTree> tree;
  Box local_box;
  std::vector<double> radius;  // per cell: largest distance from its centre to one of its points
  double largest_radius = 0;   // over all cells
  int priority = 0;
  int fin = -1;    // index of the fin it belongs to (vehicle systems), -1 for the others
  int solid = -1;  // index of the solid the grid fits (its wall), -1 for none

  [[nodiscard]] int other(int face, int cell) const {
    const auto f = static_cast<std::size_t>(face);
    if (face >= grid->internal_faces()) return -1;
    return grid->owner[f] == cell ? grid->neighbour[f] : grid->owner[f];
  }
  // Signed distance of x beyond entry k's face plane, along the cell's outward normal.
  [[nodiscard]] double beyond(int k, const Eigen::Vector3d& x) const {
    const Eigen::Vector4d& plane = planes[static_cast<std::size_t>(k)];
    return plane.head<3>().dot(x) - plane[3];
  }
  template <class F>
  void each_face(int cell, F&& fn) const {
    const auto c = static_cast<std::size_t>(cell);
    for (int k = cell_face_offsets[c]; k < cell_face_offsets[c + 1]; ++k)
      fn(cell_faces[static_cast<std::size_t>(k)]);
  }
  template <class F>
  void each_neighbour(int cell, F&& fn) const {
    each_face(cell, [&](int f) {
      const int n = other(f, cell);
      if (n >= 0) fn(n);
    });
  }
};

// Step 1. `planar`: a one-cell-thick grid of a planar system, whose cell size is measured in the
// plane (sqrt(volume / thickness)); its centres all lie in one plane z = const.
GridData prepare(const Grid& g, int priority, int fin, int solid, bool planar);
// How far x lies outside a cell: the largest distance beyond any of its face planes (<= 0 inside).
double violation(const GridData& d, int cell, const Eigen::Vector3d& x);
// The cells one locate_cell has walked through (mark[c] == stamp): a walk's step depends on its
// cell and point alone, so a walk that reaches a cell an earlier walk of the same locate passed
// through, or its own path again (a circle), would fail as that one did, and stops there. `mark`
// holds one value per cell of the grid; `stamp` is new for each locate.
struct WalkMarks {
  std::span<int> mark;
  int stamp = 0;
};
// Step 2: the cell containing x (grid frame), starting from `seed` if >= 0; -1: x is in no cell.
// Without marks every walk runs to its end.
int locate_cell(const GridData& d, const Eigen::Vector3d& x, int seed, WalkMarks marks = {});
// The cell whose centre is nearest to x (grid frame).
int nearest(const GridData& d, const Eigen::Vector3d& x);
// Keeps the (at most) 16 cells whose centres are nearest to x, nearest first.
void nearest_first(const GridData& d, const Eigen::Vector3d& x, std::vector<int>& cells);
// Step 3: weights w (one per centre) with sum w = 1 and sum w (x_i - x) = 0 (its x and y
// components only when `planar`); false when the centres do not span the space (3D or the plane).
bool linear_weights(const std::vector<Eigen::Vector3d>& xs, const Eigen::Vector3d& x,
                    std::vector<double>& w, bool planar);
// The most negative weight (summed over a stencil) that step 3 keeps: an interpolation then
// amplifies by at most sum |w| = 1 + 2 * 0.1 in the max norm. Measured on the REMUS coarse
// system (docs/mesher.md, "Donors"): the explicit Schwarz iteration of the Laplacian between its
// grids contracts by 0.957 a pass with 0, 0.960 with 0.1, 0.975 with 0.25 and grew by 1.12 with
// the earlier bound sum |w| <= 10; the 2D validations' stencils all lie within 0.1 (with 0, the
// schaefer-turek-2d1-overset estimates moved by 1e-4 and out of the marginally met intervals).
inline constexpr double kNegativeWeight = 0.1;

// Step 3 as the assembly uses it: weights with sum w = 1 bounded by their donors' values (up to
// kNegativeWeight), so that an explicit Schwarz iteration between two grids cannot grow:
//   a. linear_weights when their negative ones sum to at most kNegativeWeight;
//   b. else, when x lies in the centres' convex hull, the weights of a. with the bounds w >= 0:
//      the least sum w_i^2 / D_i of the non-negative weights exact for linear fields (a primal
//      active-set method from the feasible point that Lawson and Hanson's NNLS finds for
//      sum w_i = 1, sum w_i (x_i - x) = 0);
//   c. else (x beyond the hull: a cell between a wall and its donors' centres) the same NNLS
//      with the sum weighted 1e3 times the offsets, normalised to sum w = 1: exact for
//      constants, the smallest offset sum w_i (x_i - x) of the non-negative combinations.
// Returns |sum w_i (x_i - x)| relative to the stencil's extent (0 up to round-off when linear
// fields are reproduced), or a negative value when the centres do not span the space.
double convex_weights(const std::vector<Eigen::Vector3d>& xs, const Eigen::Vector3d& x,
                      std::vector<double>& w, bool planar);

}  // namespace auvloop::mesher::overset_detail
