// SPDX-License-Identifier: GPL-3.0-or-later
// Memory bandwidth of the solver core's hot kernels (white box: engine/src/fv/sparse.hpp), against
// STREAM-style triads a[i] = b[i] + s c[i] measured in the same run: the pressure matrix of the 3D
// lid-driven cavity N^3 (7-point Laplacian) as the linear solvers hold it; y = A x, one hybrid
// Gauss-Seidel sweep in double and in single precision (the multigrid cycle's), one fused residual
// pass; the triad on vectors of the matrix's length (they may sit in cache) and on 2^25-value
// vectors (main memory), for each thread count given. Bytes are those each kernel must move at
// least (every array it reads or writes once; x's gathers counted once, as the neighbours' values
// are in cache): the figure is the rate at which the kernel moves them. Not a test: nothing is
// asserted. Last, the cost of one parallel region (a fork-join of the engine's loops): 2,000
// regions of 1024 trivial updates each, back to back, and with 5 to 500 us of busy work on the
// calling thread alone before each (the pattern of the small multigrid levels, which run serially
// between parallel loops), in microseconds per region beyond that work. On one thread the loops
// run serially, so the difference to the one-thread line is what a region costs; the longer the
// serial stretch, the deeper TBB's idle worker has gone to sleep, and the dearer its wake-up.
//   bench_kernels [--n N] [--repeat R] [--threads T[,T...]]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "../engine/src/fv/parallel.hpp"
#include "../engine/src/fv/sparse.hpp"
#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {
template <class F>
double best_seconds(int repeat, F&& fn) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}
}  // namespace

