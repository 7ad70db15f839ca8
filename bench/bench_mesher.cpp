// SPDX-License-Identifier: GPL-3.0-or-later
// Mesher timings: building each preset's grid system, a full overset assembly, and the
// incremental update after a 0.5 deg rotation of every fin (the per-time-step cost when the
// rudders move), against a flow time step on the same number of cells; the wall distance measured
// afresh and updated after the same turn. Run:
// build/release/bench/bench_mesher
#include <ctime>
#include <memory>
#include <numbers>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "auvloop/engine/turbulence/wall_distance.hpp"
#include "auvloop/mesher/grid_system.hpp"
#include "auvloop/mesher/overset.hpp"
#include "hull_case.hpp"

namespace {
using namespace auvloop;

const geometry::Vehicle& remus() {
  static const geometry::Vehicle v = geometry::preset_vehicle("remus100");
  return v;
}

const char* preset(const benchmark::State& state) {
  static const char* names[] = {"coarse", "medium", "fine"};
  return names[state.range(0)];
}

void BuildPreset(benchmark::State& state) {
  const auto settings = mesher::mesh_preset(preset(state), remus());
  long long cells = 0;
  for (auto _ : state) {
    const auto sys = mesher::build_grid_system(remus(), settings);
    cells = sys.total_cells();
    benchmark::DoNotOptimize(cells);
  }
  state.SetLabel(preset(state));
  state.counters["cells"] = static_cast<double>(cells);
}
BENCHMARK(BuildPreset)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

void FullAssembly(benchmark::State& state) {
  auto sys = mesher::build_grid_system(remus(), mesher::mesh_preset(preset(state), remus()));
  mesher::OversetAssembler assembler(sys, remus());
  const std::vector<double> d(sys.fins.size(), 10 * std::numbers::pi / 180);
  for (auto _ : state) benchmark::DoNotOptimize(assembler.assemble(d));
  state.SetLabel(preset(state));
}
BENCHMARK(FullAssembly)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

void UpdateHalfDegree(benchmark::State& state) {
  auto sys = mesher::build_grid_system(remus(), mesher::mesh_preset(preset(state), remus()));
  mesher::OversetAssembler assembler(sys, remus());
  const double deg = std::numbers::pi / 180;
  const mesher::Assembly start = assembler.assemble(std::vector<double>(sys.fins.size(), 10 * deg));
  int visited = 0;
  for (auto _ : state) {
    const auto a = assembler.update(start, std::vector<double>(sys.fins.size(), 10.5 * deg));
    visited = a.cells_visited;
    benchmark::DoNotOptimize(a);
  }
  state.SetLabel(preset(state));
  state.counters["cells_examined"] = visited;
  state.counters["cells"] = static_cast<double>(sys.total_cells());
}
BENCHMARK(UpdateHalfDegree)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// Full assembly and update timed in the same iterations, in CPU time of this thread, so that
// their ratio is measured under the same conditions on the shared machine: counters full_ms,
// update_ms and update_over_full. Then, in the same run, the baseline the update must be small
// against: one PIMPLE time step with the paper's 5 outer iterations (2 pressure correctors,
// laminar, so a lower bound of the RANS step) on the preset's hull grid in a free stream, per cell,
// times the cells of the whole system (the solver does not yet run the overset system itself):
// counters flow_step_ms and update_over_flow_step.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double flow_step_seconds_per_cell(const char* name) {
  namespace fv = engine::fv;
  const Eigen::Vector3d u_inf(-1.54, 0, 0);  // REMUS 100 design speed
  const mesher::Grid grid = bench::hull_freestream_grid(name, u_inf);
  const fv::Mesh mesh(grid);  // refers to the grid
  fv::PimpleSettings s;
  s.nu = 1.05e-6;
  s.outer_iterations = 5;
  s.max_courant = 1e9;  // a benchmark: report, do not stop
  s.dt = bench::freestream_dt(mesh, u_inf, 1.0);
  fv::Pimple flow(mesh, s);
  bench::set_freestream(flow, mesh, u_inf);
  flow.initialise();
  (void)flow.step();  // the first step builds the solver's structures
  constexpr int kSteps = 2;
  const double t0 = thread_cpu_seconds();
  for (int k = 0; k < kSteps; ++k) (void)flow.step();
  return (thread_cpu_seconds() - t0) / (kSteps * mesh.cells());
}

