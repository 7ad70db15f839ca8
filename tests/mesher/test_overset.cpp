// SPDX-License-Identifier: GPL-3.0-or-later
// Overset assembly of the REMUS 100 grid system over the fin range: no orphans, donors active,
// weights summing to one with at most 0.1 of negative weight (0.22 for a stencil composed of
// two), interpolating linear fields to round-off wherever the fringe centre lies among its
// donors' centres, the fluid covered.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/overset.hpp"

using namespace auvloop;
using namespace auvloop::mesher;

namespace {
const geometry::Vehicle& remus() {
  static const geometry::Vehicle v = geometry::preset_vehicle("remus100");
  return v;
}

struct Check {
  int fallbacks = 0, chained = 0;
  int orphans = 0, fringe = 0, bad_donor_status = 0, largest_stencil = 0, donors = 0;
  double worst_sum = 0;  // in units of the round-off bound of each sum
  // Stencils that miss a linear field by more than round-off (the fringe centre beyond its
  // donors' centres, between a wall and the donor grid's first centres: convex_weights c.), and
  // the worst of them relative to the field's change over the stencil (|grad f| times the largest
  // donor distance).
  int inexact = 0;
  double worst_inexact = 0;
  // The largest negative weight of a stencil (summed), of the plain and the composed (chained or
  // fallback) ones.
  double worst_negative = 0, worst_negative_composed = 0;
  // Largest distance from a fringe centre to its nearest stencil centre, in that cell's size
  // (cube root of its volume): how far a fallback stencil extrapolates.
  double farthest_fallback = 0;
};

// Every fringe stencil: active donor cells (in the grid each entry names: a chained stencil spans
// several), weights summing to one, and the linear field f = 3 + 2 x - 5 y + 7 z (body frame)
// at the fringe centre: reproduced to round-off, or (inexact) within a share of its change over
// the stencil.
std::vector<GridGeometry> geometries(const GridSystem& sys) {
  std::vector<GridGeometry> out;
  for (const Grid* g : sys.grids()) out.push_back(compute_geometry(*g));
  return out;
}

Check check(const OversetAssembler& asmb, const Assembly& a, const std::vector<GridGeometry>& geo) {
  Check r;
  const Eigen::Vector3d gradient(2, -5, 7);
  const auto f = [&](const Eigen::Vector3d& x) { return 3 + gradient.dot(x); };
  for (std::size_t g = 0; g < a.grids.size(); ++g) {
    const auto& ga = a.grids[g];
    r.orphans += ga.count(CellStatus::orphan);
    r.chained += ga.chains();
    for (std::size_t c = 0; c < ga.status.size(); ++c) {
      if (ga.status[c] != CellStatus::fringe) continue;
      ++r.fringe;
      double sum = 0, value = 0, sum_abs = 0, value_abs = 0, negative = 0, extent = 0;
      const Eigen::Vector3d xc = asmb.centre(static_cast<int>(g), static_cast<int>(c));
      for (int k = ga.stencil_offsets[c]; k < ga.stencil_offsets[c + 1]; ++k) {
        const auto ku = static_cast<std::size_t>(k);
        const int dg = ga.stencil_grids[ku], d = ga.stencil_cells[ku];
        if (a.grids[static_cast<std::size_t>(dg)].status[static_cast<std::size_t>(d)] !=
            CellStatus::active)
          ++r.bad_donor_status;
        const double w = ga.stencil_weights[ku], fd = f(asmb.centre(dg, d));
        sum += w;
        sum_abs += std::abs(w);
        value += w * fd;
        value_abs += std::abs(w * fd);
        negative += std::max(0.0, -w);
        extent = std::max(extent, (asmb.centre(dg, d) - xc).norm());
      }
      const double exact = f(xc);
      if (ga.chained[c] != 0 || ga.fallback[c] != 0)
        r.worst_negative_composed = std::max(r.worst_negative_composed, negative);
      else
        r.worst_negative = std::max(r.worst_negative, negative);
      r.largest_stencil =
          std::max(r.largest_stencil, ga.stencil_offsets[c + 1] - ga.stencil_offsets[c]);
      r.donors += ga.stencil_offsets[c + 1] - ga.stencil_offsets[c];
      if (ga.fallback[c]) {
        ++r.fallbacks;
        double nearest = std::numeric_limits<double>::infinity();
        for (int k = ga.stencil_offsets[c]; k < ga.stencil_offsets[c + 1]; ++k) {
          const int dg = ga.stencil_grids[static_cast<std::size_t>(k)];
          const int d = ga.stencil_cells[static_cast<std::size_t>(k)];
          const double size =
              std::cbrt(geo[static_cast<std::size_t>(dg)].cell_volume[static_cast<std::size_t>(d)]);
          nearest = std::min(
              nearest,
              (asmb.centre(dg, d) - asmb.centre(static_cast<int>(g), static_cast<int>(c))).norm() /
                  size);
        }
        r.farthest_fallback = std::max(r.farthest_fallback, nearest);
      }
      // Round-off: the weights solve a 4 x 4 system built from n stencil cells and are summed
      // again, so Wilkinson's n^2 eps times the sum of the magnitudes, at least 1024 eps (n = 32);
      // a chained stencil composes two such levels, and its n counts the donors of both.
      const double eps = std::numeric_limits<double>::epsilon();
      const double n = ga.stencil_offsets[c + 1] - ga.stencil_offsets[c];
      const double bound = std::max(1024.0, n * n) * eps;
      r.worst_sum = std::max(r.worst_sum, std::abs(sum - 1) / (bound * sum_abs));
      if (std::abs(value - exact) > bound * value_abs) {
        ++r.inexact;
        r.worst_inexact =
            std::max(r.worst_inexact, std::abs(value - exact) / (gradient.norm() * extent));
      }
    }
  }
  return r;
}

// What every assembly must give (docs/mesher.md, "Donors"): no orphan, active donors, weights
// summing to one to round-off, an interpolation that amplifies by at most 1 + 2 * 0.1 (1.2^2 for
// a stencil composed of two: a chain through another fringe cell's stencil), exact for linear
// fields but for the few fringe centres beyond their donors' centres, and those within a share
// of the field's change over the stencil. Measured on the coarse sweep (session 18): 4.2 % to
// 7.2 % inexact, the worst 0.24 of the change; composed negative weight at most 0.155.
void expect_valid(const Check& r, const std::string& label) {
  EXPECT_EQ(r.orphans, 0) << label;
  EXPECT_EQ(r.bad_donor_status, 0) << label;
  EXPECT_LE(r.worst_sum, 1.0) << label;
  EXPECT_LE(r.worst_negative, 0.1 + 1e-12) << label;
  EXPECT_LE(r.worst_negative_composed, 0.22 + 1e-12) << label;
  EXPECT_LT(r.inexact, r.fringe / 12) << label;
  EXPECT_LT(r.worst_inexact, 0.3) << label;
}
}  // namespace

