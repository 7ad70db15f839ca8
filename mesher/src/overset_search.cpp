// SPDX-License-Identifier: GPL-3.0-or-later
// Overset assembly, the search stage: overset_search.hpp states the steps.
#include "overset_search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include <Eigen/Dense>
#include <boost/iterator/zip_iterator.hpp>

namespace auvloop::mesher::overset_detail {

GridData prepare(const Grid& g, int priority, int fin, int solid, bool planar) {
  GridData d;
  d.grid = &g;
  d.priority = priority;
  d.fin = fin;
  d.solid = solid;
  d.geo = compute_geometry(g);
  const auto nc = static_cast<std::size_t>(g.cells);
  std::vector<int> count(nc + 1, 0);
  for (int f = 0; f < g.faces(); ++f) {
    ++count[static_cast<std::size_t>(g.owner[static_cast<std::size_t>(f)]) + 1];
    if (f < g.internal_faces())
      ++count[static_cast<std::size_t>(g.neighbour[static_cast<std::size_t>(f)]) + 1];
  }
  for (std::size_t c = 0; c < nc; ++c) count[c + 1] += count[c];
  d.cell_face_offsets = count;
  d.cell_faces.resize(static_cast<std::size_t>(count[nc]));
  auto fill = count;
  for (int f = 0; f < g.faces(); ++f) {
    const auto o = static_cast<std::size_t>(g.owner[static_cast<std::size_t>(f)]);
    d.cell_faces[static_cast<std::size_t>(fill[o]++)] = f;
    if (f < g.internal_faces()) {
      const auto n = static_cast<std::size_t>(g.neighbour[static_cast<std::size_t>(f)]);
      d.cell_faces[static_cast<std::size_t>(fill[n]++)] = f;
    }
  }
  d.planes.resize(d.cell_faces.size());
  for (std::size_t c = 0; c < nc; ++c)
    for (int k = d.cell_face_offsets[c]; k < d.cell_face_offsets[c + 1]; ++k) {
      const auto f = static_cast<std::size_t>(d.cell_faces[static_cast<std::size_t>(k)]);
      const double sign = g.owner[f] == static_cast<int>(c) ? 1.0 : -1.0;
      const Eigen::Vector3d n = sign * d.geo.face_area[f] / d.geo.face_area[f].norm();
      d.planes[static_cast<std::size_t>(k)] << n, n.dot(d.geo.face_centre[f]);
    }
  d.outer.assign(nc, 0);
  for (const auto& p : g.patches)
    if (p.type == PatchType::overset)
      for (int f = p.start; f < p.start + p.size; ++f)
        d.outer[static_cast<std::size_t>(g.owner[static_cast<std::size_t>(f)])] = 1;
  for (const auto& p : g.points) d.local_box.add(p);
  const double thickness = d.local_box.hi.z() - d.local_box.lo.z();
  d.size.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    d.size[c] =
        planar ? std::sqrt(d.geo.cell_volume[c] / thickness) : std::cbrt(d.geo.cell_volume[c]);
    const auto& x = d.geo.cell_centre[c];
    d.centres.emplace_back(x.x(), x.y(), x.z());
    d.ids.push_back(static_cast<int>(c));
  }
  d.radius.assign(static_cast<std::size_t>(g.cells), 0.0);
  for (int f = 0; f < g.faces(); ++f) {
    const auto fu = static_cast<std::size_t>(f);
    for (int k = g.face_offsets[fu]; k < g.face_offsets[fu + 1]; ++k) {
      const auto& p =
          g.points[static_cast<std::size_t>(g.face_points[static_cast<std::size_t>(k)])];
      for (int c : {g.owner[fu], f < g.internal_faces() ? g.neighbour[fu] : -1})
        if (c >= 0) {
          auto& r = d.radius[static_cast<std::size_t>(c)];
          Eigen::Vector3d to = p - d.geo.cell_centre[static_cast<std::size_t>(c)];
          if (planar) to.z() = 0;
          r = std::max(r, to.norm());
        }
    }
  }
  for (double r : d.radius) d.largest_radius = std::max(d.largest_radius, r);
  d.tree = std::make_unique<KTree>(
      boost::make_zip_iterator(boost::make_tuple(d.centres.begin(), d.ids.begin())),
      boost::make_zip_iterator(boost::make_tuple(d.centres.end(), d.ids.end())));
  d.tree->build();  // now, not lazily at the first search: searches run on several threads
  return d;
}

