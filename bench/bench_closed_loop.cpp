// SPDX-License-Identifier: GPL-3.0-or-later
// Cost of one closed-loop manoeuvre on the derivative plants: the paper's 30 s heading step
// (examples/heading-step.toml) at several loop steps. Report: wall time per manoeuvre and per
// simulated second, and the ratio to the dt = 0.01 s case measured in the same run.
#include <benchmark/benchmark.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/geometry/input.hpp"

using namespace auvloop::engine;

namespace {
CaseSpec heading_step(double dt, PlantKind plant, double target_deg) {
  CaseSpec c = parse_case(
      auvloop::input::read_file(std::string(AUVLOOP_SOURCE_DIR) + "/examples/heading-step.toml"),
      "heading-step.toml", AUVLOOP_SOURCE_DIR);
  c.dt = dt;
  c.plant = plant;
  std::get<HeadingStepSpec>(c.manoeuvre).target_heading = target_deg * 3.141592653589793 / 180;
  return c;
}

void run(benchmark::State& state, const CaseSpec& c) {
  double simulated = 0;
  for (auto _ : state) {
    const CaseRun r = run_case(c);
    benchmark::DoNotOptimize(r.loop.series.rows());
    simulated = r.loop.final_time;
  }
  state.counters["simulated_s"] = simulated;
  state.counters["steps"] = simulated / c.dt;
  state.counters["sim_s_per_wall_s"] =
      benchmark::Counter(simulated, benchmark::Counter::kIsIterationInvariantRate);
}
}  // namespace

// 30 s heading step 0 -> 90 deg, Kp 1.5 Ki 0.6 Kd 1.0, derivative (nonlinear Prestero) plant.
static void BM_HeadingStep30s_Derivative(benchmark::State& state) {
  run(state, heading_step(1.0 / static_cast<double>(state.range(0)), PlantKind::derivative, 90));
}
BENCHMARK(BM_HeadingStep30s_Derivative)
    ->Arg(100)
    ->Arg(500)
    ->Arg(1000)
    ->ArgName("steps_per_s")
    ->Unit(benchmark::kMillisecond);

// Linearized (horizontal-plane) plant with a 5 deg step, which it survives.
static void BM_HeadingStep30s_Linearized(benchmark::State& state) {
  run(state, heading_step(1.0 / static_cast<double>(state.range(0)), PlantKind::linearized, 5));
}
BENCHMARK(BM_HeadingStep30s_Linearized)
    ->Arg(100)
    ->ArgName("steps_per_s")
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
