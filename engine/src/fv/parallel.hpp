// SPDX-License-Identifier: GPL-3.0-or-later
// Parallel loops of the finite-volume engine (oneTBB), private to engine/src.
//
// Determinism: every parallel loop writes only to the entries of its own index range, and any
// sum over faces is gathered per cell in the fixed order of Mesh::cell_faces, never accumulated
// across threads; so results are bitwise identical whatever the number of threads (test
// FvThreads.BitwiseIdenticalForOneAndTwoThreads).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace auvloop::engine::fv {

// fn(i) for i in [0, n), in blocks of at least `grain` indices.
template <class F>
void parallel_for(int n, F&& fn, int grain = 2048) {
  tbb::parallel_for(tbb::blocked_range<int>(0, n, static_cast<std::size_t>(grain)),
                    [&](const tbb::blocked_range<int>& r) {
                      for (int i = r.begin(); i != r.end(); ++i) fn(i);
                    });
}

}  // namespace auvloop::engine::fv