// How far x lies outside a cell: the largest distance beyond any of its face planes (<= 0 inside).
double violation(const GridData& d, int cell, const Eigen::Vector3d& x) {
  double worst = -kInf;
  const auto c = static_cast<std::size_t>(cell);
  for (int k = d.cell_face_offsets[c]; k < d.cell_face_offsets[c + 1]; ++k)
    worst = std::max(worst, d.beyond(k, x));
  return worst;
}

// A walk from cell c towards x across the face x lies furthest beyond: the cell containing x, or
// -1 when the walk leaves the grid, circles among warped cells or joins a marked path.
int walk(const GridData& d, const Eigen::Vector3d& x, int c, const WalkMarks& marks) {
  const bool marking = !marks.mark.empty();
  for (int step = 0; step < 200 && c >= 0; ++step) {
    const auto cs = static_cast<std::size_t>(c);
    if (marking) {
      if (marks.mark[cs] == marks.stamp) return -1;
      marks.mark[cs] = marks.stamp;
    }
    int best_k = -1;
    double best = 1e-12 * d.size[cs];
    for (int k = d.cell_face_offsets[cs]; k < d.cell_face_offsets[cs + 1]; ++k) {
      const double s = d.beyond(k, x);
      if (s > best) {
        best = s;
        best_k = k;
      }
    }
    if (best_k < 0) return c;
    c = d.other(d.cell_faces[static_cast<std::size_t>(best_k)], c);
  }
  return -1;
}

// The cell containing x (grid frame): a walk from `seed` (a previous donor), else from the nearest
// cell centre (k-d tree). A walk can end on the boundary although x is inside the grid (the fluid
// round a body is not convex: a walk from a distant seed can run into the wall), or circle among
// warped cells, or stop in the gap their face planes leave; then walks from the 16 nearest cells,
// and last those cells by their face planes. -1: x is in no cell.
int locate_cell(const GridData& d, const Eigen::Vector3d& x, int seed, WalkMarks marks) {
  if (!d.local_box.contains(x)) return -1;
  const KPoint q(x.x(), x.y(), x.z());
  if (seed >= 0) {
    const int c = walk(d, x, seed, marks);
    if (c >= 0) return c;
  }
  {
    KSearch search(*d.tree, q, 1);
    const int c = walk(d, x, boost::get<1>(search.begin()->first), marks);
    if (c >= 0) return c;
  }
  KSearch search(*d.tree, q, 16);
  bool first = true;                // the nearest cell's walk has just failed
  for (const auto& hit : search) {  // walks from the nearest cells: warped cells leave gaps
    if (std::exchange(first, false)) continue;
    const int c = walk(d, x, boost::get<1>(hit.first), marks);
    if (c >= 0) return c;
  }
  int best_cell = -1;
  double best = kInf;
  for (const auto& hit : search) {
    const int cell = boost::get<1>(hit.first);
    const double v = violation(d, cell, x) / d.size[static_cast<std::size_t>(cell)];
    if (v < best) {
      best = v;
      best_cell = cell;
    }
  }
  // Warped faces: accept a point within a thousandth of the cell size outside its face planes.
  return best <= 1e-3 ? best_cell : -1;
}

// The cell whose centre is nearest to x (grid frame).
int nearest(const GridData& d, const Eigen::Vector3d& x) {
  KSearch search(*d.tree, KPoint(x.x(), x.y(), x.z()), 1);
  return boost::get<1>(search.begin()->first);
}

