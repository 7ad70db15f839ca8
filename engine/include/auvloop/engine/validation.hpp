// SPDX-License-Identifier: GPL-3.0-or-later
// Verification and validation cases of the CFD engine, shared by the tests and `auvloop validate`.
// Each case runs the solver, compares with a reference nobody in this project produced (an exact
// solution, an observed order of accuracy, a published table; see
// shared/reference/validation-data.md) and returns one row per compared quantity. Tolerances are
// stated, with their source, where each case is defined.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace auvloop::engine::validation {

struct Row {
  std::string quantity;
  double value = 0;      // auvloop's result
  double reference = 0;  // the published or exact value
  double error = 0;      // as the tolerance measures it (stated per row)
  double tolerance = 0;
  bool pass = false;
};

struct Result {
  std::string name;
  std::vector<Row> rows;
  std::vector<std::string> notes;  // grid sizes, timings, convergence history
  [[nodiscard]] bool pass() const;
};

struct Case {
  std::string name;
  std::string description;
  std::function<Result(bool quick)> run;  // quick: the CI-sized version (seconds)
};

// The implemented cases, in the order `auvloop validate --list` shows them.
const std::vector<Case>& cases();

// Manufactured steady convection-diffusion on stretched, smoothly skewed hexahedra: the L2 and
// maximum errors for n^3 cells and the observed orders between successive grids.
struct MmsError {
  int n = 0;
  double l2 = 0, max = 0;
  int iterations = 0;  // deferred-correction iterations to convergence
};
MmsError mms_convection_diffusion(int n);

// Lid-driven cavity on n x n uniform cells: the largest deviations from Ghia et al. of u on the
// vertical and v on the horizontal centreline, in units of the lid speed.
struct CavityResult {
  int n = 0;
  double reynolds = 0;
  int steps = 0;               // pseudo-time steps to the steady state
  double final_change = 0;     // max |du/dt| at the last step (1/s)
  double max_deviation_u = 0;  // max over Ghia's points
  double max_deviation_v = 0;
  double seconds = 0;
};
CavityResult lid_driven_cavity(int n, double reynolds);
double cavity_pseudo_dt(int n, double reynolds);

// 2D Taylor-Green vortex on n x n cells of [0, pi]^2 to end_time in `steps` BDF2 steps.
struct TaylorGreenRun {
  std::vector<double> u, v, volumes;  // per cell at end_time
  double error_vs_exact = 0;          // volume-weighted L2 of the velocity error (m/s)
  int max_outer = 0;                  // outer iterations the slowest step needed
};
TaylorGreenRun taylor_green(int n, int steps, double end_time, double nu);
double l2_difference(const TaylorGreenRun& a, const TaylorGreenRun& b);

// Schaefer-Turek 2D-1 (steady, Re = 20) on the cylinder grid with `cells_per_side` cells per
// side of the O-grid's square box (half as many radially, twice as many downstream), pseudo-time
// step dt (0.008 s runs up to m = 32; m = 48 needs less).
struct CylinderResult {
  int cells = 0, steps = 0;
  double final_change = 0;
  double cd = 0, cl = 0, dp = 0, la = 0;  // drag and lift coefficients, p difference, L_a (m)
  double seconds = 0;
};
CylinderResult schaefer_turek_2d1(int cells_per_side, double dt);

// Schaefer-Turek 2D-2 (Re = 100, periodic shedding) from rest to end_time with BDF2 at fixed dt;
// St, cD max and cL max over the last `measured_periods` periods of cL (upward crossings of its
// mean). periods = 0 when fewer than measured_periods + 2 periods developed (no shedding).
struct SheddingResult {
  int cells = 0, steps = 0, periods = 0;
  double strouhal = 0, cd_max = 0, cl_max = 0;
  double period_drift = 0;    // relative change of the window's length from the previous window
  double shedding_onset = 0;  // time of the first upward crossing of cL (s)
  double max_courant = 0;
  double seconds = 0;
};
SheddingResult schaefer_turek_2d2(int cells_per_side, double dt, double end_time,
                                  int measured_periods);

}  // namespace auvloop::engine::validation
