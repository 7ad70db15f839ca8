// SPDX-License-Identifier: GPL-3.0-or-later
// Where a step went wrong, in words a user can act on: a cell by index and centre, and the cell
// where a failed linear solve leaves its largest residual.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "auvloop/engine/fv/linear_solver.hpp"
#include "auvloop/engine/fv/matrix.hpp"
#include "auvloop/engine/fv/mesh.hpp"

namespace auvloop::engine::fv {

// "cell C at (x, y, z) m"
std::string cell_at(const Mesh& mesh, int cell);

// cell_at of the cell with the largest |source - A x| per unit volume (for a linear solve that
// did not converge: where it fails).
std::string largest_residual_at(const Mesh& mesh, const Matrix& m, std::span<const double> x);

// Runs `solve` (which solves eq for x); a solver failure is rethrown naming the equation and
// the cell of the largest residual.
template <class Solve>
SolveStats solve_named(const Mesh& mesh, const Matrix& eq, std::span<const double> x,
                       std::string_view equation, Solve&& solve) {
  try {
    return solve();
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(equation) + ": " + e.what() + "; largest residual in " +
                             largest_residual_at(mesh, eq, x));
  }
}

}  // namespace auvloop::engine::fv
