// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/matrix.hpp"

#include "parallel.hpp"

namespace auvloop::engine::fv {

namespace {
void add_scaled(std::vector<double>& a, const std::vector<double>& b, double s) {
  parallel_for(static_cast<int>(a.size()), [&](int i) {
    a[static_cast<std::size_t>(i)] += s * b[static_cast<std::size_t>(i)];
  });
}
}  // namespace

Matrix::Matrix(const Mesh& mesh)
    : diag(static_cast<std::size_t>(mesh.cells()), 0.0),
      upper(static_cast<std::size_t>(mesh.internal_faces()), 0.0),
      lower(static_cast<std::size_t>(mesh.internal_faces()), 0.0),
      source(static_cast<std::size_t>(mesh.cells()), 0.0) {}

Matrix& Matrix::operator+=(const Matrix& o) {
  add_scaled(diag, o.diag, 1);
  add_scaled(upper, o.upper, 1);
  add_scaled(lower, o.lower, 1);
  add_scaled(source, o.source, 1);
  return *this;
}

Matrix& Matrix::operator-=(const Matrix& o) {
  add_scaled(diag, o.diag, -1);
  add_scaled(upper, o.upper, -1);
  add_scaled(lower, o.lower, -1);
  add_scaled(source, o.source, -1);
  return *this;
}

Matrix& Matrix::operator*=(double s) {
  for (auto* v : {&diag, &upper, &lower, &source})
    for (double& x : *v) x *= s;
  return *this;
}

void Matrix::add_rhs(const Mesh& mesh, std::span<const double> per_unit_volume) {
  for (int c = 0; c < mesh.cells(); ++c)
    source[static_cast<std::size_t>(c)] +=
        per_unit_volume[static_cast<std::size_t>(c)] * mesh.volume(c);
}

// Per-cell gathers in Mesh::cell_faces order (ascending face index): the same sums in the same
// order as the serial face scatter, in parallel. The gather visits every face twice with indirect
// reads (measured 1.8 times the scatter's time on one thread, 64^3 cells), so one thread scatters.
void Matrix::multiply(const Mesh& mesh, std::span<const double> x, std::span<double> y) const {
  const int internal = mesh.internal_faces();
  if (single_thread()) {
    for (std::size_t c = 0; c < diag.size(); ++c) y[c] = diag[c] * x[c];
    for (int f = 0; f < internal; ++f) {
      const auto P = static_cast<std::size_t>(mesh.owner(f));
      const auto N = static_cast<std::size_t>(mesh.neighbour(f));
      y[P] += upper[static_cast<std::size_t>(f)] * x[N];
      y[N] += lower[static_cast<std::size_t>(f)] * x[P];
    }
    return;
  }
  parallel_for(mesh.cells(), [&](int c) {
    const auto C = static_cast<std::size_t>(c);
    double sum = diag[C] * x[C];
    for (int f : mesh.cell_faces(c)) {
      if (f >= internal) break;  // boundary faces come last
      const auto fs = static_cast<std::size_t>(f);
      sum += mesh.owner(f) == c ? upper[fs] * x[static_cast<std::size_t>(mesh.neighbour(f))]
                                : lower[fs] * x[static_cast<std::size_t>(mesh.owner(f))];
    }
    y[C] = sum;
  });
}

void Matrix::h_operator(const Mesh& mesh, std::span<const double> x, std::span<double> h) const {
  const int internal = mesh.internal_faces();
  if (single_thread()) {
    for (std::size_t c = 0; c < diag.size(); ++c) h[c] = source[c];
    for (int f = 0; f < internal; ++f) {
      const auto P = static_cast<std::size_t>(mesh.owner(f));
      const auto N = static_cast<std::size_t>(mesh.neighbour(f));
      h[P] -= upper[static_cast<std::size_t>(f)] * x[N];
      h[N] -= lower[static_cast<std::size_t>(f)] * x[P];
    }
    return;
  }
  parallel_for(mesh.cells(), [&](int c) {
    const auto C = static_cast<std::size_t>(c);
    double sum = source[C];
    for (int f : mesh.cell_faces(c)) {
      if (f >= internal) break;
      const auto fs = static_cast<std::size_t>(f);
      sum -= mesh.owner(f) == c ? upper[fs] * x[static_cast<std::size_t>(mesh.neighbour(f))]
                                : lower[fs] * x[static_cast<std::size_t>(mesh.owner(f))];
    }
    h[C] = sum;
  });
}

void Matrix::relax(std::span<const double> x_prev, double alpha) {
  for (std::size_t c = 0; c < diag.size(); ++c) {
    const double d = diag[c] / alpha;
    source[c] += (d - diag[c]) * x_prev[c];
    diag[c] = d;
  }
}

Matrix operator+(Matrix a, const Matrix& b) {
  return a += b;
}
Matrix operator-(Matrix a, const Matrix& b) {
  return a -= b;
}
Matrix operator-(Matrix a) {
  return a *= -1.0;
}

}  // namespace auvloop::engine::fv
