// SPDX-License-Identifier: GPL-3.0-or-later
// Parallel loops of the finite-volume engine (oneTBB), private to engine/src.
//
// Determinism: every parallel loop writes only to the entries of its own index range, and any
// sum over faces is gathered per cell in the fixed order of Mesh::cell_faces, never accumulated
// across threads; so results are bitwise identical whatever the number of threads (test
// FvThreads.BitwiseIdenticalForOneAndTwoThreads).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <array>
#include <vector>

namespace auvloop::engine::fv {

// True when only one thread may run: loops whose parallel form costs more work (per-cell gathers
// instead of a face scatter) then take their serial form, which adds the same terms in the same
// order, so the results stay bitwise equal.
inline bool single_thread() {
  return tbb::this_task_arena::max_concurrency() == 1 ||
         tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) == 1;
}

// fn(i) for i in [0, n), in blocks of at least `grain` indices.
template <class F>
void parallel_for(int n, F&& fn, int grain = 2048) {
  tbb::parallel_for(tbb::blocked_range<int>(0, n, static_cast<std::size_t>(grain)),
                    [&](const tbb::blocked_range<int>& r) {
                      for (int i = r.begin(); i != r.end(); ++i) fn(i);
                    });
}

// Sums per-face contributions into two per-cell arrays a and b (the diagonal and source of an
// assembly): term(f, owner_side) returns {da, db} for the owner (owner_side true) or the
// neighbour of face f. In parallel a per-cell gather over Mesh::cell_faces; on one thread the
// face scatter, which is cheaper (each face visited once) and adds the same terms in the same
// order per cell (ascending face index), so the results are bitwise equal.
template <class Mesh, class Term>
void accumulate_faces(const Mesh& mesh, std::vector<double>& a, std::vector<double>& b,
                      Term&& term) {
  const int internal = mesh.internal_faces();
  if (single_thread()) {
    for (int f = 0; f < mesh.faces(); ++f) {
      const auto P = static_cast<std::size_t>(mesh.owner(f));
      const auto [da, db] = term(f, true);
      a[P] += da;
      b[P] += db;
      if (f >= internal) continue;
      const auto N = static_cast<std::size_t>(mesh.neighbour(f));
      const auto [na, nb] = term(f, false);
      a[N] += na;
      b[N] += nb;
    }
    return;
  }
  parallel_for(mesh.cells(), [&](int cell) {
    const auto c = static_cast<std::size_t>(cell);
    double sa = a[c], sb = b[c];
    for (int f : mesh.cell_faces(cell)) {
      const auto [da, db] = term(f, mesh.owner(f) == cell);
      sa += da;
      sb += db;
    }
    a[c] = sa;
    b[c] = sb;
  });
}

}  // namespace auvloop::engine::fv