int main(int argc, char** argv) {
  int n = 64, repeat = 20;
  std::string threads = "1,2";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--n") {
      n = std::atoi(argv[i + 1]);
    } else if (key == "--repeat") {
      repeat = std::atoi(argv[i + 1]);
    } else if (key == "--threads") {
      threads = argv[i + 1];
    } else {
      std::fprintf(stderr, "unknown option %s (--n N --repeat R --threads T[,T...])\n", argv[i]);
      return 2;
    }
  }
  const auto nodes = mesher::graded_nodes(0, 1, n);
  const mesher::Grid grid = mesher::cartesian_box(nodes, nodes, nodes, {}, "cavity");
  const fv::Mesh mesh(grid);
  std::vector<int> row_start(static_cast<std::size_t>(mesh.cells()) + 1, 0), columns;
  for (int c = 0; c < mesh.cells(); ++c) {
    for (int f : mesh.cell_faces(c)) {
      if (f >= mesh.internal_faces()) break;
      columns.push_back(mesh.owner(f) == c ? mesh.neighbour(f) : mesh.owner(f));
    }
    row_start[static_cast<std::size_t>(c) + 1] = static_cast<int>(columns.size());
  }
  fv::BlockCsr A(mesh.cells(), row_start, columns);
  for (int i = 0; i < A.rows(); ++i) {  // a diagonally dominant Laplacian (positive definite)
    const auto s = static_cast<std::size_t>(i);
    A.diag[s] = 6.5;
    for (int k = A.row_begin(i); k < A.row_end(i); ++k) A.value[static_cast<std::size_t>(k)] = -1;
  }
  A.coefficients_changed();
  const auto rows = static_cast<std::size_t>(A.rows());
  const auto nnz = static_cast<double>(A.entries());
  std::vector<double> x(rows, 1.0), y(rows), b(rows, 1.0), r(rows), scratch(rows), c(rows, 2.0);
  // Bytes: values 8 + columns 4 per entry; per row diag 8, row_start 4, x 8, y (or r, b) 8 each.
  const double matvec_bytes = nnz * 12 + static_cast<double>(rows) * (8 + 4 + 8 + 8);
  const double sweep_bytes = nnz * 12 + static_cast<double>(rows) * (8 + 4 + 4 + 8 + 8 + 8);
  const double residual_bytes = matvec_bytes + static_cast<double>(rows) * 16;
  const double triad_bytes = static_cast<double>(rows) * 24;
  const double single_sweep_bytes = nnz * 8 + static_cast<double>(rows) * (4 + 4 + 4 + 4 + 8 + 8);
  constexpr int kBig = 1 << 25;
  std::vector<double> big_a(kBig, 0.0), big_b(kBig, 1.0), big_c(kBig, 2.0);
  const double big_bytes = 24.0 * kBig;
  A.keep_single();
  std::printf("cavity %d^3: %zu rows, %.0f off-diagonal entries, %d smoother blocks; best of %d\n",
              n, rows, nnz, A.blocks(), repeat);
  std::printf("%-8s %-40s %10s %8s %s\n", "threads", "kernel", "ms", "GB/s", "of the memory triad");
  std::size_t pos = 0;
  while (pos <= threads.size()) {
    const auto comma = threads.find(',', pos);
    const int t = std::atoi(threads.substr(pos, comma - pos).c_str());
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(std::max(1, t)));
    const double triad = best_seconds(repeat, [&] {
      fv::parallel_for(A.rows(), [&](int i) {
        const auto s = static_cast<std::size_t>(i);
        y[s] = b[s] + 0.5 * c[s];
      });
    });
    const double matvec = best_seconds(repeat, [&] { A.multiply(x, y); });
    const double big_triad = best_seconds(std::max(3, repeat / 4), [&] {
      fv::parallel_for(kBig, [&](int i) {
        const auto k = static_cast<std::size_t>(i);
        big_a[k] = big_b[k] + 0.5 * big_c[k];
      });
    });
    const double sweep = best_seconds(repeat, [&] { A.sweep(b, x, false, false, scratch); });
    const double sweep_single =
        best_seconds(repeat, [&] { A.sweep<true>(b, x, false, false, scratch); });
    const double residual = best_seconds(repeat, [&] { (void)A.residual(b, x, r); });
    const auto line = [&](const char* name, double seconds, double bytes) {
      std::printf("%-8d %-40s %10.3f %8.1f %.2f\n", t, name, 1e3 * seconds, bytes / seconds / 1e9,
                  (bytes / seconds) / (big_bytes / big_triad));
    };
    line("triad, 2^25 values (main memory)", big_triad, big_bytes);
    line("triad, the matrix's length", triad, triad_bytes);
    line("y = A x", matvec, matvec_bytes);
    line("hybrid Gauss-Seidel sweep", sweep, sweep_bytes);
    line("hybrid Gauss-Seidel sweep, single", sweep_single, single_sweep_bytes);
    line("residual r = b - A x and its norms", residual, residual_bytes);
    constexpr int kRegions = 2000;
    const auto regions = [&](double serial_seconds, bool on_team = false) {
      return best_seconds(3,
                          [&] {
                            const fv::Team::Region team(on_team ? fv::threads() : 1);
                            for (int k = 0; k < kRegions; ++k) {
                              if (serial_seconds > 0) {  // busy work on the calling thread alone
                                const auto until = std::chrono::steady_clock::now() +
                                                   std::chrono::duration<double>(serial_seconds);
                                while (std::chrono::steady_clock::now() < until) {
                                }
                              }
                              fv::parallel_for(
                                  1024, [&](int i) { y[static_cast<std::size_t>(i)] += 1.0; }, 512);
                            }
                          }) /
             kRegions;
    };
    std::printf("%-8d %-40s %10.2f us per region\n", t, "fork-join, back to back",
                1e6 * regions(0));
    for (const double us : {5.0, 20.0, 100.0, 500.0})
      std::printf("%-8d fork-join after %3.0f us of serial work %11.2f us per region, beyond it\n",
                  t, us, 1e6 * regions(us * 1e-6) - us);
    std::printf("%-8d %-40s %10.2f us per loop\n", t, "team loop, back to back",
                1e6 * regions(0, true));
    for (const double us : {5.0, 20.0, 100.0, 500.0})
      std::printf("%-8d team loop after %3.0f us of serial work %11.2f us per loop, beyond it\n", t,
                  us, 1e6 * regions(us * 1e-6, true) - us);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return 0;
}
