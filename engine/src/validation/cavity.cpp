// SPDX-License-Identifier: GPL-3.0-or-later
// Lid-driven cavity (Ghia, Ghia and Shin 1982): unit square, lid u = 1 m/s, Re = 1 / nu, one cell
// thick with empty sides. Marched in pseudo-time to a steady state, then u on x = 0.5 and v on
// y = 0.5 are interpolated (bilinear on cell centres and wall values) to Ghia's points.
#include <chrono>
#include <cmath>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::engine::validation {

namespace {
// Ghia et al. 1982, tables I and II (shared/reference/validation-data.md, section 1).
const std::vector<double> kY{1.0000, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5000,
                             0.4531, 0.2813, 0.1719, 0.1016, 0.0703, 0.0625, 0.0547, 0.0000};
const std::vector<double> kU100{1.00000,  0.84123,  0.78871,  0.73722,  0.68717,  0.23151,
                                0.00332,  -0.13641, -0.20581, -0.21090, -0.15662, -0.10150,
                                -0.06434, -0.04775, -0.04192, -0.03717, 0.00000};
const std::vector<double> kU1000{1.00000,  0.65928,  0.57492,  0.51117,  0.46604,  0.33304,
                                 0.18719,  0.05702,  -0.06080, -0.10648, -0.27805, -0.38289,
                                 -0.29730, -0.22220, -0.20196, -0.18109, 0.00000};
const std::vector<double> kX{1.0000, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5000,
                             0.2344, 0.2266, 0.1563, 0.0938, 0.0781, 0.0703, 0.0625, 0.0000};
const std::vector<double> kV100{0.00000,  -0.05906, -0.07391, -0.08864, -0.10313, -0.16914,
                                -0.22445, -0.24533, 0.05454,  0.17527,  0.17507,  0.16077,
                                0.12317,  0.10890,  0.10091,  0.09233,  0.00000};
const std::vector<double> kV1000{0.00000,  -0.21388, -0.27669, -0.33714, -0.39188, -0.51550,
                                 -0.42665, -0.31966, 0.02526,  0.32235,  0.33075,  0.37095,
                                 0.32627,  0.30353,  0.29012,  0.27485,  0.00000};

// Bilinear interpolation on the (n + 2)^2 lattice of wall positions and cell centres of a uniform
// n x n cavity; `value(i, j)` for i, j in 0 .. n + 1 (0 and n + 1 are the walls).
template <class F>
double bilinear(int n, F&& value, double x, double y) {
  auto locate = [n](double s, int& i, double& t) {
    // Lattice coordinates: 0, h/2, 3h/2, ..., 1 - h/2, 1.
    const double h = 1.0 / n;
    if (s <= 0.5 * h) {
      i = 0;
      t = s / (0.5 * h);
    } else if (s >= 1 - 0.5 * h) {
      i = n;
      t = (s - (1 - 0.5 * h)) / (0.5 * h);
    } else {
      i = static_cast<int>(std::floor((s - 0.5 * h) / h)) + 1;
      t = (s - (i - 0.5) * h) / h;
    }
  };
  int i = 0, j = 0;
  double tx = 0, ty = 0;
  locate(x, i, tx);
  locate(y, j, ty);
  return (1 - tx) * (1 - ty) * value(i, j) + tx * (1 - ty) * value(i + 1, j) +
         (1 - tx) * ty * value(i, j + 1) + tx * ty * value(i + 1, j + 1);
}
}  // namespace

CavityResult lid_driven_cavity(int n, double reynolds) {
  const auto t_start = std::chrono::steady_clock::now();
  const auto nodes = mesher::graded_nodes(0, 1, n);
  mesher::BoxPatches patches;
  patches.names = {"left", "right", "bottom", "lid", "front", "back"};
  patches.types[4] = patches.types[5] = mesher::PatchType::empty;
  const auto grid = mesher::cartesian_box(nodes, nodes, {0.0, 1.0 / n}, patches, "cavity");
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = 1.0 / reynolds;
  s.dt = cavity_pseudo_dt(n, reynolds);
  s.bdf2 = false;  // only the steady state matters
  s.outer_iterations = 1;
  s.pressure_correctors = 2;
  s.max_courant = 1e3;
  fv::Pimple flow(mesh, s);
  for (const char* wall : {"left", "right", "bottom"}) flow.U.fix(mesh, wall, {0, 0, 0});
  flow.U.fix(mesh, "lid", {1, 0, 0});
  flow.initialise();
  CavityResult r{n, reynolds, 0, 0, 0, 0, 0};
  for (r.steps = 1; r.steps <= 20000; ++r.steps) {
    const auto before = flow.U.c[0].cells;
    const auto report = flow.step();
    double change = 0;
    for (std::size_t c = 0; c < before.size(); ++c)
      change = std::max(change, std::abs(flow.U.c[0].cells[c] - before[c]));
    r.final_change = change / s.dt;
    // Steady when du/dt < 1e-5 1/s (lid speed / unit time): the profiles then move by less than
    // 1e-4 of the lid speed over the remaining decay (checked against longer runs).
    if (r.final_change < 1e-5 && report.momentum_residual < 1e-4) break;
  }
  auto sample = [&](const fv::ScalarField& phi, double wall_top, int i, int j) {
    // Walls: the lid (j = n + 1) moves with u = wall_top; every other wall is at rest.
    if (j == n + 1) return (i == 0 || i == n + 1) ? 0.0 : wall_top;
    if (i == 0 || i == n + 1 || j == 0) return 0.0;
    return phi.cells[static_cast<std::size_t>((i - 1) + n * (j - 1))];
  };
  const auto& U100 = reynolds < 500 ? kU100 : kU1000;
  const auto& V100 = reynolds < 500 ? kV100 : kV1000;
  for (std::size_t k = 0; k < kY.size(); ++k) {
    const double u = bilinear(
        n, [&](int i, int j) { return sample(flow.U.c[0], 1.0, i, j); }, 0.5, kY[k]);
    const double v = bilinear(
        n, [&](int i, int j) { return sample(flow.U.c[1], 0.0, i, j); }, kX[k], 0.5);
    r.max_deviation_u = std::max(r.max_deviation_u, std::abs(u - U100[k]));
    r.max_deviation_v = std::max(r.max_deviation_v, std::abs(v - V100[k]));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return r;
}

double cavity_pseudo_dt(int n, double reynolds) {
  (void)reynolds;
  return 2.0 / n;  // Courant number about 2 at the lid
}

}  // namespace auvloop::engine::validation
