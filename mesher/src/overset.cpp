// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/overset.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/surface_query.hpp"
#include "auvloop/mesher/fin_grid.hpp"
#include "overset_search.hpp"

namespace auvloop::mesher {

using overset_detail::Box;
using overset_detail::convex_weights;
using overset_detail::GridData;
using overset_detail::kInf;
using overset_detail::KPoint;
using overset_detail::KSearch;
using overset_detail::locate_cell;
using overset_detail::nearest;
using overset_detail::nearest_first;
using overset_detail::prepare;
using overset_detail::violation;

const char* to_string(CellStatus s) {
  switch (s) {
    case CellStatus::active:
      return "active";
    case CellStatus::fringe:
      return "fringe";
    case CellStatus::hole:
      return "hole";
    case CellStatus::orphan:
      return "orphan";
  }
  return "unknown";
}

int GridAssembly::count(CellStatus s) const {
  return static_cast<int>(std::count(status.begin(), status.end(), s));
}

int GridAssembly::fallbacks() const {
  return static_cast<int>(std::count(fallback.begin(), fallback.end(), 1));
}

int GridAssembly::chains() const {
  return static_cast<int>(std::count(chained.begin(), chained.end(), 1));
}

namespace {
// How far outside its grid's wall (in edges of the hole test's triangulated surfaces) a fringe
// centre may lie and still take the nearest cell as a containing donor: the triangulation lies
// inside the exact body by at most its sagitta, edge^2 / (8 radius), 0.04 mm for 4 mm edges on the
// 50 mm hull radius at the fins.
constexpr double kWallSliver = 0.05;

// A stencil whose non-negative weights (convex_weights) miss linear exactness by less than this
// (relative to its extent) is taken without trying a larger one.
constexpr double kExactLinear = 1e-9;

// How deep inside the covering grid's active region (away from its holes and outer boundary) a
// cell of this size must lie to be covered, where the covering cell has this radius (largest
// centre-to-point distance). `overlap_cells` of the cell's own sizes, so that its fringe, which
// lies up to about two of them away, falls inside that region; and fringe_layers + 1.5 diameters
// of the covering cell, so that the covering grid's cells there are not its own fringe: those lie
// within fringe_layers face steps of its holes, and a step across a stretched cell (a hull wall
// cell is ten times longer than it is high) spans up to a diameter. Without this second term a
// small fin-grid cell was covered over a coarse hull cell next to the hull's hole round the fin,
// and its fringe fell into the hull's fringe (with it, the medium fallback donors at 0 deg fell
// from 2,600 to 110).
double cover_depth(const OversetSettings& s, double size, double covering_radius) {
  return s.overlap_cells * size + (s.fringe_layers + 1.5) * 2 * covering_radius;
}

// How much nearer another grid's wall must be for it to cover a cell of this size: the fringe
// layers plus one and a half sizes (so both grids keep an overlap band).
double cover_band(const OversetSettings& s, double size) {
  return (s.fringe_layers + 1.5) * size;
}
}  // namespace

struct OversetAssembler::Impl {
  void init(const std::vector<OversetComponent>& components, const std::vector<int>& fin_of);
  OversetSettings settings;
  std::vector<GridData> grids;  // GridSystem::grids() order
  std::vector<int> order;       // grid indices, highest priority first
  GridSystem* sys = nullptr;    // a vehicle's system (fins, update()); null for general systems
  // The bodies the grids fit, each in the frame of its grid (the hull in the body frame, a fin
  // undeflected in its fin grid's frame): built once, so moving a grid costs no new tree.
  struct Solid {
    std::unique_ptr<geometry::SurfaceQuery> query;
    Box local;
    int grid = -1;
  };
  std::vector<Solid> solids;
  bool planar = false;  // every grid one cell thick (2D): weights and sizes in the plane
  std::vector<std::vector<double>> depth;      // per grid: distance from holes and outer edge (m)
  std::vector<std::vector<double>> wall_dist;  // per grid: distance of cell centres from its wall
  std::vector<std::vector<char>> wall_hole;    // per grid: centre inside another solid
  // Per grid: how much farther a cell's own wall is than the cover band (0: no grid can cover
  // it; infinite for the background); fixed, since wall distances are taken in the grid's frame.
  std::vector<std::vector<double>> slack;
  // Per grid: whether it moved since the previous assembly (update(): the fin grids whose
  // deflection changed; every grid for a full assembly). Stencils between grids that did not move
  // are kept (keep()).
  std::vector<char> moved;
  std::unique_ptr<geometry::MyringProfile> profile;
  double cb_station = 0;
  // Scratch of the searches, one per thread: per grid, the stamp of the search that last
  // reached a cell (stencil_in), and the cell found by the last successful locate, the seed of
  // the next walk (receivers are visited in cell order, so consecutive ones are mostly
  // neighbours and a walk from there takes a step or two instead of a k-d tree search).
  struct Scratch {
    std::vector<std::vector<int>> marks;
    std::vector<int> stamps, found;
  };
  mutable tbb::enumerable_thread_specific<Scratch> scratch;
  [[nodiscard]] Scratch& local() const {
    Scratch& s = scratch.local();
    if (s.marks.size() != grids.size()) {
      s.marks.clear();
      for (const auto& d : grids) s.marks.emplace_back(static_cast<std::size_t>(d.grid->cells), 0);
      s.stamps.assign(grids.size(), 0);
      s.found.assign(grids.size(), -1);
    }
    return s;
  }
  [[nodiscard]] int last_found(int h) const { return local().found[static_cast<std::size_t>(h)]; }
  // A stamp no cell of grid h carries yet in this thread's marks (all cleared when the counter
  // would overflow: a long run stamps some hundred thousand times a step).
  static int next_stamp(Scratch& own, std::size_t h) {
    if (own.stamps[h] == std::numeric_limits<int>::max()) {
      std::fill(own.marks[h].begin(), own.marks[h].end(), 0);
      own.stamps[h] = 0;
    }
    return ++own.stamps[h];
  }
  // The cell of grid h containing xl (h's frame) by locate_cell from `seed`, its walks sharing the
  // thread's marks (a stamp of their own); remembered as the next seed.
  int find_cell(int h, const Eigen::Vector3d& xl, int seed) const {
    Scratch& own = local();
    const auto hu = static_cast<std::size_t>(h);
    const overset_detail::WalkMarks marks{own.marks[hu], next_stamp(own, hu)};
    const int loc = locate_cell(grids[hu], xl, seed, marks);
    if (loc >= 0) own.found[hu] = loc;
    return loc;
  }
  // The same from the thread's last cell found in h.
  int find_cell(int h, const Eigen::Vector3d& xl) const { return find_cell(h, xl, last_found(h)); }
  // A walk ends in the cell containing its point, but a point on a face between two cells may end
  // in either, depending on the seed: the seeds are forgotten at the start of every block of
  // cells (for_blocks) and every serial stage, so that where a walk ends depends on the cells
  // alone, never on the thread that ran them or on what it ran before.
  void forget_seeds() const {
    auto& found = local().found;
    std::fill(found.begin(), found.end(), -1);
  }
  // fn(i) for i in [0, n) on TBB's pool, in blocks of kBlock indices fixed by n alone (the
  // simple partitioner halves a range until it is at most a block), each block in index order
  // on one thread with the seeds forgotten first. A stage whose fn(i) writes only what belongs to
  // index i thus gives the same result for any number of threads.
  static constexpr int kBlock = 64;
  template <class F>
  void for_blocks(std::size_t n, F&& fn) const {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, kBlock),
        [&](const tbb::blocked_range<std::size_t>& r) {
          forget_seeds();
          for (std::size_t i = r.begin(); i != r.end(); ++i) fn(i);
        },
        tbb::simple_partitioner());
  }

  // Steps 1-3 for the given cells of every grid (all others keep their statuses).
  // The depths are measured afresh over the whole of every component grid whose wall holes
  // changed (`all_depths`: every one): a wall hole that moved changes them far beyond the cells
  // whose statuses can change (up to the deepest a covered cell must lie, several of the largest
  // hull cells). They depend on nothing else (the outer boundary is fixed in the grid's frame).
  void run(Assembly& a, const std::vector<std::vector<int>>& cells, bool all_depths) {
    for (int g : order)
      if (mark_wall_holes(g, cells[static_cast<std::size_t>(g)],
                          a.grids[static_cast<std::size_t>(g)].status) ||
          all_depths)
        if (grids[static_cast<std::size_t>(g)].priority > 0) measure_depth(g);
    for (int g : order)
      cover(g, cells[static_cast<std::size_t>(g)], a.grids[static_cast<std::size_t>(g)].status);
    // Fringe layers are redrawn on the cells given and `fringe_layers` rings around them: a
    // ring cell may have been fringe only because of a cell that changed.
    for (int g : order) {
      const auto gu = static_cast<std::size_t>(g);
      const auto& d = grids[gu];
      std::vector<char> in(a.grids[gu].status.size(), 0);
      std::vector<int> region = cells[gu];
      for (int c : region) in[static_cast<std::size_t>(c)] = 1;
      std::size_t begin = 0;
      for (int l = 0; l < settings.fringe_layers; ++l) {
        const std::size_t end = region.size();
        for (std::size_t i = begin; i < end; ++i)
          d.each_neighbour(region[i], [&](int n) {
            if (!in[static_cast<std::size_t>(n)]) {
              in[static_cast<std::size_t>(n)] = 1;
              region.push_back(n);
            }
          });
        begin = end;
      }
      add_fringe(g, region, a.grids[gu].status);
    }
  }

  // Distance of a body-frame point from the hull, radial beside it (which exceeds the distance to
  // the sloping tail by up to 1 / cos of its slope) and to the nearer end face's rim beyond it.
  [[nodiscard]] double hull_gap(const Eigen::Vector3d& x) const {
    const double station = cb_station - x.x(), rho = std::hypot(x.y(), x.z());
    const double length = profile->length();
    if (station < 0 || station > length) {
      const double end = station < 0 ? 0.0 : length;
      return std::hypot(station - end, std::max(0.0, rho - profile->radius(end)));
    }
    return rho - profile->radius(station);
  }

  [[nodiscard]] Eigen::Vector3d body(int g, int c) const {
    const auto& d = grids[static_cast<std::size_t>(g)];
    return d.grid->placement * d.geo.cell_centre[static_cast<std::size_t>(c)];
  }
  [[nodiscard]] Box body_box(int g) const {
    const auto& d = grids[static_cast<std::size_t>(g)];
    Box b;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d corner((k & 1) ? d.local_box.hi.x() : d.local_box.lo.x(),
                                   (k & 2) ? d.local_box.hi.y() : d.local_box.lo.y(),
                                   (k & 4) ? d.local_box.hi.z() : d.local_box.lo.z());
      b.add(d.grid->placement * corner);
    }
    return b;
  }

  // Body-frame box of the solid of grid g at its present placement.
  [[nodiscard]] Box solid_body_box(int g) const {
    const auto& solid = solids[static_cast<std::size_t>(grids[static_cast<std::size_t>(g)].solid)];
    const auto& local = solid.local;
    const auto& placement = grids[static_cast<std::size_t>(g)].grid->placement;
    Box b;
    for (int k = 0; k < 8; ++k)
      b.add(placement * Eigen::Vector3d((k & 1) ? local.hi.x() : local.lo.x(),
                                        (k & 2) ? local.hi.y() : local.lo.y(),
                                        (k & 4) ? local.hi.z() : local.lo.z()));
    return b;
  }

  // Fins turn rigidly with their grids: their surfaces are built once, undeflected, and queried
  // in the fin grid's frame, so moving a fin costs no new triangulation or tree.
  void place_fins(const std::vector<double>& deflections) {
    set_fin_deflections(*sys, deflections);
  }

  // Inside a solid other than the one grid g fits: a body-fitted grid is not cut by its own body
  // (its wall is that body's surface, and the centres of thin wall cells over a curved wall may
  // lie inside the finer triangulation by the chord sagitta). The grid whose solid it is, -1 if
  // none.
  [[nodiscard]] int in_body(const Eigen::Vector3d& x, int g) const {
    for (const auto& solid : solids) {
      if (solid.grid == g) continue;
      const Eigen::Vector3d xl =
          grids[static_cast<std::size_t>(solid.grid)].grid->placement.inverse() * x;
      if (solid.local.contains(xl) && solid.query->inside(xl)) return solid.grid;
    }
    return -1;
  }

  // Step 1 for the cells given: wall holes (centre inside a solid other than the grid's own).
  // True if any cell's wall-hole mark changed.
  bool mark_wall_holes(int g, const std::vector<int>& cells, std::vector<CellStatus>& st) {
    auto& holes = wall_hole[static_cast<std::size_t>(g)];
    bool changed = false;
    for (int c : cells) {
      const auto cu = static_cast<std::size_t>(c);
      const auto hole = static_cast<char>(in_body(body(g, c), g) + 1);  // 0: not a wall hole
      changed = changed || hole != holes[cu];
      holes[cu] = hole;
      st[cu] = hole ? CellStatus::hole : CellStatus::active;
    }
    return changed;
  }

  // Step 2: a cell is covered by another component grid whose wall is nearer (by the fringe
  // layers plus one and a half of this cell's sizes, so that both grids keep an overlap band where
  // each has active cells for the other's fringe), when it also lies deep enough inside that grid
  // (away from its outer boundary and wall holes: cover_depth). The background has no wall: it is
  // covered wherever a component grid reaches deep enough.
  void cover(int g, const std::vector<int>& cells, std::vector<CellStatus>& st) const {
    const auto& d = grids[static_cast<std::size_t>(g)];
    const auto& own_wall = wall_dist[static_cast<std::size_t>(g)];
    std::vector<int> others;
    std::vector<Box> boxes;
    for (int h : order) {
      if (h == g || grids[static_cast<std::size_t>(h)].priority == 0) continue;  // not background
      others.push_back(h);
      boxes.push_back(body_box(h));
    }
    for_blocks(cells.size(), [&](std::size_t i) {  // each cell's status its own
      const int c = cells[i];
      const auto cu = static_cast<std::size_t>(c);
      if (st[cu] != CellStatus::active) return;
      const Eigen::Vector3d x = body(g, c);
      const double band = cover_band(settings, d.size[cu]);
      for (std::size_t k = 0; k < others.size(); ++k) {
        if (!boxes[k].contains(x)) continue;
        const auto hu = static_cast<std::size_t>(others[k]);
        const auto& hd = grids[hu];
        const int loc = find_cell(others[k], hd.grid->placement.inverse() * x);
        if (loc < 0) continue;
        const auto lu = static_cast<std::size_t>(loc);
        if (wall_hole[hu][lu] || depth[hu][lu] < cover_depth(settings, d.size[cu], hd.radius[lu]))
          continue;
        if (wall_dist[hu][lu] + band < own_wall[cu]) {
          st[cu] = CellStatus::hole;
          break;
        }
      }
    });
  }

  // Step 3: fringe = the non-hole cells at most `fringe_layers` face steps from a hole, counting
  // a cell on the outer (overset) boundary as one step. Decided for the cells given from the holes
  // within reach of them, so that a partial update draws the same layers as a full assembly.
  void add_fringe(int g, const std::vector<int>& cells, std::vector<CellStatus>& st) const {
    const auto& d = grids[static_cast<std::size_t>(g)];
    const int layers = settings.fringe_layers;
    std::vector<int> level(st.size(), -1), region = cells;  // -1: not in the region
    for (int c : region) level[static_cast<std::size_t>(c)] = layers + 1;
    std::size_t begin = 0;
    for (int l = 0; l < layers; ++l) {  // the holes that can reach the cells lie this far out
      const std::size_t end = region.size();
      for (std::size_t i = begin; i < end; ++i)
        d.each_neighbour(region[i], [&](int n) {
          if (level[static_cast<std::size_t>(n)] < 0) {
            level[static_cast<std::size_t>(n)] = layers + 1;
            region.push_back(n);
          }
        });
      begin = end;
    }
    std::vector<int> queue;
    for (int c : region) {
      const auto cu = static_cast<std::size_t>(c);
      if (st[cu] == CellStatus::hole) {
        level[cu] = 0;
        queue.push_back(c);
      } else if (d.outer[cu]) {
        level[cu] = 1;
      }
    }
    for (int c : region)
      if (level[static_cast<std::size_t>(c)] == 1) queue.push_back(c);
    for (std::size_t i = 0; i < queue.size(); ++i) {  // breadth first: levels in order
      const int c = queue[i];
      const int next = level[static_cast<std::size_t>(c)] + 1;
      if (next > layers) continue;
      d.each_neighbour(c, [&](int n) {
        const auto nu = static_cast<std::size_t>(n);
        if (level[nu] > next && st[nu] != CellStatus::hole) {
          level[nu] = next;
          queue.push_back(n);
        }
      });
    }
    for (int c : cells) {
      const auto cu = static_cast<std::size_t>(c);
      if (st[cu] == CellStatus::hole) continue;
      st[cu] = level[cu] <= layers ? CellStatus::fringe : CellStatus::active;
    }
  }

  // Distance of each cell centre from the grid's wall holes and outer-boundary cells, along paths
  // of centre-to-centre steps (Dijkstra).
  void measure_depth(int g) {
    const auto& d = grids[static_cast<std::size_t>(g)];
    const auto& holes = wall_hole[static_cast<std::size_t>(g)];
    auto& dist = depth[static_cast<std::size_t>(g)];
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (int c = 0; c < d.grid->cells; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      dist[cu] = holes[cu] || d.outer[cu] ? 0.0 : kInf;
      if (dist[cu] == 0.0) queue.emplace(0.0, c);
    }
    while (!queue.empty()) {
      const double dc = queue.top().first;  // (not a structured binding: captured below)
      const int c = queue.top().second;
      queue.pop();
      if (dc > dist[static_cast<std::size_t>(c)]) continue;
      d.each_neighbour(c, [&](int n) {
        const auto nu = static_cast<std::size_t>(n);
        const double dn =
            dc + (d.geo.cell_centre[nu] - d.geo.cell_centre[static_cast<std::size_t>(c)]).norm();
        if (dn < dist[nu]) {
          dist[nu] = dn;
          queue.emplace(dn, n);
        }
      });
    }
  }

  // Stencil in grid h round the located cell `loc` for the point xl (h's frame). An active `loc`
  // that contains xl (`containing`): loc and its active face neighbours, grown ring by ring (at
  // most three) while the centres do not span 3D (at the edge of an active region they may all lie
  // in one plane). A `loc` that is not active (a fallback donor: the point lies in a hole or fringe
  // cell of h, e.g. a fin-grid cell straddling the hull wall at the fin root): the active cells
  // within `fallback_rings` face steps of it, through any cells. The weights reproduce linear
  // fields either way; the fallback extrapolates over at most those few cells. With `relay`, the
  // cells it marks (fringe cells with containing stencils of their own) count as active for a
  // containing stencil: a chained stencil (chain()).
  bool stencil_in(int h, const Eigen::Vector3d& xl, int loc, bool containing,
                  const std::vector<CellStatus>& hs, std::vector<int>& stencil,
                  std::vector<double>& w, const std::vector<char>* relay = nullptr) const {
    const auto& hd = grids[static_cast<std::size_t>(h)];
    // Cells reached are stamped (mark[cell] == stamp) instead of searched for in a list.
    Scratch& own = local();
    auto& mark = own.marks[static_cast<std::size_t>(h)];
    const int stamp = next_stamp(own, static_cast<std::size_t>(h));
    std::vector<int> reached{loc};
    mark[static_cast<std::size_t>(loc)] = stamp;
    // The weights are non-negative (convex_weights: no value beyond its donors', so that no
    // Schwarz loop between two grids' fringes can grow). A candidate that reproduces linear
    // fields (its centres surround xl) is kept; otherwise the rings grow, and the candidate
    // nearest to linear is taken at the end.
    std::vector<int> best;
    std::vector<double> best_w;
    double best_error = std::numeric_limits<double>::infinity();
    const auto consider = [&](const std::vector<int>& candidate) {
      std::vector<Eigen::Vector3d> xs;
      for (int c : candidate) xs.push_back(hd.geo.cell_centre[static_cast<std::size_t>(c)]);
      const double error = convex_weights(xs, xl, w, planar);
      if (error < 0) return false;
      if (error < best_error) {
        best_error = error;
        best = candidate;
        best_w = w;
      }
      return error <= kExactLinear;
    };
    const auto settle = [&] {
      if (best.empty()) return false;
      stencil = best;
      w = best_w;
      return true;
    };
    stencil.clear();
    if (containing) stencil.push_back(loc);
    const int rings = containing ? 3 : settings.fallback_rings;
    std::size_t begin = 0;
    for (int ring = 0; ring < rings; ++ring) {
      const std::size_t end = reached.size();
      for (std::size_t i = begin; i < end; ++i)
        hd.each_neighbour(reached[i], [&](int n) {
          const auto nu = static_cast<std::size_t>(n);
          if (mark[nu] == stamp) return;
          const bool act = hs[nu] == CellStatus::active || (relay != nullptr && (*relay)[nu]);
          if (containing && !act) return;  // a containing donor's rings grow through active cells
          mark[nu] = stamp;
          reached.push_back(n);
          if (act) stencil.push_back(n);
        });
      begin = end;
      if (!containing && ring + 1 < rings && stencil.size() < 8) continue;
      if (!containing) nearest_first(hd, xl, stencil);
      if (consider(stencil)) return true;
    }
    if (containing) return settle();
    // Last resort, when the rings stay inside a thick hole (or gave only poor stencils): the
    // nearest active cell centres.
    KSearch search(*hd.tree, KPoint(xl.x(), xl.y(), xl.z()), 64);
    stencil.clear();
    for (const auto& hit : search) {
      const int cell = boost::get<1>(hit.first);
      if (hs[static_cast<std::size_t>(cell)] != CellStatus::active) continue;
      stencil.push_back(cell);
      if (stencil.size() == 12) break;
    }
    consider(stencil);
    return settle();
  }

  // Donor stencil of one fringe cell; false when no grid offers an active donor. First a cell of
  // another grid that contains the centre and is active, in priority order; failing that (and
  // only `with_fallback`), the nearest active cells round the containing cell in the grid where
  // they extrapolate least (a lower-quality donor).
  bool find_donor(int g, int c, int seed_grid, int seed_cell, const Assembly& a,
                  std::vector<int>& cells_out, std::vector<double>& w_out, int& donor_grid,
                  int& donor_cell, bool& fallback, bool with_fallback) const {
    const Eigen::Vector3d x = body(g, c);
    // (grid, cell) containing x, any status; or, when x lies in no cell of a grid but within its
    // box widened by the receiver's fringe depth (between a wall and its triangulation, just
    // past a corner of its outer boundary), the cell whose centre is nearest.
    const double reach = settings.fringe_layers *
                         grids[static_cast<std::size_t>(g)].size[static_cast<std::size_t>(c)];
    std::vector<std::pair<int, int>> located;  // the cells that are not active donors
    for (int h : order) {
      if (h == g) continue;
      const auto& hd = grids[static_cast<std::size_t>(h)];
      const auto& hs = a.grids[static_cast<std::size_t>(h)].status;
      const Eigen::Vector3d xl = hd.grid->placement.inverse() * x;
      int loc = find_cell(h, xl, h == seed_grid ? seed_cell : last_found(h));
      if (loc >= 0 && hs[static_cast<std::size_t>(loc)] == CellStatus::active &&
          stencil_in(h, xl, loc, true, hs, cells_out, w_out)) {
        donor_grid = h;
        donor_cell = loc;
        fallback = false;
        return true;
      }
      if (loc < 0 && hd.local_box.contains(xl, reach)) {
        loc = nearest(hd, xl);
        // Just outside a body-fitted grid's inscribed wall, inside the exact body but outside the
        // coarser triangulation of the hole test: the nearest cell contains the centre but for
        // that sliver, and is a containing donor if active.
        if (hs[static_cast<std::size_t>(loc)] == CellStatus::active &&
            violation(hd, loc, xl) < kWallSliver * settings.surface_edge &&
            stencil_in(h, xl, loc, true, hs, cells_out, w_out)) {
          donor_grid = h;
          donor_cell = loc;
          fallback = false;
          return true;
        }
      }
      if (loc >= 0) located.emplace_back(h, loc);
    }
    if (!with_fallback) return false;
    // Among the grids' fallback stencils, the one that extrapolates least: the smallest distance
    // from x to its nearest centre, in that cell's size (a donor-quality rule; the priority order
    // decides ties).
    double best = kInf;
    std::vector<int> cells;
    std::vector<double> w;
    for (const auto& [h, loc] : located) {
      const auto& hd = grids[static_cast<std::size_t>(h)];
      const auto& hs = a.grids[static_cast<std::size_t>(h)].status;
      const Eigen::Vector3d xl = hd.grid->placement.inverse() * x;
      if (!stencil_in(h, xl, loc, false, hs, cells, w)) continue;
      const auto first = static_cast<std::size_t>(cells.front());  // nearest first
      const double extrapolation = (hd.geo.cell_centre[first] - xl).norm() / hd.size[first];
      if (extrapolation >= best) continue;
      best = extrapolation;
      cells_out = cells;
      w_out = w;
      donor_grid = h;
      donor_cell = cells.front();
    }
    fallback = best < kInf;
    return fallback;
  }

  // Assembly::warnings: whether a body's grid cuts or covers anything at all, and per grid that
  // a solid cuts, whether any of its holes is a covered cell.
  void warn(Assembly& a) const {
    for (const auto& solid : solids) {
      int holes = 0;
      for (std::size_t g = 0; g < grids.size(); ++g)
        if (static_cast<int>(g) != solid.grid) holes += a.grids[g].count(CellStatus::hole);
      if (holes == 0)
        a.warnings.push_back(fmt::format(
            "overset grid {}: no cell of another grid lies inside its body or is covered by it: "
            "the other grids' flow passes through the body (their cells are too coarse to see it)",
            solid.grid));
    }
    for (std::size_t g = 0; g < grids.size(); ++g) {
      // Cut by the solid of a grid that outranks it (that grid should cover it round its body; a
      // fin grid reaching into the hull below its root is cut by the hull's solid by design).
      const auto& holes = wall_hole[g];
      const auto& st = a.grids[g].status;
      int cut = 0, covered = 0, by = -1;
      for (std::size_t c = 0; c < st.size(); ++c) {
        const int k = holes[c] - 1;
        if (k >= 0 && grids[static_cast<std::size_t>(k)].priority > grids[g].priority) {
          ++cut;
          by = k;
        }
        covered += st[c] == CellStatus::hole && holes[c] == 0;
      }
      if (cut == 0 || covered > 0) continue;
      a.warnings.push_back(fmt::format(
          "overset grid {}: the body of grid {} cuts {} of its cells but no other grid covers "
          "any: it resolves the body on its own cells; a cell is covered only {} of its sizes "
          "inside the covering grid's active region, so refine grid {} near the body or let the "
          "body's grid reach further",
          g, by, cut, settings.overlap_cells, g));
    }
  }

  // 4.-5. Donors for every fringe cell, then chains. With a previous assembly, a stencil is kept
  // (keep()) or refitted (refit()) where it can be; otherwise the search starts from the previous
  // donor cell. A receiver without an active containing cell is a fallback receiver; its fallback
  // stencil is searched only if chain() finds no chained stencil for it (chaining reads no
  // fallback stencil, only which receivers are fallbacks), since it costs tens of times more than
  // a containing one.
  void connect(Assembly& a, const Assembly* previous,
               const std::vector<std::vector<char>>* redo) const {
    for (auto& ga : a.grids)  // an orphan is a fringe cell still looking for donors
      std::replace(ga.status.begin(), ga.status.end(), CellStatus::orphan, CellStatus::fringe);
    std::vector<std::vector<int>> pending(grids.size());
    for (std::size_t g = 0; g < grids.size(); ++g) {
      auto& ga = a.grids[g];
      const auto n = static_cast<std::size_t>(grids[g].grid->cells);
      ga.donor_grid.assign(n, -1);
      ga.donor_cell.assign(n, -1);
      ga.fallback.assign(n, 0);
      ga.chained.assign(n, 0);
      ga.stencil_offsets.assign(1, 0);
      ga.stencil_grids.clear();
      ga.stencil_cells.clear();
      ga.stencil_weights.clear();
      // Each fringe cell's donors in parallel (keep, refit or search: each reads the statuses
      // and the previous assembly only), then the stencil arrays in cell order.
      std::vector<int> fringe;
      for (std::size_t c = 0; c < n; ++c)
        if (ga.status[c] == CellStatus::fringe) fringe.push_back(static_cast<int>(c));
      std::vector<Donors> donors(fringe.size());
      for_blocks(fringe.size(), [&](std::size_t i) {
        const auto c = static_cast<std::size_t>(fringe[i]);
        Donors& d = donors[i];
        if (previous && keep(a, *previous, *redo, g, c)) {
          d.kind = Donors::kept;
          return;
        }
        if (previous != nullptr &&
            refit(a, previous->grids[g], static_cast<int>(g), static_cast<int>(c), d.cells, d.w)) {
          d.kind = Donors::refitted;
          return;
        }
        int seed_grid = -1, seed_cell = -1;
        if (previous != nullptr) {
          seed_grid = previous->grids[g].donor_grid[c];
          seed_cell = previous->grids[g].donor_cell[c];
        }
        bool fb = false;
        d.kind = find_donor(static_cast<int>(g), static_cast<int>(c), seed_grid, seed_cell, a,
                            d.cells, d.w, d.grid, d.cell, fb, false)
                     ? Donors::searched
                     : Donors::pending;
      });
      const auto append = [&](int dg, const Donors& d) {
        ga.stencil_grids.insert(ga.stencil_grids.end(), d.cells.size(), dg);
        ga.stencil_cells.insert(ga.stencil_cells.end(), d.cells.begin(), d.cells.end());
        ga.stencil_weights.insert(ga.stencil_weights.end(), d.w.begin(), d.w.end());
      };
      std::size_t next = 0;
      for (std::size_t c = 0; c < n; ++c) {
        if (ga.status[c] == CellStatus::fringe) {
          const Donors& d = donors[next++];
          switch (d.kind) {
            case Donors::refitted:
              ga.donor_grid[c] = previous->grids[g].donor_grid[c];
              ga.donor_cell[c] = previous->grids[g].donor_cell[c];
              ga.fallback[c] = previous->grids[g].fallback[c];
              append(ga.donor_grid[c], d);
              break;
            case Donors::searched:
              ga.donor_grid[c] = d.grid;
              ga.donor_cell[c] = d.cell;
              append(d.grid, d);
              break;
            case Donors::pending:
              ga.fallback[c] = 1;  // its stencil (empty for now) after chain()
              pending[g].push_back(static_cast<int>(c));
              break;
            case Donors::kept: {  // copy the previous stencil
              const auto& pg = previous->grids[g];
              ga.donor_grid[c] = pg.donor_grid[c];
              ga.donor_cell[c] = pg.donor_cell[c];
              ga.fallback[c] = pg.fallback[c];
              const auto b = static_cast<std::size_t>(pg.stencil_offsets[c]);
              const auto e = static_cast<std::size_t>(pg.stencil_offsets[c + 1]);
              const auto range = [&](const auto& v) {
                return std::pair(v.begin() + static_cast<std::ptrdiff_t>(b),
                                 v.begin() + static_cast<std::ptrdiff_t>(e));
              };
              const auto [g0, g1] = range(pg.stencil_grids);
              const auto [c0, c1] = range(pg.stencil_cells);
              const auto [w0, w1] = range(pg.stencil_weights);
              ga.stencil_grids.insert(ga.stencil_grids.end(), g0, g1);
              ga.stencil_cells.insert(ga.stencil_cells.end(), c0, c1);
              ga.stencil_weights.insert(ga.stencil_weights.end(), w0, w1);
              break;
            }
          }
        }
        ga.stencil_offsets.push_back(static_cast<int>(ga.stencil_cells.size()));
      }
    }
    chain(a);
    // The fallback stencils of the receivers left unchained (in parallel, as above); orphans
    // where there is none.
    for (std::size_t g = 0; g < grids.size(); ++g) {
      auto& ga = a.grids[g];
      std::vector<int> unchained;
      for (int c : pending[g])
        if (!ga.chained[static_cast<std::size_t>(c)]) unchained.push_back(c);
      std::vector<Donors> donors(unchained.size());
      for_blocks(unchained.size(), [&](std::size_t i) {
        Donors& d = donors[i];
        bool fb = false;
        d.kind = find_donor(static_cast<int>(g), unchained[i], -1, -1, a, d.cells, d.w, d.grid,
                            d.cell, fb, true)
                     ? Donors::searched
                     : Donors::pending;
      });
      std::map<int, std::vector<Entry>> fallbacks;
      for (std::size_t i = 0; i < unchained.size(); ++i) {
        const auto cu = static_cast<std::size_t>(unchained[i]);
        const Donors& d = donors[i];
        if (d.kind == Donors::pending) {
          ga.status[cu] = CellStatus::orphan;
          ga.fallback[cu] = 0;
          continue;
        }
        ga.donor_grid[cu] = d.grid;
        ga.donor_cell[cu] = d.cell;
        auto& entries = fallbacks[unchained[i]];
        for (std::size_t k = 0; k < d.cells.size(); ++k)
          entries.push_back({d.grid, d.cells[k], d.w[k]});
      }
      if (!fallbacks.empty()) replace_stencils(ga, fallbacks, false);
    }
  }

  // What connect() found for one fringe cell: its previous stencil kept, refitted (new weights,
  // the previous donor), a new one searched (grid, cell, stencil), or none yet (pending).
  struct Donors {
    enum Kind : char { kept, refitted, searched, pending } kind = pending;
    int grid = -1, cell = -1;
    std::vector<int> cells;
    std::vector<double> w;
  };

  // One donor of a chained stencil: grid, cell, weight.
  struct Entry {
    int grid, cell;
    double weight;
  };

  // Fallback receivers whose centre lies in a fringe cell of another grid with a containing or
  // chained stencil of its own (a relay) get a chained stencil instead: the containing stencil in
  // that grid, through active cells and relays, with each relay replaced by its own stencil.
  // Every donor is then active, the weights still reproduce linear fields (each level does), and
  // nothing extrapolates. Each pass lets the chains reach one relay further into a region where
  // two grids are both fringe (the fin root gap, docs/mesher.md); in its middle the receivers
  // depend on each other, and solve_knots composes their stencils through a small linear solve.
  void chain(Assembly& a) const {
    for (int pass = 0; pass < settings.chain_passes; ++pass)
      if (!chain_once(a)) break;
    solve_knots(a);
  }

  // A fallback receiver's containing stencil through relays (knot_row): weights on active cells
  // (`known`, keyed by grid and cell) and on knot receivers (`knot`, by index; solve_knots).
  struct KnotRow {
    std::map<std::pair<int, int>, double> known;
    std::map<int, double> knot;
    bool ok = false;
    int grid = -1, cell = -1;  // the containing cell (a relay or knot receiver)
  };

  // The fallback receivers the chains cannot reach: where two grids are both fringe, each one's
  // containing cell is another's receiver (a knot). Each gets its containing stencil through
  // active cells, relays and the other knot receivers; their values then solve
  // (I - W_kk) v_k = W_ka v_a, and the rows of X = (I - W_kk)^-1 W_ka are stencils over active
  // cells only. They reproduce linear fields, since the exact values solve the same system, and
  // they interpolate (no stencil extrapolates). A receiver without such a stencil, or a singular
  // system, keeps its fallback.
  void solve_knots(Assembly& a) const {
    std::vector<std::pair<int, int>> knots;
    std::vector<std::vector<int>> index(grids.size());
    std::vector<std::vector<char>> usable(grids.size());
    for (std::size_t g = 0; g < grids.size(); ++g) {
      const auto& ga = a.grids[g];
      index[g].assign(ga.status.size(), -1);
      usable[g].assign(ga.status.size(), 0);
      for (std::size_t c = 0; c < ga.status.size(); ++c) {
        if (ga.status[c] != CellStatus::fringe) continue;
        usable[g][c] = 1;  // a relay or a knot receiver
        if (!ga.fallback[c]) continue;
        index[g][c] = static_cast<int>(knots.size());
        knots.emplace_back(static_cast<int>(g), static_cast<int>(c));
      }
    }
    if (knots.empty()) return;
    std::vector<KnotRow> rows(knots.size());
    for_blocks(knots.size(), [&](std::size_t k) {
      rows[k] = knot_row(a, usable, index, knots[k].first, knots[k].second);
    });
    for (bool changed = true; changed;) {  // drop rows that lean on receivers without rows
      changed = false;
      for (auto& row : rows)
        if (row.ok)
          for (const auto& [j, w] : row.knot)
            if (!rows[static_cast<std::size_t>(j)].ok) {
              row.ok = false;
              changed = true;
              break;
            }
    }
    std::vector<int> unknown(knots.size(), -1);  // row index among the solved ones
    std::vector<std::size_t> solved;
    for (std::size_t k = 0; k < knots.size(); ++k)
      if (rows[k].ok) {
        unknown[k] = static_cast<int>(solved.size());
        solved.push_back(k);
      }
    if (solved.empty()) return;
    std::map<std::pair<int, int>, int> column;  // active donor -> column of W_ka
    for (std::size_t k : solved)
      for (const auto& [donor, w] : rows[k].known) column.emplace(donor, 0);
    std::vector<std::pair<int, int>> donors;
    for (auto& [donor, col] : column) {
      col = static_cast<int>(donors.size());
      donors.push_back(donor);
    }
    const auto m = static_cast<Eigen::Index>(solved.size());
    std::vector<Eigen::Triplet<double>> b, r;
    for (Eigen::Index i = 0; i < m; ++i) {
      const KnotRow& row = rows[solved[static_cast<std::size_t>(i)]];
      b.emplace_back(i, i, 1.0);
      for (const auto& [j, w] : row.knot)
        b.emplace_back(i, unknown[static_cast<std::size_t>(j)], -w);
      for (const auto& [donor, w] : row.known) r.emplace_back(i, column.at(donor), w);
    }
    Eigen::SparseMatrix<double> B(m, m), R(m, static_cast<Eigen::Index>(donors.size()));
    B.setFromTriplets(b.begin(), b.end());
    R.setFromTriplets(r.begin(), r.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(B);
    if (lu.info() != Eigen::Success) return;
    const Eigen::MatrixXd X = lu.solve(Eigen::MatrixXd(R));
    if (lu.info() != Eigen::Success || !X.allFinite()) return;
    std::vector<std::map<int, std::vector<Entry>>> stencils(grids.size());
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto [g, c] = knots[solved[static_cast<std::size_t>(i)]];
      const KnotRow& row = rows[solved[static_cast<std::size_t>(i)]];
      a.grids[static_cast<std::size_t>(g)].donor_grid[static_cast<std::size_t>(c)] = row.grid;
      a.grids[static_cast<std::size_t>(g)].donor_cell[static_cast<std::size_t>(c)] = row.cell;
      auto& entries = stencils[static_cast<std::size_t>(g)][c];
      for (Eigen::Index j = 0; j < X.cols(); ++j)
        if (X(i, j) != 0.0)
          entries.push_back({donors[static_cast<std::size_t>(j)].first,
                             donors[static_cast<std::size_t>(j)].second, X(i, j)});
    }
    for (std::size_t g = 0; g < grids.size(); ++g)
      if (!stencils[g].empty()) replace_stencils(a.grids[g], stencils[g]);
  }

  // The containing stencil of fallback receiver c of grid g in the first other grid (priority
  // order) whose cell containing it is `usable` (a relay, or for solve_knots another knot
  // receiver), grown through active and usable cells: a relay's weight is spread over its own
  // donors, a knot receiver's (index >= 0) kept as an unknown.
  KnotRow knot_row(const Assembly& a, const std::vector<std::vector<char>>& usable,
                   const std::vector<std::vector<int>>& index, int g, int c) const {
    KnotRow row;
    const Eigen::Vector3d x = body(g, c);
    for (int h : order) {
      if (h == g) continue;
      const auto hu = static_cast<std::size_t>(h);
      const auto& hd = grids[hu];
      const auto& ha = a.grids[hu];
      const Eigen::Vector3d xl = hd.grid->placement.inverse() * x;
      const int loc = find_cell(h, xl);
      std::vector<int> cells;
      std::vector<double> w;
      if (loc < 0 || !usable[hu][static_cast<std::size_t>(loc)] ||
          !stencil_in(h, xl, loc, true, ha.status, cells, w, &usable[hu]))
        continue;
      for (std::size_t i = 0; i < cells.size(); ++i) {
        const auto cu = static_cast<std::size_t>(cells[i]);
        if (ha.status[cu] == CellStatus::active) {
          row.known[{h, cells[i]}] += w[i];
        } else if (index[hu][cu] >= 0) {
          row.knot[index[hu][cu]] += w[i];
        } else {
          for (int k = ha.stencil_offsets[cu]; k < ha.stencil_offsets[cu + 1]; ++k) {
            const auto ku = static_cast<std::size_t>(k);
            row.known[{ha.stencil_grids[ku], ha.stencil_cells[ku]}] +=
                w[i] * ha.stencil_weights[ku];
          }
        }
      }
      row.ok = true;
      row.grid = h;
      row.cell = loc;
      return row;
    }
    return row;
  }

  // One pass of chain(): true if it chained any receiver.
  bool chain_once(Assembly& a) const {
    std::vector<std::vector<char>> relay(grids.size());
    for (std::size_t h = 0; h < grids.size(); ++h) {
      const auto& ha = a.grids[h];
      relay[h].assign(ha.status.size(), 0);
      for (std::size_t c = 0; c < ha.status.size(); ++c)
        relay[h][c] = ha.status[c] == CellStatus::fringe && !ha.fallback[c] ? 1 : 0;
    }
    std::vector<std::vector<int>> no_knots(grids.size());
    for (std::size_t h = 0; h < grids.size(); ++h) no_knots[h].assign(relay[h].size(), -1);
    std::vector<std::map<int, std::vector<Entry>>> chained(grids.size());
    for (std::size_t g = 0; g < grids.size(); ++g) {
      // The rows in parallel: each reads the pass's relays and their stencils, which change only
      // after the pass (replace_stencils below).
      std::vector<int> receivers;
      for (std::size_t c = 0; c < a.grids[g].status.size(); ++c)
        if (a.grids[g].status[c] == CellStatus::fringe && a.grids[g].fallback[c])
          receivers.push_back(static_cast<int>(c));
      std::vector<KnotRow> rows(receivers.size());
      for_blocks(receivers.size(), [&](std::size_t i) {
        rows[i] = knot_row(a, relay, no_knots, static_cast<int>(g), receivers[i]);
      });
      for (std::size_t i = 0; i < receivers.size(); ++i) {
        const KnotRow& row = rows[i];
        if (!row.ok) continue;
        const auto c = static_cast<std::size_t>(receivers[i]);
        a.grids[g].donor_grid[c] = row.grid;
        a.grids[g].donor_cell[c] = row.cell;
        auto& entries = chained[g][receivers[i]];
        for (const auto& [donor, w] : row.known) entries.push_back({donor.first, donor.second, w});
      }
    }
    bool any = false;
    for (std::size_t g = 0; g < grids.size(); ++g)
      if (!chained[g].empty()) {
        replace_stencils(a.grids[g], chained[g]);
        any = true;
      }
    return any;
  }

  // Rebuilds a grid's stencil arrays with the stencils given in place of the receivers' present
  // ones (empty for pending fallbacks): chained ones, or else fallback ones.
  static void replace_stencils(GridAssembly& ga, const std::map<int, std::vector<Entry>>& chained,
                               bool are_chained = true) {
    std::vector<int> offsets{0}, grids_out, cells_out;
    std::vector<double> weights_out;
    offsets.reserve(ga.stencil_offsets.size());
    grids_out.reserve(ga.stencil_grids.size());
    cells_out.reserve(ga.stencil_cells.size());
    weights_out.reserve(ga.stencil_weights.size());
    auto next = chained.begin();  // the receivers in cell order, as the loop meets them
    for (std::size_t c = 0; c + 1 < ga.stencil_offsets.size(); ++c) {
      const auto it =
          next != chained.end() && next->first == static_cast<int>(c) ? next++ : chained.end();
      if (it == chained.end()) {
        for (int k = ga.stencil_offsets[c]; k < ga.stencil_offsets[c + 1]; ++k) {
          const auto ku = static_cast<std::size_t>(k);
          grids_out.push_back(ga.stencil_grids[ku]);
          cells_out.push_back(ga.stencil_cells[ku]);
          weights_out.push_back(ga.stencil_weights[ku]);
        }
      } else {
        for (const Entry& e : it->second) {
          grids_out.push_back(e.grid);
          cells_out.push_back(e.cell);
          weights_out.push_back(e.weight);
        }
        ga.fallback[c] = are_chained ? 0 : 1;
        ga.chained[c] = are_chained ? 1 : 0;
      }
      offsets.push_back(static_cast<int>(cells_out.size()));
    }
    ga.stencil_offsets = std::move(offsets);
    ga.stencil_grids = std::move(grids_out);
    ga.stencil_cells = std::move(cells_out);
    ga.stencil_weights = std::move(weights_out);
  }

  // After a small move, the previous stencil of a receiver is refitted (new weights, same cells)
  // when its donor cell still contains the centre, its cells are all still active, and no grid of
  // higher priority now offers an active cell containing the centre: the donor a full search would
  // choose is then the same cell. A fallback stencil is refitted while no grid offers an active
  // containing cell and its first cell stays within the fallback reach. Either only while the
  // new weights reproduce linear fields (kExactLinear).
  bool refit(const Assembly& a, const GridAssembly& pg, int g, int c, std::vector<int>& cells,
             std::vector<double>& w) const {
    const auto cu = static_cast<std::size_t>(c);
    if (pg.status[cu] != CellStatus::fringe || pg.donor_grid[cu] < 0 || pg.chained[cu])
      return false;
    const bool fallback = pg.fallback[cu] != 0;
    const int dg = pg.donor_grid[cu];
    const auto& hd = grids[static_cast<std::size_t>(dg)];
    const auto& hs = a.grids[static_cast<std::size_t>(dg)].status;
    const Eigen::Vector3d x = body(g, c);
    const Eigen::Vector3d xl = hd.grid->placement.inverse() * x;
    const int donor = pg.donor_cell[cu];
    const double size = hd.size[static_cast<std::size_t>(donor)];
    if (fallback ? (hd.geo.cell_centre[static_cast<std::size_t>(donor)] - xl).norm() >
                       settings.fallback_rings * size
                 : violation(hd, donor, xl) > 1e-12 * size)
      return false;
    cells.assign(pg.stencil_cells.begin() + pg.stencil_offsets[cu],
                 pg.stencil_cells.begin() + pg.stencil_offsets[cu + 1]);
    for (int s : cells)
      if (hs[static_cast<std::size_t>(s)] != CellStatus::active) return false;
    if (outranked(a, g, c, dg, fallback)) return false;
    std::vector<Eigen::Vector3d> xs;
    for (int s : cells) xs.push_back(hd.geo.cell_centre[static_cast<std::size_t>(s)]);
    // No longer exact for linear fields at the new place: search again (stencil_in).
    const double error = convex_weights(xs, xl, w, planar);
    return error >= 0 && error <= kExactLinear;
  }

  // A stencil between two grids that did not move is kept as it is (weights included) when its
  // cells are all still active and, for a receiver within reach of the moved fins (`redo`), no
  // grid that outranks its donor grid now offers an active cell containing it.
  [[nodiscard]] bool keep(const Assembly& a, const Assembly& previous,
                          const std::vector<std::vector<char>>& redo, std::size_t g,
                          std::size_t c) const {
    const auto& pg = previous.grids[g];
    if (pg.status[c] != CellStatus::fringe || pg.chained[c]) return false;  // chained: redone
    if (moved[g]) return false;                                             // the receiver moved
    const int dg = pg.donor_grid[c];
    if (dg < 0 || moved[static_cast<std::size_t>(dg)]) return false;  // the donor moved
    const auto& ds = a.grids[static_cast<std::size_t>(dg)].status;
    for (int k = pg.stencil_offsets[c]; k < pg.stencil_offsets[c + 1]; ++k)
      if (ds[static_cast<std::size_t>(pg.stencil_cells[static_cast<std::size_t>(k)])] !=
          CellStatus::active)
        return false;
    return !redo[g][c] ||
           !outranked(a, static_cast<int>(g), static_cast<int>(c), dg, pg.fallback[c] != 0);
  }

  // Whether a grid before `dg` in priority order (any grid, for a fallback donor) now has an
  // active cell containing the centre of receiver c of grid g.
  [[nodiscard]] bool outranked(const Assembly& a, int g, int c, int dg, bool fallback) const {
    const Eigen::Vector3d x = body(g, c);
    for (int h : order) {
      if (h == dg && !fallback) break;
      if (h == g) continue;
      const auto& od = grids[static_cast<std::size_t>(h)];
      const int loc = find_cell(h, od.grid->placement.inverse() * x);
      if (loc >= 0 && a.grids[static_cast<std::size_t>(h)].status[static_cast<std::size_t>(loc)] ==
                          CellStatus::active)
        return true;
    }
    return false;
  }
};