// Deflections -35 .. 35 deg in 5 deg steps, all fins together: valid stencils (expect_valid)
// and their sizes printed (the implicit coupling's matrix entries grow with them). No fringe cell
// takes a fallback (extrapolating) stencil: every one has a containing cell, active or a relay
// (docs/mesher.md).
void sweep(const char* preset, double max_fallback_share) {
  const MeshSettings settings = mesh_preset(preset, remus());
  GridSystem sys = build_grid_system(remus(), settings);
  OversetAssembler asmb(sys, remus());
  const auto geo = geometries(sys);
  for (int deg = -35; deg <= 35; deg += 5) {
    const double d = deg * std::numbers::pi / 180;
    const Assembly a = asmb.assemble(std::vector<double>(sys.fins.size(), d));
    const Check r = check(asmb, a, geo);
    std::printf(
        "%s %+3d deg: %d fringe (%d chained, %d with fallback donors, nearest donor centre at "
        "most %.2f cell sizes away), %d orphans, |sum w - 1| at most %.2f of its round-off bound, "
        "%d not exact for linear fields (worst %.3f of the change over the stencil), negative "
        "weight at most %.3f (%.3f composed), stencils of %.1f cells on average, at most %d "
        "(%.2f s)\n",
        preset, deg, r.fringe, r.chained, r.fallbacks, r.farthest_fallback, r.orphans, r.worst_sum,
        r.inexact, r.worst_inexact, r.worst_negative, r.worst_negative_composed,
        static_cast<double>(r.donors) / r.fringe, r.largest_stencil, a.seconds);
    EXPECT_GT(r.fringe, 0) << deg;
    EXPECT_LE(r.fallbacks, max_fallback_share * r.fringe) << deg;
    expect_valid(r, std::to_string(deg) + " deg");
  }
}

