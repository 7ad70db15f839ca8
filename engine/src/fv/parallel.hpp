// SPDX-License-Identifier: GPL-3.0-or-later
// Parallel loops of the finite-volume engine (oneTBB), private to engine/src.
//
// Determinism (results bitwise identical for any number of threads; test FvThreads):
//   1. a loop writes only to the entries of its own index range;
//   2. a sum over the faces of a cell is taken in ascending face order, by the thread that owns
//      the cell (scatter_faces), never accumulated across threads;
//   3. a reduction (parallel_sum) adds partial sums over fixed blocks of indices, whose size
//      depends on the length only, in block order;
//   4. an algorithm whose result depends on a partition (the hybrid Gauss-Seidel smoother,
//      sparse.hpp) takes a partition that depends on the matrix only.
// Inside a Team::Region (a time step, a linear solve) the loops run as phases of that team
// (team.hpp), elsewhere on TBB's pool with its static partitioner. Either way each thread starts
// on the same contiguous share of a range in every loop, so the data a thread touched in one
// loop is in its cache for the next.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>

#include "auvloop/engine/fv/mesh.hpp"
#include "team.hpp"

namespace auvloop::engine::fv {

// Below this many indices a loop runs on the calling thread (a fork-join costs a microsecond or
// two): vector operations; loops over matrix rows (several entries each) split from kRowGrain.
inline constexpr int kSerialBelow = 1024;
inline constexpr int kRowGrain = 256;
// Vector operations of the solvers (a few flops per entry, in loops that follow one another).
inline constexpr int kVectorGrain = 512;

// The number of threads the engine's loops may use now.
inline int threads() {
  const auto limit =
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return std::max(1, std::min(tbb::this_task_arena::max_concurrency(), static_cast<int>(limit)));
}

// A phase of the team is split into this many parts per thread: a late thread's parts go to the
// others in pieces, while each thread still starts on the same contiguous share in every loop.
inline constexpr int kPartsPerThread = 4;

// fn(begin, end) over contiguous sub-ranges of [0, n) of at least `grain` indices: on the team
// the calling thread leads (team.hpp), else on TBB's pool; serially inside a team's part.
template <class F>
void parallel_ranges(int n, F&& fn, int grain = kSerialBelow) {
  if (n <= grain || threads() == 1 || Team::in_part()) {
    if (n > 0) fn(0, n);
    return;
  }
  if (Team* team = Team::current()) {
    const int parts =
        std::min({kPartsPerThread * team->size(), Team::kMaxParts, n / std::max(grain, 1)});
    if (parts < 2) {
      fn(0, n);
      return;
    }
    team->run(parts, [&](int k) {
      fn(static_cast<int>(static_cast<long long>(n) * k / parts),
         static_cast<int>(static_cast<long long>(n) * (k + 1) / parts));
    });
    return;
  }
  tbb::parallel_for(
      tbb::blocked_range<int>(0, n, static_cast<std::size_t>(grain)),
      [&](const tbb::blocked_range<int>& r) { fn(r.begin(), r.end()); }, tbb::static_partitioner());
}

// fn(i) for i in [0, n).
template <class F>
void parallel_for(int n, F&& fn, int grain = kSerialBelow) {
  parallel_ranges(
      n,
      [&](int b, int e) {
        for (int i = b; i < e; ++i) fn(i);
      },
      grain);
}

// fn(k) for every block k in [0, blocks) (one task per block; blocks are few and large); on the
// calling thread alone when `serial`.
template <class F>
void parallel_blocks(int blocks, F&& fn, bool serial = false) {
  if (serial || blocks == 1 || threads() == 1 || Team::in_part()) {
    for (int k = 0; k < blocks; ++k) fn(k);
    return;
  }
  if (Team* team = Team::current()) {
    const int parts = std::min(blocks, Team::kMaxParts);
    team->run(parts, [&](int p) {
      const int end = static_cast<int>(static_cast<long long>(blocks) * (p + 1) / parts);
      for (int k = static_cast<int>(static_cast<long long>(blocks) * p / parts); k < end; ++k)
        fn(k);
    });
    return;
  }
  tbb::parallel_for(
      tbb::blocked_range<int>(0, blocks, 1),
      [&](const tbb::blocked_range<int>& r) {
        for (int k = r.begin(); k != r.end(); ++k) fn(k);
      },
      tbb::static_partitioner());
}

// The fixed blocks of a reduction over n indices: at least 1024 indices each and at most 256
// blocks; depends on n only.
struct ReductionBlocks {
  static constexpr int kMaxBlocks = 256;
  explicit ReductionBlocks(int length)
      : n(length),
        size(std::max(1024, (length + kMaxBlocks - 1) / kMaxBlocks)),
        count((length + size - 1) / size) {}
  int n, size, count;
  [[nodiscard]] int begin(int k) const { return k * size; }
  [[nodiscard]] int end(int k) const { return std::min(n, (k + 1) * size); }
};

// K sums over i in [0, n): fn(begin, end, sums) adds the terms of [begin, end) to `sums` (which
// it receives zeroed) in ascending order; the partial sums of the fixed blocks are then added in
// block order. Bitwise the same for any number of threads (and for any `grain`, below which the
// blocks are summed on the calling thread).
template <std::size_t K, class F>
std::array<double, K> parallel_sum(int n, F&& fn, int grain = kSerialBelow) {
  const ReductionBlocks blocks(n);
  std::array<std::array<double, K>, ReductionBlocks::kMaxBlocks> partial;
  parallel_blocks(
      blocks.count,
      [&](int k) {
        auto& s = partial[static_cast<std::size_t>(k)];
        s.fill(0.0);
        fn(blocks.begin(k), blocks.end(k), s);
      },
      n < grain);
  std::array<double, K> total{};
  for (int k = 0; k < blocks.count; ++k)
    for (std::size_t j = 0; j < K; ++j) total[j] += partial[static_cast<std::size_t>(k)][j];
  return total;
}

// Face contributions summed into cells, in parallel over the blocks of Mesh::face_blocks: in each
// block, cells(begin, end) for its cells first, then face(f, owner, neighbour) for every face of
// the block's list in ascending order, `owner` / `neighbour` telling which of the face's cells lie
// in the block (a face between two blocks is visited from both, with one flag each). face() adds
// the face's terms to the flagged cells only, and may write per-face values of f when `owner` is
// set (once per face). Each cell's terms arrive in ascending face order, owner side before
// neighbour side, exactly as in the serial loop
//     cells(0, n); for f: add to owner(f); if internal: add to neighbour(f)
// so the sums are bitwise those of that loop whatever the number of threads.
template <class Cells, class Face>
void scatter_faces(const Mesh& mesh, Cells&& cells, Face&& face) {
  const auto& fb = mesh.face_blocks();
  parallel_blocks(fb.blocks(), [&](int k) {
    cells(fb.cell_begin(k), fb.cell_end(k));
    for (int t : fb.faces(k))
      face(t >> 2, (t & FaceBlocks::kOwner) != 0, (t & FaceBlocks::kNeighbour) != 0);
  });
}

// out[c] = the sum of value(f) over the faces of cell c, the neighbour side taking
// neighbour_sign * value(f) (-1: a net flux out of the cell, +1: a sum of magnitudes).
template <class Value>
void sum_faces(const Mesh& mesh, std::span<double> out, Value&& value, double neighbour_sign) {
  const int internal = mesh.internal_faces();
  scatter_faces(
      mesh,
      [&](int b, int e) {
        for (auto c = static_cast<std::size_t>(b); c < static_cast<std::size_t>(e); ++c) out[c] = 0;
      },
      [&](int f, bool own, bool nei) {
        const double v = value(f);
        if (own) out[static_cast<std::size_t>(mesh.owner(f))] += v;
        if (nei && f < internal)
          out[static_cast<std::size_t>(mesh.neighbour(f))] += neighbour_sign * v;
      });
}

}  // namespace auvloop::engine::fv