namespace {
Box bounding_box(const geometry::SurfaceMesh& mesh) {
  Box b;
  for (const auto& v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    b.add(Eigen::Vector3d(p.x(), p.y(), p.z()));
  }
  return b;
}

bool one_cell_thick(const Grid& g) {
  return std::any_of(g.patches.begin(), g.patches.end(),
                     [](const Patch& p) { return p.type == PatchType::empty && p.size > 0; });
}
}  // namespace

// Every grid with its solid (fin: the vehicle's fin index, -1 for the others), the priority order
// (stable: equal priorities keep the given order), and the fixed per-cell data.
void OversetAssembler::Impl::init(const std::vector<OversetComponent>& components,
                                  const std::vector<int>& fin_of) {
  planar = std::all_of(components.begin(), components.end(),
                       [](const OversetComponent& c) { return one_cell_thick(*c.grid); });
  for (std::size_t g = 0; g < components.size(); ++g) {
    const auto& comp = components[g];
    int solid = -1;
    if (comp.solid != nullptr) {
      solid = static_cast<int>(solids.size());
      solids.push_back({std::make_unique<geometry::SurfaceQuery>(*comp.solid),
                        bounding_box(*comp.solid), static_cast<int>(g)});
    }
    grids.push_back(prepare(*comp.grid, comp.priority, fin_of[g], solid, planar));
  }
  for (std::size_t g = 0; g < grids.size(); ++g) order.push_back(static_cast<int>(g));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return grids[static_cast<std::size_t>(a)].priority >
           grids[static_cast<std::size_t>(b)].priority;
  });
  // Wall distances in each grid's own frame: fixed, since a grid moves with its solid.
  for (const auto& d : grids) {
    const auto n = static_cast<std::size_t>(d.grid->cells);
    std::vector<double> w(n, kInf);
    if (d.solid >= 0) {
      const auto& q = *solids[static_cast<std::size_t>(d.solid)].query;
      for (std::size_t c = 0; c < n; ++c) w[c] = std::abs(q.signed_distance(d.geo.cell_centre[c]));
    }
    std::vector<double> s(n);
    for (std::size_t c = 0; c < n; ++c)
      s[c] = std::max(0.0, w[c] - cover_band(settings, d.size[c]));
    slack.push_back(std::move(s));
    wall_dist.push_back(std::move(w));
    wall_hole.emplace_back(n, 0);
    depth.emplace_back(n, kInf);
  }
}

