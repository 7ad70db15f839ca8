// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/matrix.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "auvloop/engine/fv/operators.hpp"

#include "parallel.hpp"
#include "scratch.hpp"

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

void Matrix::reset(const Mesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.cells());
  const auto nf = static_cast<std::size_t>(mesh.internal_faces());
  for (auto* v : {&diag, &source}) v->resize(n);
  for (auto* v : {&upper, &lower}) v->resize(nf);
  for (auto* v : {&diag, &upper, &lower, &source})
    parallel_for(static_cast<int>(v->size()),
                 [&](int i) { (*v)[static_cast<std::size_t>(i)] = 0; });
}

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
    parallel_for(static_cast<int>(v->size()),
                 [&](int i) { (*v)[static_cast<std::size_t>(i)] *= s; });
  return *this;
}

void Matrix::add_rhs(const Mesh& mesh, std::span<const double> per_unit_volume) {
  parallel_for(mesh.cells(), [&](int c) {
    source[static_cast<std::size_t>(c)] +=
        per_unit_volume[static_cast<std::size_t>(c)] * mesh.volume(c);
  });
}

// The face scatter in parallel blocks (scatter_faces): each cell's sum starts with its diagonal
// term and adds its faces in ascending order, for any number of threads.
void Matrix::multiply(const Mesh& mesh, std::span<const double> x, std::span<double> y) const {
  const int internal = mesh.internal_faces();
  scatter_faces(
      mesh,
      [&](int b, int e) {
        for (auto c = static_cast<std::size_t>(b); c < static_cast<std::size_t>(e); ++c)
          y[c] = diag[c] * x[c];
      },
      [&](int f, bool own, bool nei) {
        if (f >= internal) return;
        const auto fs = static_cast<std::size_t>(f);
        const auto P = static_cast<std::size_t>(mesh.owner(f));
        const auto N = static_cast<std::size_t>(mesh.neighbour(f));
        if (own) y[P] += upper[fs] * x[N];
        if (nei) y[N] += lower[fs] * x[P];
      });
}

void Matrix::h_operator(const Mesh& mesh, std::span<const double> x, std::span<double> h) const {
  const int internal = mesh.internal_faces();
  scatter_faces(
      mesh,
      [&](int b, int e) {
        for (auto c = static_cast<std::size_t>(b); c < static_cast<std::size_t>(e); ++c)
          h[c] = source[c];
      },
      [&](int f, bool own, bool nei) {
        if (f >= internal) return;
        const auto fs = static_cast<std::size_t>(f);
        const auto P = static_cast<std::size_t>(mesh.owner(f));
        const auto N = static_cast<std::size_t>(mesh.neighbour(f));
        if (own) h[P] -= upper[fs] * x[N];
        if (nei) h[N] -= lower[fs] * x[P];
      });
}

void Matrix::relax(std::span<const double> x_prev, double alpha) {
  parallel_for(static_cast<int>(diag.size()), [&](int i) {
    const auto c = static_cast<std::size_t>(i);
    const double d = diag[c] / alpha;
    source[c] += (d - diag[c]) * x_prev[c];
    diag[c] = d;
  });
}

void Matrix::scale_rows(const Mesh& mesh, std::span<const double> factor) {
  parallel_for(static_cast<int>(diag.size()), [&](int i) {
    const auto c = static_cast<std::size_t>(i);
    diag[c] *= factor[c];
    source[c] *= factor[c];
  });
  parallel_for(mesh.internal_faces(), [&](int f) {
    const auto fs = static_cast<std::size_t>(f);
    upper[fs] *= factor[static_cast<std::size_t>(mesh.owner(f))];      // row owner
    lower[fs] *= factor[static_cast<std::size_t>(mesh.neighbour(f))];  // row neighbour
  });
}

void Matrix::fix_values(const Mesh& mesh, std::span<const int> cells,
                        std::span<const double> values) {
  // 1. slot[c]: the position of cell c in `cells`, -1 for a free cell;
  // 2. per cell in parallel, each writing only its own row and source: a fixed cell's row
  //    becomes diag x = diag v (its off-diagonal entries 0); a free cell's couplings to fixed
  //    neighbours move into its source, in the cell's face order (deterministic for any thread
  //    count). The fixed set may be large (an overset mesh's fringe and hole cells).
  const int n = mesh.cells();
  const int internal = mesh.internal_faces();
  Scratch<int> slot(static_cast<std::size_t>(n));
  parallel_for(n, [&](int c) { slot[static_cast<std::size_t>(c)] = -1; });
  parallel_for(static_cast<int>(cells.size()), [&](int i) {
    slot[static_cast<std::size_t>(cells[static_cast<std::size_t>(i)])] = i;
  });
  parallel_for(n, [&](int c) {
    const auto s = static_cast<std::size_t>(c);
    const int own = slot[s];
    for (int f : mesh.cell_faces(c)) {
      if (f >= internal) continue;
      const auto fs = static_cast<std::size_t>(f);
      const bool owner = mesh.owner(f) == c;
      const auto other = static_cast<std::size_t>(owner ? mesh.neighbour(f) : mesh.owner(f));
      double& to_other = owner ? upper[fs] : lower[fs];  // row c, column other
      if (own >= 0) {
        to_other = 0;
      } else if (slot[other] >= 0) {
        source[s] -= to_other * values[static_cast<std::size_t>(slot[other])];
        to_other = 0;
      }
    }
    if (own >= 0) source[s] = diag[s] * values[static_cast<std::size_t>(own)];
  });
}

void Matrix::pull_values(std::span<const int> cells, std::span<const double> values,
                         std::span<const double> weights) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const double w = weights[i];
    if (!(w >= 0 && w < 1))
      throw std::invalid_argument("Matrix::pull_values: a weight must be in [0, 1), got " +
                                  std::to_string(w));
    const auto c = static_cast<std::size_t>(cells[i]);
    const double extra = w / (1 - w) * diag[c];
    diag[c] += extra;
    source[c] += extra * values[i];
  }
}

void SpTerm::add_to(Matrix& eq, double sign) const {
  const Mesh& mesh = *m;
  parallel_for(mesh.cells(), [&](int c) {
    const auto s = static_cast<std::size_t>(c);
    eq.diag[s] += sign * rate[s] * mesh.volume(c);
  });
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