// Keeps the (at most) 16 cells of a fallback stencil whose centres are nearest to x: the weights
// stay local, and their round-off (n^2 eps) small.
void nearest_first(const GridData& d, const Eigen::Vector3d& x, std::vector<int>& cells) {
  const auto dist = [&](int c) {
    return (d.geo.cell_centre[static_cast<std::size_t>(c)] - x).squaredNorm();
  };
  std::sort(cells.begin(), cells.end(), [&](int a, int b) { return dist(a) < dist(b); });
  if (cells.size() > 16) cells.resize(16);
}

// The dense algebra of step 3 on matrices whose storage holds up to MaxN centres (MaxN ==
// Eigen::Dynamic: any number, on the heap): a stencil's weights are computed for thousands of
// receivers an update, and heap-allocated temporaries were a sixth of its time. The arithmetic
// is the same for any MaxN.
namespace {
constexpr int kStackCentres = 32;  // more centres than this (rare): heap storage
template <int MaxN>
struct Dense {
  using MN = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, MaxN>;  // m x n
  using NM = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaxN, 4>;  // n x m
  using MM = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
  using N = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MaxN, 1>;
  using M = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 4, 1>;
  using Flags = Eigen::Matrix<int, Eigen::Dynamic, 1, 0, MaxN, 1>;
  using Index = Eigen::Index;

  // The constraint matrix A (m x n: row 0 ones, rows 1.. the offsets in units of the stencil's
  // extent h) and D_i = 1 / (|r_i|^2 + 1e-3).
  static double constraints(const std::vector<Eigen::Vector3d>& xs, const Eigen::Vector3d& x,
                            Index m, MN& A, N& D) {
    const auto n = static_cast<Index>(xs.size());
    double h = 0;
    for (const auto& p : xs) h = std::max(h, (p - x).norm());
    A.resize(m, n);
    D.resize(n);
    for (Index i = 0; i < n; ++i) {
      const Eigen::Vector3d r = (xs[static_cast<std::size_t>(i)] - x) / h;
      A(0, i) = 1.0;
      A.block(1, i, m - 1, 1) = r.head(m - 1);
      D(i) = 1.0 / (r.squaredNorm() + 1e-3);
    }
    return h;
  }

  // Interpolation weights reproducing linear fields: minimise sum w_i^2 / D_i subject to
  // sum w_i = 1 and sum w_i (x_i - x) = 0, D_i = 1 / |x_i - x|^2 (near cells weigh more); m = 4
  // constraints, or 3 in the plane (the z offsets of a planar system are all zero).
  static bool linear(const std::vector<Eigen::Vector3d>& xs, const Eigen::Vector3d& x,
                     std::vector<double>& w, bool planar) {
    const auto n = static_cast<Index>(xs.size());
    const Index m = planar ? 3 : 4;
    if (n < m) return false;
    // Offsets in units of the stencil's extent keep the system well scaled; the constraints
    // (and so the exactness for linear fields) do not depend on that scale or on D.
    MN A;
    N D;
    constraints(xs, x, m, A, D);
    // Minimum-norm solution of B v = e1 with B = A D^(1/2), w = D^(1/2) v, through a QR
    // factorisation of B^T (n x m): v = Q R^-T e1. Unlike the normal equations (A D A^T) y = e1
    // it does not square the condition number, which matters for fallback stencils that
    // extrapolate; two steps of iterative refinement on the constraint residual e1 - A w bring
    // sum w = 1 and sum w r = 0 back to round-off.
    const N sqrt_d = D.cwiseSqrt();
    const NM Bt = (A * sqrt_d.asDiagonal()).transpose();
    const Eigen::HouseholderQR<NM> qr(Bt);
    const MM R = qr.matrixQR().topLeftCorner(m, m).template triangularView<Eigen::Upper>();
    const double scale = std::abs(R(0, 0));
    for (Index k = 0; k < m; ++k)
      if (!(std::abs(R(k, k)) > 1e-8 * scale)) return false;  // centres in a plane (a line)
    NM Q = NM::Identity(n, m);
    Q.applyOnTheLeft(qr.householderQ());
    const auto solve = [&](const M& rhs) -> N {
      const M y = R.transpose().template triangularView<Eigen::Lower>().solve(rhs);
      return sqrt_d.asDiagonal() * (Q * y);
    };
    const M e1 = M::Unit(m, 0);
    N wv = solve(e1);
    for (int step = 0; step < 2; ++step) wv += solve(e1 - A * wv);
    w.assign(wv.data(), wv.data() + n);
    return true;
  }