OversetAssembler::OversetAssembler(GridSystem& system, const geometry::Vehicle& vehicle,
                                   OversetSettings settings)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  m.sys = &system;
  m.settings = settings;
  const auto hull_mesh = geometry::hull_surface(geometry::MyringProfile(vehicle.hull),
                                                vehicle.mass.cb_station, {settings.surface_edge});
  std::vector<geometry::SurfaceMesh> fin_meshes;
  for (const auto& fin : system.fin_geometry)
    fin_meshes.push_back(geometry::fin_surface(fin, 0.0, {settings.surface_edge}));
  // Priorities: fins, then hull, then background (the finest, nearest-wall grid wins).
  std::vector<OversetComponent> components{{&system.hull, 1, &hull_mesh}};
  std::vector<int> fin_of{-1};
  for (std::size_t i = 0; i < system.fins.size(); ++i) {
    components.push_back({&system.fins[i], 2, &fin_meshes[i]});
    fin_of.push_back(static_cast<int>(i));
  }
  components.push_back({&system.background, 0, nullptr});
  fin_of.push_back(-1);
  m.init(components, fin_of);
  m.profile = std::make_unique<geometry::MyringProfile>(vehicle.hull);
  m.cb_station = vehicle.mass.cb_station;
}

OversetAssembler::OversetAssembler(const std::vector<OversetComponent>& components,
                                   OversetSettings settings)
    : impl_(std::make_unique<Impl>()) {
  if (components.size() < 2)
    throw std::invalid_argument(fmt::format(
        "OversetAssembler: an overset system needs at least two grids, got {}", components.size()));
  for (const auto& c : components)
    if (c.grid == nullptr || c.grid->cells == 0)
      throw std::invalid_argument("OversetAssembler: a component without cells");
  impl_->settings = settings;
  impl_->init(components, std::vector<int>(components.size(), -1));
}

