// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/matrix.hpp"

namespace auvloop::engine::fv {

namespace {
void add_scaled(std::vector<double>& a, const std::vector<double>& b, double s) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] += s * b[i];
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

void Matrix::multiply(const Mesh& mesh, std::span<const double> x, std::span<double> y) const {
  for (std::size_t c = 0; c < diag.size(); ++c) y[c] = diag[c] * x[c];
  for (int f = 0; f < mesh.internal_faces(); ++f) {
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    const auto N = static_cast<std::size_t>(mesh.neighbour(f));
    y[P] += upper[static_cast<std::size_t>(f)] * x[N];
    y[N] += lower[static_cast<std::size_t>(f)] * x[P];
  }
}

void Matrix::h_operator(const Mesh& mesh, std::span<const double> x, std::span<double> h) const {
  for (std::size_t c = 0; c < diag.size(); ++c) h[c] = source[c];
  for (int f = 0; f < mesh.internal_faces(); ++f) {
    const auto P = static_cast<std::size_t>(mesh.owner(f));
    const auto N = static_cast<std::size_t>(mesh.neighbour(f));
    h[P] -= upper[static_cast<std::size_t>(f)] * x[N];
    h[N] -= lower[static_cast<std::size_t>(f)] * x[P];
  }
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