// Cells whose statuses differ between two assemblies (the first few are printed).
int differing_statuses(const OversetAssembler& asmb, const Assembly& full, const Assembly& inc) {
  int differ = 0;
  for (std::size_t g = 0; g < full.grids.size(); ++g)
    for (std::size_t c = 0; c < full.grids[g].status.size(); ++c)
      if (full.grids[g].status[c] != inc.grids[g].status[c]) {
        if (differ < 8) {
          const auto x = asmb.centre(static_cast<int>(g), static_cast<int>(c));
          std::printf("  differ: grid %zu cell %zu full %s inc %s at (%.4f %.4f %.4f)\n", g, c,
                      to_string(full.grids[g].status[c]), to_string(inc.grids[g].status[c]), x.x(),
                      x.y(), x.z());
        }
        ++differ;
      }
  return differ;
}

// An incremental update from the fins' present angles to `next` against a full assembly at
// `next`: the same statuses, fewer than half the cells examined, and valid stencils. The
// update runs first, so that the full assembly leaves the fins (and the assembler's per-cell
// state) at `next` for the following update.
Assembly update_and_compare(OversetAssembler& asmb, const Assembly& previous,
                            const std::vector<double>& next, const std::vector<GridGeometry>& geo,
                            const char* label) {
  Assembly inc = asmb.update(previous, next);
  const Assembly full = asmb.assemble(next);
  const int differ = differing_statuses(asmb, full, inc);
  std::printf(
      "%s: full assembly %d cells examined in %.3f s; update %d cells in %.3f s; %d statuses "
      "differ\n",
      label, full.cells_visited, full.seconds, inc.cells_visited, inc.seconds, differ);
  EXPECT_EQ(differ, 0) << label;
  EXPECT_LT(inc.cells_visited, full.cells_visited / 2) << label;
  expect_valid(check(asmb, inc, geo), label);
  return inc;
}

// Successive 0.5 deg rotations of every fin by incremental updates (kept and refitted stencils
// carried along) against full assemblies at each angle.
void chained_updates(const char* preset, int steps) {
  const MeshSettings settings = mesh_preset(preset, remus());
  GridSystem sys = build_grid_system(remus(), settings);
  OversetAssembler asmb(sys, remus());
  const double step = 0.5 * std::numbers::pi / 180;
  const auto fins = sys.fins.size();
  Assembly inc = asmb.assemble(std::vector<double>(fins, 10 * step));
  const auto geo = geometries(sys);
  for (int k = 11; k <= 10 + steps; ++k) {
    char label[32];
    std::snprintf(label, sizeof label, "%s %.1f deg", preset, k * 0.5);
    inc = update_and_compare(asmb, inc, std::vector<double>(fins, k * step), geo, label);
  }
}