void UpdateOverFull(benchmark::State& state) {
  auto sys = mesher::build_grid_system(remus(), mesher::mesh_preset(preset(state), remus()));
  mesher::OversetAssembler assembler(sys, remus());
  const double deg = std::numbers::pi / 180;
  const auto fins = sys.fins.size();
  double full = 0, update = 0;
  for (auto _ : state) {
    const double t0 = thread_cpu_seconds();
    const auto start = assembler.assemble(std::vector<double>(fins, 10 * deg));
    const double t1 = thread_cpu_seconds();
    const auto moved = assembler.update(start, std::vector<double>(fins, 10.5 * deg));
    const double t2 = thread_cpu_seconds();
    full += t1 - t0;
    update += t2 - t1;
    benchmark::DoNotOptimize(moved);
  }
  const auto n = static_cast<double>(state.iterations());
  const double flow_step =
      flow_step_seconds_per_cell(preset(state)) * static_cast<double>(sys.total_cells());
  state.SetLabel(preset(state));
  state.counters["full_ms"] = 1e3 * full / n;
  state.counters["update_ms"] = 1e3 * update / n;
  state.counters["update_over_full"] = update / full;
  state.counters["flow_step_ms"] = 1e3 * flow_step;
  state.counters["update_over_flow_step"] = update / n / flow_step;
}
BENCHMARK(UpdateOverFull)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// The wall distance of every cell of the system (engine::turbulence::WallDistances): measured
// afresh at 10 deg, then updated after every fin turned by 0.5 deg, in the same iterations (CPU
// time of this thread, one thread): counters full_ms, update_ms, update_over_full, and the
// exact queries of each (queries_full, queries_update) against the system's cells; the same
// update with only the cells in the equations at 10.5 deg measured (active and fringe cells of
// the assembly): masked_ms, masked_over_full, queries_masked.
void WallDistanceUpdateOverFull(benchmark::State& state) {
  auto sys = mesher::build_grid_system(remus(), mesher::mesh_preset(preset(state), remus()));
  std::vector<std::unique_ptr<engine::fv::Mesh>> meshes;
  std::vector<const engine::fv::Mesh*> pointers;
  for (const mesher::Grid* g : sys.grids()) {
    meshes.push_back(std::make_unique<engine::fv::Mesh>(*g));
    pointers.push_back(meshes.back().get());
  }
  const double deg = std::numbers::pi / 180;
  const auto fins = sys.fins.size();
  // The cells in the equations at 10.5 deg (active and fringe) for the masked update.
  mesher::OversetAssembler assembler(sys, remus());
  const mesher::Assembly at = assembler.assemble(std::vector<double>(fins, 10.5 * deg));
  std::vector<std::vector<char>> needed;
  for (const auto& ga : at.grids) {
    needed.emplace_back();
    for (const auto s : ga.status)
      needed.back().push_back(s == mesher::CellStatus::active || s == mesher::CellStatus::fringe);
  }
  const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  double full = 0, update = 0, masked = 0;
  long queries_full = 0, queries_update = 0, queries_masked = 0;
  for (auto _ : state) {
    mesher::set_fin_deflections(sys, std::vector<double>(fins, 10 * deg));
    const double t0 = thread_cpu_seconds();
    engine::turbulence::WallDistances walls(pointers);
    const double t1 = thread_cpu_seconds();
    engine::turbulence::WallDistances walls_masked(pointers);
    mesher::set_fin_deflections(sys, std::vector<double>(fins, 10.5 * deg));
    const double t2 = thread_cpu_seconds();
    const auto work = walls.update();
    const double t3 = thread_cpu_seconds();
    const auto work_masked = walls_masked.update(needed);
    const double t4 = thread_cpu_seconds();
    full += t1 - t0;
    update += t3 - t2;
    masked += t4 - t3;
    queries_full = walls.initial_work().queries;
    queries_update = work.queries;
    queries_masked = work_masked.queries;
  }
  const auto n = static_cast<double>(state.iterations());
  state.SetLabel(preset(state));
  state.counters["full_ms"] = 1e3 * full / n;
  state.counters["update_ms"] = 1e3 * update / n;
  state.counters["update_over_full"] = update / full;
  state.counters["queries_full"] = static_cast<double>(queries_full);
  state.counters["queries_update"] = static_cast<double>(queries_update);
  state.counters["masked_ms"] = 1e3 * masked / n;
  state.counters["masked_over_full"] = masked / full;
  state.counters["queries_masked"] = static_cast<double>(queries_masked);
  state.counters["cells"] = static_cast<double>(sys.total_cells());
}
BENCHMARK(WallDistanceUpdateOverFull)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
