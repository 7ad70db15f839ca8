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

}  // namespace auvloop::engine::validation