OversetAssembler::OversetAssembler(OversetAssembler&&) noexcept = default;
OversetAssembler::~OversetAssembler() = default;

Eigen::Vector3d OversetAssembler::centre(int grid, int cell) const {
  return impl_->body(grid, cell);
}

int OversetAssembler::locate(int grid, const Eigen::Vector3d& x) const {
  const auto& d = impl_->grids.at(static_cast<std::size_t>(grid));
  return locate_cell(d, d.grid->placement.inverse() * x, -1);
}

Assembly OversetAssembler::assemble(const std::vector<double>& deflections) {
  if (impl_->sys == nullptr)
    throw std::logic_error("OversetAssembler: fin deflections given to a system without fins");
  impl_->place_fins(deflections);
  Assembly a = assemble();
  a.fin_deflections = deflections;
  return a;
}

Assembly OversetAssembler::assemble() {
  const auto t0 = std::chrono::steady_clock::now();
  auto& m = *impl_;
  Assembly a;
  if (m.sys != nullptr) a.fin_deflections = m.sys->fin_deflections;
  a.grids.resize(m.grids.size());
  std::vector<std::vector<int>> all(m.grids.size());
  for (std::size_t g = 0; g < m.grids.size(); ++g) {
    const int n = m.grids[g].grid->cells;
    a.grids[g].status.assign(static_cast<std::size_t>(n), CellStatus::active);
    for (int c = 0; c < n; ++c) all[g].push_back(c);
    a.cells_visited += n;
  }
  m.moved.assign(m.grids.size(), 1);
  m.run(a, all, true);
  m.connect(a, nullptr, nullptr);
  m.warn(a);
  a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return a;
}