// The fins at unequal angles (3, -5, 7, -9 deg), each moved by 0.5 deg in turn while the others
// keep still, then all at once in opposite directions: a fin grid that stays beside one that
// moves, and the narrowed region an update re-examines round each swept fin solid, against full
// assemblies.
void fin_by_fin_updates(const char* preset) {
  const MeshSettings settings = mesh_preset(preset, remus());
  GridSystem sys = build_grid_system(remus(), settings);
  OversetAssembler asmb(sys, remus());
  const double deg = std::numbers::pi / 180;
  const auto fins = sys.fins.size();
  std::vector<double> d(fins);
  for (std::size_t i = 0; i < fins; ++i)
    d[i] = (i % 2 == 0 ? 1.0 : -1.0) * (3.0 + 2.0 * static_cast<double>(i)) * deg;
  Assembly inc = asmb.assemble(d);
  const auto geo = geometries(sys);
  for (std::size_t i = 0; i <= fins; ++i) {
    char label[64];
    if (i < fins) {
      d[i] += 0.5 * deg;
      std::snprintf(label, sizeof label, "%s fin %zu +0.5 deg", preset, i);
    } else {
      for (std::size_t j = 0; j < fins; ++j) d[j] += (j % 2 == 0 ? -0.5 : 0.5) * deg;
      std::snprintf(label, sizeof label, "%s every fin +-0.5 deg", preset);
    }
    inc = update_and_compare(asmb, inc, d, geo, label);
  }
}

// Coverage of the fluid, by Monte-Carlo sampling of the near-body region (where the grids overlap;
// the background alone covers the rest). The fluid is given by the analytic solids (the Myring
// profile and the NACA fins, not the grids). Every fluid sample must lie in an active or fringe
// cell of some grid, unless it lies only in cells whose centres are inside a solid: the staircase
// by which a grid that is not fitted to a wall (the background at every wall, the fin grid at the
// hull, the hull grid at a fin) and the gap between an exact wall and a body-fitted grid's
// inscribed polyhedral wall. A cell blanked for overlap without an active replacement fails the
// test wherever a sample hits it. The uncovered volume (box x uncovered fraction) is printed.
struct Coverage {
  int fluid = 0, covered = 0, active = 0, uncovered = 0, uncovered_not_staircase = 0;
};

bool in_solid(const GridSystem& sys, const Eigen::Vector3d& p, double deflection) {
  const geometry::MyringProfile profile(remus().hull);
  const double station = remus().mass.cb_station - p.x();
  if (station >= 0 && station <= profile.length() &&
      std::hypot(p.y(), p.z()) < profile.radius(station))
    return true;
  for (const auto& fin : sys.fin_geometry)
    if (fin.contains(p, deflection)) return true;
  return false;
}

void coverage(const char* preset) {
  const MeshSettings settings = mesh_preset(preset, remus());
  GridSystem sys = build_grid_system(remus(), settings);
  OversetAssembler asmb(sys, remus());
  const geometry::MyringProfile profile(remus().hull);
  const double length = profile.length(), cb = remus().mass.cb_station;
  const double side = remus().fin_set.tip_radius + 0.1;
  const Eigen::Vector3d lo(cb - length - 0.1, -side, -side), hi(cb + 0.1, side, side);
  const double box = (hi - lo).prod();
  for (int deg = -35; deg <= 35; deg += 5) {
    const double d = deg * std::numbers::pi / 180;
    const Assembly a = asmb.assemble(std::vector<double>(sys.fins.size(), d));
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0, 1);
    Coverage c;
    const int samples = 40000;
    for (int s = 0; s < samples; ++s) {
      const Eigen::Vector3d p =
          lo + (hi - lo).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
      if (in_solid(sys, p, d)) continue;
      ++c.fluid;
      bool covered = false, active = false, staircase = true;
      for (std::size_t g = 0; g < a.grids.size(); ++g) {
        const int cell = asmb.locate(static_cast<int>(g), p);
        if (cell < 0) continue;
        const CellStatus st = a.grids[g].status[static_cast<std::size_t>(cell)];
        covered = covered || st == CellStatus::active || st == CellStatus::fringe;
        active = active || st == CellStatus::active;
        staircase = staircase && in_solid(sys, asmb.centre(static_cast<int>(g), cell), d);
      }
      c.covered += covered ? 1 : 0;
      c.active += active ? 1 : 0;
      c.uncovered += covered ? 0 : 1;
      c.uncovered_not_staircase += covered || staircase ? 0 : 1;
    }
    std::printf(
        "%s %+d deg: %d of %d samples in the fluid, %d in active or fringe cells (%d in active "
        "cells), %d in neither (%d not in a wall staircase): uncovered volume %.2e m^3 of %.4f\n",
        preset, deg, c.fluid, samples, c.covered, c.active, c.uncovered, c.uncovered_not_staircase,
        box * c.uncovered / samples, box * c.fluid / samples);
    EXPECT_EQ(c.uncovered_not_staircase, 0) << deg;
    // All but a few samples: the staircases are wall-cell thin.
    EXPECT_LE(c.uncovered, c.fluid / 1000) << deg;
  }
}

