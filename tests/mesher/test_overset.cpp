// SPDX-License-Identifier: GPL-3.0-or-later
// Overset assembly of the REMUS 100 grid system over the fin range: no orphans, donors active,
// weights summing to one and interpolating linear fields to round-off, the fluid covered.
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

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
  int orphans = 0, outside_junction = 0, fringe = 0, bad_donor_status = 0;
  double worst_sum = 0, worst_linear = 0;  // in units of the round-off bound of each sum
};

// Every fringe stencil: active donor cells, weights summing to one, and the linear field
// f = 3 + 2 x - 5 y + 7 z (body frame) reproduced at the fringe centre.
// The fin-root junction: where a fin grid overlaps the hull near its root (stations from the
// root leading edge to the tail end, radius below the root station, each widened by the fin grid's
// extent). Hull wall cells and fin cells inside the hull blank each other there (known defect).
bool in_junction(const Eigen::Vector3d& x, double extent) {
  const auto& f = remus().fin_set;
  const double station = remus().mass.cb_station - x.x();
  const double length = geometry::MyringProfile(remus().hull).length();
  return station > f.root_le_station - extent && station < length + extent &&
         std::hypot(x.y(), x.z()) < f.root_radius() + extent;
}

Check check(const OversetAssembler& asmb, const Assembly& a, double extent) {
  Check r;
  const auto f = [](const Eigen::Vector3d& x) { return 3 + 2 * x.x() - 5 * x.y() + 7 * x.z(); };
  for (std::size_t g = 0; g < a.grids.size(); ++g) {
    const auto& ga = a.grids[g];
    r.orphans += ga.count(CellStatus::orphan);
    for (std::size_t c = 0; c < ga.status.size(); ++c) {
      if (ga.status[c] == CellStatus::orphan &&
          !in_junction(asmb.centre(static_cast<int>(g), static_cast<int>(c)), extent))
        ++r.outside_junction;
      if (ga.status[c] != CellStatus::fringe) continue;
      ++r.fringe;
      const int dg = ga.donor_grid[c];
      double sum = 0, value = 0, sum_abs = 0, value_abs = 0;
      for (int k = ga.stencil_offsets[c]; k < ga.stencil_offsets[c + 1]; ++k) {
        const auto ku = static_cast<std::size_t>(k);
        const int d = ga.stencil_cells[ku];
        if (a.grids[static_cast<std::size_t>(dg)].status[static_cast<std::size_t>(d)] !=
            CellStatus::active)
          ++r.bad_donor_status;
        const double w = ga.stencil_weights[ku], fd = f(asmb.centre(dg, d));
        sum += w;
        sum_abs += std::abs(w);
        value += w * fd;
        value_abs += std::abs(w * fd);
      }
      const double exact = f(asmb.centre(static_cast<int>(g), static_cast<int>(c)));
      // Round-off: the weights solve a 4 x 4 system built from n <= 32 stencil cells and are
      // summed again, so Wilkinson's n^2 eps (about 1e3 eps) times the sum of the magnitudes.
      const double eps = std::numeric_limits<double>::epsilon();
      r.worst_sum = std::max(r.worst_sum, std::abs(sum - 1) / (1024 * eps * sum_abs));
      r.worst_linear = std::max(r.worst_linear, std::abs(value - exact) / (1024 * eps * value_abs));
    }
  }
  return r;
}
}  // namespace

// Deflections -35 .. 35 deg in 5 deg steps (all fins together) on the coarse preset: donors are
// active cells, and weights sum to one and reproduce a linear field to round-off. Not met yet
// (docs/mesher.md, known defects): "no orphans". The fin-root junction leaves orphans, whose
// number is printed here; this test does not hide them by asserting on them.
TEST(Overset, FinSweepDonorsAreActiveAndInterpolateLinearFieldsExactly) {
  const MeshSettings settings = mesh_preset("coarse", remus());
  GridSystem sys = build_grid_system(remus(), settings);
  OversetAssembler asmb(sys, remus());
  for (int deg = -35; deg <= 35; deg += 5) {
    const double d = deg * std::numbers::pi / 180;
    const Assembly a = asmb.assemble(std::vector<double>(sys.fins.size(), d));
    const Check r = check(asmb, a, settings.fin.extent);
    std::printf(
        "%+3d deg: %d fringe, %d orphans (%d outside the fin-root junction), |sum w - 1| "
        "and linear error at most %.2f and %.2f of their round-off bounds (%.2f s)\n",
        deg, r.fringe, r.orphans, r.outside_junction, r.worst_sum, r.worst_linear, a.seconds);
    EXPECT_GT(r.fringe, 0) << deg;
    EXPECT_EQ(r.bad_donor_status, 0) << deg;
    EXPECT_LE(r.worst_sum, 1.0) << deg;
    EXPECT_LE(r.worst_linear, 1.0) << deg;
  }
}

// A 0.5 deg rotation of every fin: the incremental update re-examines a fraction of the cells and
// gives the statuses of a full assembly.
TEST(Overset, IncrementalUpdateMatchesFullAssembly) {
  const MeshSettings settings = mesh_preset("coarse", remus());
  GridSystem sys = build_grid_system(remus(), settings);
  OversetAssembler asmb(sys, remus());
  const double step = 0.5 * std::numbers::pi / 180;
  const auto fins = sys.fins.size();
  const Assembly start = asmb.assemble(std::vector<double>(fins, 10 * step));
  const Assembly full = asmb.assemble(std::vector<double>(fins, 11 * step));
  const Assembly restart = asmb.assemble(std::vector<double>(fins, 10 * step));
  const Assembly inc = asmb.update(restart, std::vector<double>(fins, 11 * step));
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
  std::printf(
      "full assembly: %d cells examined in %.3f s; update: %d cells in %.3f s; %d statuses "
      "differ\n",
      full.cells_visited, full.seconds, inc.cells_visited, inc.seconds, differ);
  EXPECT_EQ(differ, 0);
  EXPECT_LT(inc.cells_visited, full.cells_visited / 2);
  const Check r = check(asmb, inc, settings.fin.extent);
  EXPECT_EQ(r.bad_donor_status, 0);
  EXPECT_LE(r.worst_linear, 1.0);
  (void)start;
}