Assembly OversetAssembler::update(const Assembly& previous,
                                  const std::vector<double>& deflections) {
  if (impl_->sys == nullptr)
    throw std::logic_error("OversetAssembler::update: only a vehicle's system turns its fins");
  const auto t0 = std::chrono::steady_clock::now();
  auto& m = *impl_;
  // The fins that turn (all of them after an assembly without deflections), and the region they
  // sweep: their grids' boxes, and the boxes of the fin solids, before and after the move. A fin
  // that keeps its angle sweeps nothing (its swept box stays empty).
  const auto& before = previous.fin_deflections;
  m.moved.assign(m.grids.size(), 0);
  std::vector<Box> swept, swept_solid;
  for (std::size_t g = 0; g < m.grids.size(); ++g) {
    const int fin = m.grids[g].fin;
    if (fin < 0) continue;
    const auto f = static_cast<std::size_t>(fin);
    m.moved[g] = before.size() != deflections.size() || before[f] != deflections[f] ? 1 : 0;
    swept.emplace_back();
    swept_solid.emplace_back();
    if (!m.moved[g]) continue;
    swept.back() = m.body_box(static_cast<int>(g));
    swept_solid.back() = m.solid_body_box(static_cast<int>(g));
  }
  m.place_fins(deflections);
  for (std::size_t g = 0; g < m.grids.size(); ++g)
    if (m.moved[g]) {
      const auto k = static_cast<std::size_t>(m.grids[g].fin);
      const Box b = m.body_box(static_cast<int>(g));
      swept[k].add(b.lo);
      swept[k].add(b.hi);
      const Box s = m.solid_body_box(static_cast<int>(g));
      swept_solid[k].add(s.lo);
      swept_solid[k].add(s.hi);
    }
  Assembly a = previous;
  a.fin_deflections = deflections;
  a.cells_visited = 0;
  const double reach_cells = m.settings.overlap_cells + m.settings.fringe_layers + 2;
  // The largest centre-to-vertex distance of the cells that can cover a hull or fin cell: a point
  // lies at most this far from the centre of the covering cell containing it, where that cell's
  // wall distance is taken.
  double fin_cell_radius = 0;
  for (const auto& d : m.grids)
    if (d.fin >= 0) fin_cell_radius = std::max(fin_cell_radius, d.largest_radius);
  // The hull cells that can contain a fin-grid cell's centre lie within their radius of a swept
  // fin-grid box: only their radii matter (the hull's outer cells are ten times larger).
  double hull_cell_radius = 0;
  const auto& hull = m.grids[0];  // grid 0 is the hull
  for (int c = 0; c < hull.grid->cells; ++c) {
    const double r = hull.radius[static_cast<std::size_t>(c)];
    const Eigen::Vector3d x = m.body(0, c);
    if (std::any_of(swept.begin(), swept.end(), [&](const Box& b) { return b.contains(x, r); }))
      hull_cell_radius = std::max(hull_cell_radius, r);
  }
  // Which cells are re-examined (`cells`: their statuses may change) and which kept stencils are
  // re-checked (`redo`). Each test is a necessary condition for a cell's status to change
  // (test_overset compares the statuses with full assemblies; the depths are measured over whole
  // grids, run()):
  //  - every change lies within reach of a swept fin-grid box (overlap depth plus fringe layers
  //    and a margin, in the cell's own size): a moved grid's wall holes and the cells it covers
  //    lie in its box;
  //  - a hull or fin cell becomes or stops being a hole only inside a fin solid or where a fin
  //    grid covers it, which needs the fin's wall nearer than its own by the cover band: within
  //    its slack, plus the covering cell's radius, of the fin solid. Most fin-grid cells and the
  //    hull's near-wall cells have no slack, so only the swept solids' boxes widened by the reach
  //    matter to them, not the whole fin-grid boxes. The background has no wall (infinite slack);
  //  - a fin-grid cell turns with its fin, so it can also change near the hull: inside it, or
  //    covered by the hull grid within its slack (plus the hull cells' radius) of the hull wall.
  //    The gap is measured radially at the cell's station, which exceeds the distance to the
  //    sloping tail by up to 1 / cos of its slope (about 10 % at 25 deg); only the reach makes up
  //    for that, a margin rather than a bound.
  // A kept stencil of a hull or background receiver within reach of a swept fin-grid box is
  // re-checked (`redo`) even where the receiver's status cannot change: a fin grid's active cells
  // may now contain it and outrank its donor grid.
  // The background has no wall and its cells are large: a fin grid covers one only where the
  // fin grid is deeper than overlap_cells of its sizes, which its deepest cell (twice that, as a
  // margin for the move) bounds; otherwise only the fin solids' wall holes and the fringe round
  // them can change it.
  double fin_depth = 0;
  for (std::size_t g = 0; g < m.grids.size(); ++g)
    if (m.grids[g].fin >= 0)
      for (double v : m.depth[g]) fin_depth = std::max(fin_depth, v);
  std::vector<std::vector<int>> cells(m.grids.size());
  std::vector<std::vector<char>> redo(m.grids.size());
  for (std::size_t g = 0; g < m.grids.size(); ++g) {
    const auto& d = m.grids[g];
    const auto n = static_cast<std::size_t>(d.grid->cells);
    redo[g].assign(n, 0);
    std::vector<char> near_cell(n, 0);
    const auto& slack = m.slack[g];
    m.for_blocks(n, [&](std::size_t cu) {  // each cell's marks its own
      const Eigen::Vector3d x = m.body(static_cast<int>(g), static_cast<int>(cu));
      const bool coverable =
          d.priority > 0 || m.settings.overlap_cells * d.size[cu] < 2 * fin_depth;
      const double reach = (coverable ? reach_cells : m.settings.fringe_layers + 2) * d.size[cu];
      const double fin_cover_reach = slack[cu] > 0 && coverable ? slack[cu] + fin_cell_radius : 0.0;
      bool near = false, in_swept_box = false;
      for (std::size_t k = 0; k < swept.size(); ++k) {
        if (static_cast<int>(k) == d.fin || !swept[k].contains(x, reach)) continue;
        in_swept_box = true;
        near = near || swept_solid[k].contains(x, reach + fin_cover_reach);
      }
      if (!m.moved[g] && in_swept_box) redo[g][cu] = 1;
      if (m.moved[g] && !near) {
        const double hull_cover_reach = slack[cu] > 0 ? slack[cu] + hull_cell_radius : 0.0;
        near = m.hull_gap(x) < reach + hull_cover_reach;
      }
      if (near) {
        near_cell[cu] = 1;
        redo[g][cu] = 1;
      }
    });
    for (std::size_t c = 0; c < n; ++c)
      if (near_cell[c]) cells[g].push_back(static_cast<int>(c));
    a.cells_visited += static_cast<int>(cells[g].size());
  }
  m.run(a, cells, false);
  m.connect(a, &previous, &redo);
  m.warn(a);
  a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return a;
}

}  // namespace auvloop::mesher