#ifdef AUVLOOP_OVERSET_PRESETS
// Built as test_overset_presets, label slow: the medium and fine presets (0.26 M and 1.15 M
// cells), no fallback donor at any angle.
TEST(OversetSlow, MediumFinSweepHasNoOrphans) {
  sweep("medium", 0.0);
}
TEST(OversetSlow, FineFinSweepHasNoOrphans) {
  sweep("fine", 0.0);
}
TEST(OversetSlow, MediumAndFineCellsCoverTheFluid) {
  coverage("medium");
  coverage("fine");
}
TEST(OversetSlow, MediumAndFineUpdatesMatchFullAssemblies) {
  chained_updates("medium", 2);
  fin_by_fin_updates("medium");
  chained_updates("fine", 1);
}
#else
TEST(Overset, CoarseFinSweepHasNoOrphansAndBoundedWeights) {
  sweep("coarse", 0.0);
}

TEST(Overset, ActiveAndFringeCellsCoverTheFluid) {
  coverage("coarse");
}
TEST(Overset, IncrementalUpdatesMatchFullAssemblies) {
  chained_updates("coarse", 4);
}
TEST(Overset, FinByFinUpdatesMatchFullAssemblies) {
  fin_by_fin_updates("coarse");
}

// The searches run in parallel in fixed blocks of cells (a walk's seed forgotten at each block's
// start): a full assembly and an incremental update give the same statuses, donors and weights,
// bit for bit, on 1, 2 and 3 threads.
TEST(Overset, AssembliesAreTheSameOnAnyNumberOfThreads) {
  const MeshSettings settings = mesh_preset("coarse", remus());
  const double deg = std::numbers::pi / 180;
  std::vector<std::pair<Assembly, Assembly> > runs;
  for (int threads : {1, 2, 3}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(threads));
    GridSystem sys = build_grid_system(remus(), settings);
    OversetAssembler asmb(sys, remus());
    const auto fins = sys.fins.size();
    Assembly full = asmb.assemble(std::vector<double>(fins, 7 * deg));
    std::vector<double> next(fins);
    for (std::size_t i = 0; i < fins; ++i) next[i] = (7 + (i % 2 == 0 ? 0.3 : -0.4)) * deg;
    Assembly inc = asmb.update(full, next);
    runs.emplace_back(std::move(full), std::move(inc));
  }
  const auto same = [](const Assembly& a, const Assembly& b) {
    if (a.grids.size() != b.grids.size()) return false;
    for (std::size_t g = 0; g < a.grids.size(); ++g) {
      const auto& x = a.grids[g];
      const auto& y = b.grids[g];
      if (x.status != y.status || x.donor_grid != y.donor_grid || x.donor_cell != y.donor_cell ||
          x.fallback != y.fallback || x.chained != y.chained ||
          x.stencil_offsets != y.stencil_offsets || x.stencil_grids != y.stencil_grids ||
          x.stencil_cells != y.stencil_cells || x.stencil_weights != y.stencil_weights)
        return false;
    }
    return true;
  };
  ASSERT_GT(runs[0].first.grids[0].count(CellStatus::fringe), 0);
  for (std::size_t k = 1; k < runs.size(); ++k) {
    EXPECT_TRUE(same(runs[0].first, runs[k].first)) << "full assembly, " << k + 1 << " threads";
    EXPECT_TRUE(same(runs[0].second, runs[k].second)) << "update, " << k + 1 << " threads";
  }
}
#endif