  // Lawson and Hanson's NNLS ("Solving Least Squares Problems", 1974, ch. 23): x >= 0 minimising
  // |E x - f| for a small dense E; the passive set's least-squares solves by complete orthogonal
  // decomposition (minimum norm when it has more columns than E has rows).
  static N nnls(const MN& E, const M& f) {
    const Index n = E.cols();
    N x = N::Zero(n);
    Flags passive = Flags::Zero(n), cols(n);
    const double tol = 1e-12 * std::max(1.0, E.cwiseAbs().maxCoeff()) * std::max(1.0, f.norm());
    MN Ep;
    N z(n);
    for (int outer = 0; outer < 3 * static_cast<int>(n) + 10; ++outer) {
      const N grad = E.transpose() * (f - E * x);
      Index j = -1;
      double best = tol;
      for (Index i = 0; i < n; ++i)
        if (!passive[i] && grad[i] > best) {
          best = grad[i];
          j = i;
        }
      if (j < 0) break;
      passive[j] = 1;
      for (int inner = 0; inner <= static_cast<int>(n); ++inner) {
        Index count = 0;
        for (Index i = 0; i < n; ++i)
          if (passive[i]) cols[count++] = static_cast<int>(i);
        Ep.resize(E.rows(), count);
        for (Index k = 0; k < count; ++k) Ep.col(k) = E.col(cols[k]);
        const N zp = Ep.completeOrthogonalDecomposition().solve(f);
        z.setZero();
        for (Index k = 0; k < count; ++k) z[cols[k]] = zp[k];
        if (zp.minCoeff() > 0) {
          x = z;
          break;
        }
        double alpha = 1;
        for (Index k = 0; k < count; ++k) {
          const Index i = cols[k];
          if (z[i] <= 0) alpha = std::min(alpha, x[i] / (x[i] - z[i]));
        }
        x += alpha * (z - x);
        for (Index k = 0; k < count; ++k) {
          const Index i = cols[k];
          if (x[i] <= tol) {
            x[i] = 0;
            passive[i] = 0;
          }
        }
      }
    }
    return x;
  }

