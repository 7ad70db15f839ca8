// SPDX-License-Identifier: GPL-3.0-or-later
// A finite-volume equation on a mesh in LDU form (OpenFOAM's fvMatrix): one diagonal coefficient
// per cell, one upper (row owner, column neighbour) and one lower (row neighbour, column owner)
// coefficient per internal face, and a source. The equation is A phi = source; each operator adds
// the volume integral of its term to the left-hand side, implicit parts into A and explicit parts
// as -source, so that an equation reads like its PDE:
//     Matrix eq = ddt(...) + div(...) - laplacian(...);  eq == rhs_per_unit_volume;
// The sparsity pattern is the grid's face addressing, so it never changes for a given grid.
//
// The implicit operators (operators.hpp) return terms, not matrices: a term adds its coefficients
// to a Matrix when it is assigned or added to one, so `eq = ddt(...) + div(...) - laplacian(...)`
// into a Matrix kept from the last time step allocates nothing (the solver's hot path).
#pragma once

#include <concepts>
#include <span>
#include <vector>

#include "auvloop/engine/fv/mesh.hpp"

namespace auvloop::engine::fv {

struct Matrix;

// A term of an equation: mesh() and add_to(m, sign), which adds sign times its coefficients.
template <class T>
concept Term = requires(const T& t, Matrix& m) {
  { t.mesh() } -> std::same_as<const Mesh&>;
  t.add_to(m, 1.0);
};

struct Matrix {
  std::vector<double> diag, upper, lower, source;

  Matrix() = default;
  explicit Matrix(const Mesh& mesh);
  template <Term T>
  Matrix(const T& term) : Matrix(term.mesh()) {  // NOLINT: implicit, as an equation reads
    term.add_to(*this, 1.0);
  }
  template <Term T>
  Matrix& operator=(const T& term) {
    reset(term.mesh());
    term.add_to(*this, 1.0);
    return *this;
  }
  template <Term T>
  Matrix& operator+=(const T& term) {
    term.add_to(*this, 1.0);
    return *this;
  }
  template <Term T>
  Matrix& operator-=(const T& term) {
    term.add_to(*this, -1.0);
    return *this;
  }
  // Sized for the mesh and zero, keeping the storage it has.
  void reset(const Mesh& mesh);

  Matrix& operator+=(const Matrix& o);
  Matrix& operator-=(const Matrix& o);
  Matrix& operator*=(double s);
  // Adds an explicit right-hand side given per unit volume (e.g. a body force, -grad p).
  void add_rhs(const Mesh& mesh, std::span<const double> per_unit_volume);
  // y = A x.
  void multiply(const Mesh& mesh, std::span<const double> x, std::span<double> y) const;
  // H(x) = source - sum_N a_N x_N per cell (OpenFOAM's H operator, off-diagonals only).
  void h_operator(const Mesh& mesh, std::span<const double> x, std::span<double> h) const;
  // Implicit under-relaxation (Patankar): diag / alpha, source + (1 - alpha) / alpha diag x_prev.
  void relax(std::span<const double> x_prev, double alpha);
  // Multiplies row c (its diagonal, its off-diagonals and its source) by factor[c] > 0: the same
  // solution, and the same iterates for Gauss-Seidel and Jacobi-preconditioned Krylov methods
  // (both invariant under row scaling); only a residual-based stopping test changes.
  void scale_rows(const Mesh& mesh, std::span<const double> factor);
  // Fixes phi = values[i] in cells[i] (OpenFOAM's setValues; the cells ascending, each once):
  // their rows become diag phi = diag value, and each neighbour takes its coupling to a fixed
  // cell into its source, so the solve returns exactly the values there.
  void fix_values(const Mesh& mesh, std::span<const int> cells, std::span<const double> values);
  // Draws phi in cells[i] towards values[i] with weight w = weights[i] in [0, 1): row c gains
  // w / (1 - w) diag_c (phi_c - value), so that at the solution
  //     phi_c = w value + (1 - w) (source_c - sum_N a_N phi_N) / diag_c,
  // the weighted mean of the value and of what c's own row gives (w = 0: unchanged; w -> 1:
  // fix_values). The matrix stays an M-matrix if it was one (only its diagonal grows).
  void pull_values(std::span<const int> cells, std::span<const double> values,
                   std::span<const double> weights);
};

Matrix operator+(Matrix a, const Matrix& b);
Matrix operator-(Matrix a, const Matrix& b);
Matrix operator-(Matrix a);

}  // namespace auvloop::engine::fv