  static double convex(const std::vector<Eigen::Vector3d>& xs, const Eigen::Vector3d& x,
                       std::vector<double>& w, bool planar) {
    if (!linear(xs, x, w, planar)) return -1;
    const auto n = static_cast<Index>(xs.size());
    const Index m = planar ? 3 : 4;
    double h = 0;
    for (const auto& p : xs) h = std::max(h, (p - x).norm());
    const auto offset = [&](const double* v) {  // n weights
      Eigen::Vector3d o = Eigen::Vector3d::Zero();
      for (Index i = 0; i < n; ++i) o += v[i] * (xs[static_cast<std::size_t>(i)] - x) / h;
      if (planar) o.z() = 0;
      return o.norm();
    };
    double negative = 0;
    for (double v : w) negative += std::max(0.0, -v);
    if (negative <= kNegativeWeight) return offset(w.data());  // a.
    // b. The constraints with the columns scaled by 1 / (|x_i - x| / h): w_i = s_i v_i.
    MN E(m, n);
    N scale(n);
    for (Index i = 0; i < n; ++i) {
      const Eigen::Vector3d r = (xs[static_cast<std::size_t>(i)] - x) / h;
      scale[i] = 1.0 / (r.norm() + 1e-3);
      E(0, i) = 1.0;
      E.block(1, i, m - 1, 1) = r.head(m - 1);
      E.col(i) *= scale[i];
    }
    const M e1 = M::Unit(m, 0);
    N v = nnls(E, e1);
    N trial(n);
    for (Index i = 0; i < n; ++i) trial[i] = scale[i] * v[i];
    double sum = 0;
    for (Index i = 0; i < n; ++i) sum += trial[i];
    const auto give = [&] {
      w.assign(trial.data(), trial.data() + n);
      return offset(w.data());
    };
    if (std::abs(sum - 1) < 1e-9 && offset(trial.data()) < 1e-9) {
      // In the hull: from this feasible point to the weights of least sum w_i^2 / D_i among the
      // non-negative ones (the minimum-norm solution of a. with the bounds: a primal active-set
      // method; at each free set F, w_F = D_F A_F^T y / 2 with (A_F D_F A_F^T) y = 2 e1).
      MN A;
      N D;
      constraints(xs, x, m, A, D);
      N wv = trial;
      Flags free(n);
      for (Index i = 0; i < n; ++i) free[i] = wv[i] > 0 ? 1 : 0;
      N z(n);
      for (int it = 0; it < 4 * static_cast<int>(n) + 10; ++it) {
        MM Nm = MM::Zero(m, m);
        for (Index i = 0; i < n; ++i)
          if (free[i]) Nm += D(i) * A.col(i) * A.col(i).transpose();
        const Eigen::FullPivLU<MM> lu(Nm);
        if (!lu.isInvertible()) break;  // the free centres span less than the space: keep w
        const M y = lu.solve(2 * e1);
        z.setZero();
        for (Index i = 0; i < n; ++i)
          if (free[i]) z[i] = 0.5 * D(i) * A.col(i).dot(y);
        double alpha = 1;
        Index block = -1;
        for (Index i = 0; i < n; ++i)
          if (free[i] && z[i] < 0 && wv[i] / (wv[i] - z[i]) < alpha) {
            alpha = wv[i] / (wv[i] - z[i]);
            block = i;
          }
        wv += alpha * (z - wv);
        if (block >= 0) {  // a weight reached zero on the way: bound it
          wv[block] = 0;
          free[block] = 0;
          continue;
        }
        // At the free set's optimum: release the bound whose multiplier -(A^T y)_i is most
        // negative.
        Index release = -1;
        double most = 1e-12;
        for (Index i = 0; i < n; ++i)
          if (!free[i] && A.col(i).dot(y) > most) {
            most = A.col(i).dot(y);
            release = i;
          }
        if (release < 0) break;  // optimal
        free[release] = 1;
      }
      for (Index i = 0; i < n; ++i) trial[i] = std::max(0.0, wv[i]);
      return give();
    }
    // c. Beyond the hull: the sum weighted above the offsets, then normalised.
    E.row(0) *= 1e3;
    v = nnls(E, 1e3 * e1);
    for (Index i = 0; i < n; ++i) trial[i] = scale[i] * v[i];
    sum = 0;
    for (Index i = 0; i < n; ++i) sum += trial[i];
    if (!(sum > 0)) return -1;
    for (Index i = 0; i < n; ++i) trial[i] /= sum;
    return give();
  }
};
}  // namespace

bool linear_weights(const std::vector<Eigen::Vector3d>& xs, const Eigen::Vector3d& x,
                    std::vector<double>& w, bool planar) {
  return xs.size() <= kStackCentres ? Dense<kStackCentres>::linear(xs, x, w, planar)
                                    : Dense<Eigen::Dynamic>::linear(xs, x, w, planar);
}

double convex_weights(const std::vector<Eigen::Vector3d>& xs, const Eigen::Vector3d& x,
                      std::vector<double>& w, bool planar) {
  return xs.size() <= kStackCentres ? Dense<kStackCentres>::convex(xs, x, w, planar)
                                    : Dense<Eigen::Dynamic>::convex(xs, x, w, planar);
}

}  // namespace auvloop::mesher::overset_detail
