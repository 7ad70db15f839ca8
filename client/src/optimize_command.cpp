// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop optimize OPT.toml`: surrogate-based tuning in-process (no daemon) of a case's PID gains
// on the derivative plant, or of a built-in test function (docs/optimization.md).
#include <chrono>
#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/geometry/file_io.hpp"
#include "auvloop/geometry/input.hpp"
#include "auvloop/optimizer/optimizer.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"
#include "auvloop/results/run_directory.hpp"
#include "auvloop/scheduler/study.hpp"
#include "cli.hpp"
#include "daemon_connection.hpp"

namespace auvloop::cli {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

using scheduler::Study;

void convergence_plot(const fs::path& dir, const optimizer::SurrogateOptimizer& opt,
                      const std::string& name) {
  std::string data = "evaluation,value,best\n";
  double best = std::numeric_limits<double>::infinity();
  int n = 0;
  for (const auto& e : opt.evaluations()) {
    ++n;
    if (e.value) best = std::min(best, *e.value);
    data += fmt::format("{},{},{}\n", n, e.value ? fmt::format("{:.10g}", *e.value) : "",
                        std::isfinite(best) ? fmt::format("{:.10g}", best) : "");
  }
  write_file_atomically(dir / "convergence.csv", data);
  std::string script;
  for (const auto& [term, ext] :
       {std::pair{"pngcairo noenhanced size 1100,650 font 'DejaVu Sans,11'", "png"},
        std::pair{"svg noenhanced size 1100,650 font 'DejaVu Sans,11' dynamic", "svg"}}) {
    script += fmt::format(
        "set terminal {}\nset output 'convergence.{}'\nset title '{}: objective per evaluation'\n"
        "set xlabel 'evaluation'\nset ylabel 'objective'\nset logscale y\n"
        "plot 'convergence.csv' using 1:2 skip 1 with points pt 7 ps 0.8 title 'evaluated', "
        "'' using 1:3 skip 1 with steps lw 2 title 'best so far'\nunset output\n",
        term, ext, name);
  }
  if (auto w = results::run_gnuplot(dir, script)) fmt::print(stderr, "warning: {}\n", *w);
}

json evaluation_json(const Study& s, const optimizer::Evaluation& e, const json& metrics) {
  json x = json::object();
  for (std::size_t k = 0; k < s.config.names.size(); ++k)
    x[s.config.names[k]] = e.x[static_cast<Eigen::Index>(k)];
  return {{"batch", e.batch},     {"origin", e.origin},
          {"parameters", x},      {"objective", e.value ? json(*e.value) : json(nullptr)},
          {"failure", e.failure}, {"indices", metrics}};
}

// optimization.json: the optimizer's replayable state plus every evaluation's indices.
void save_state(const fs::path& out, const Study& study, const optimizer::SurrogateOptimizer& opt,
                const std::vector<json>& indices) {
  json state = opt.to_json();
  json evals = json::array();
  for (std::size_t i = 0; i < opt.evaluations().size(); ++i) {
    evals.push_back(evaluation_json(study, opt.evaluations()[i], indices[i]));
  }
  state["study"] = {
      {"name", study.name}, {"objective_weights", study.weights}, {"evaluations", evals}};
  write_file_atomically(out / "optimization.json", state.dump(2) + "\n");
}

int run_optimize(const std::string& file, const std::string& out_arg) {
  const Study study = scheduler::parse_study_bundle(scheduler::bundle_study_file(file));
  const fs::path out = out_arg.empty() ? fs::path("out") / study.name : fs::path(out_arg);
  fs::create_directories(out);
  optimizer::SurrogateOptimizer opt(study.config);
  std::vector<json> indices;  // per evaluation, in order
  const auto start = std::chrono::steady_clock::now();
  fmt::print("{}: {} parameters, {} initial points, at most {} iterations\n", study.name,
             study.config.names.size(), study.config.initial_points, study.config.max_iterations);
  while (auto batch = opt.ask()) {
    std::vector<std::optional<double>> values;
    std::vector<std::string> failures;
    for (const auto& x : batch->points) {
      const scheduler::Outcome o = scheduler::evaluate_in_process(study, x);
      values.push_back(o.value);
      failures.push_back(o.failure);
      indices.push_back(o.metrics);
    }
    opt.tell(*batch, values, failures);
    const auto best = opt.best();
    std::string vals;
    for (std::size_t i = 0; i < values.size() && batch->index > 0; ++i) {
      vals += fmt::format("{}{} {}", i ? ", " : "", batch->origins[i],
                          values[i] ? fmt::format("{:.6g}", *values[i]) : "failed");
    }
    fmt::print("  batch {:>2} ({:>2} points{}{}) best {:.6g} at {}\n", batch->index,
               batch->points.size(), vals.empty() ? "" : ": ", vals,
               best ? *best->value : std::nan(""),
               best ? scheduler::point_text(study, best->x) : "-");
    save_state(out, study, opt, indices);
  }
  save_state(out, study, opt, indices);  // with the stop reason
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto best = opt.best();
  fmt::print("stopped: {} after {} evaluations ({} failed) in {:.2f} s\n", opt.stop_reason(),
             opt.evaluations().size(), opt.failures(), wall);
  if (!best) {
    fmt::print(stderr, "error: no evaluation succeeded\n");
    return kFailed;
  }
  fmt::print("best: {} = {:.6g} at {}\n", study.function ? "f" : "objective", *best->value,
             scheduler::point_text(study, best->x));
  convergence_plot(out, opt, study.name);
  if (study.base_case) {
    // Before (the case's own gains) and after (the best gains), as runs, plots and a table.
    std::vector<results::StoredRun> runs;
    for (const auto& [label, c] :
         {std::pair{std::string("before"), *study.base_case},
          std::pair{std::string("after"), scheduler::with_gains(study, best->x)}}) {
      const auto r = engine::run_case(c);
      results::RunReport report{c.name + "-" + label, engine::canonical_json(c),
                                r.loop.series,        results::manoeuvre_metrics(c, r.loop.series),
                                r.plant_name,         0.0,
                                r.loop.failure};
      results::write_run_directory(out / label, report);
      runs.push_back(results::read_run_directory(out / label));
    }
    results::write_comparison(out / "before-after", runs, {"before", "after"});
    const auto& g0 = std::get<engine::HeadingStepSpec>(study.base_case->manoeuvre).gains;
    const auto g1 =
        std::get<engine::HeadingStepSpec>(scheduler::with_gains(study, best->x).manoeuvre).gains;
    fmt::print("\n{:<28} {:>14} {:>14}\n", "", "before", "after");
    fmt::print("{:<28} {:>14} {:>14}\n", "Kp / Ki / Kd",
               fmt::format("{:.3g}/{:.3g}/{:.3g}", g0.kp, g0.ki, g0.kd),
               fmt::format("{:.3g}/{:.3g}/{:.3g}", g1.kp, g1.ki, g1.kd));
    for (const auto& [label, key] : {std::pair{"ITAE (deg s^2)", "itae_deg_s2"},
                                     {"rise time (s)", "rise_time_s"},
                                     {"settling time (s)", "settling_time_s"},
                                     {"peak (deg)", "peak_deg"},
                                     {"overshoot (%)", "overshoot_percent"}}) {
      auto cell = [&, key = key](const json& m) {
        return m[key].is_null() ? std::string("not settled")
                                : fmt::format("{:.4g}", m[key].get<double>());
      };
      fmt::print("{:<28} {:>14} {:>14}\n", label, cell(runs[0].metrics), cell(runs[1].metrics));
    }
  }
  fmt::print("\nresults: {}/ (optimization.json, convergence.png{})\n", out.string(),
             study.base_case ? ", before/, after/, before-after/" : "");
  return kOk;
}

}  // namespace

void register_optimize_command(CLI::App& app, int& exit_code) {
  auto file = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto daemon = std::make_shared<bool>(false);
  auto wait = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  auto co = std::make_shared<ConnectOptions>();
  auto* cmd = app.add_subcommand(
      "optimize", "Tune PID gains (or a test function) with the Kriging surrogate optimizer");
  cmd->add_option("file", *file, "Optimisation file (TOML); see examples/pid-optimization.toml")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out,-o", *out, "Output directory (default: out/NAME)");
  cmd->add_flag("--daemon,-d", *daemon,
                "Submit to the daemon instead: evaluations run as parallel jobs, are cached, and "
                "survive a restart");
  cmd->add_flag("--wait,-w", *wait, "With --daemon: follow it until it ends");
  cmd->add_flag("--json", *json, "With --daemon: machine-readable output");
  add_connect_options(cmd, *co, true);
  cmd->footer(
      "Runs in-process on the case's plant: the Latin hypercube first, then EI + MSP batches "
      "until\n"
      "the best value improves by less than epsilon (patience iterations in a row) or the\n"
      "iteration limit. Writes optimization.json after every batch, then convergence plots and,\n"
      "for a case, before/after runs and their comparison.\n"
      "Example: auvloop optimize examples/pid-optimization.toml");
  cmd->callback([=, &exit_code] {
    exit_code = *daemon ? optimize_on_daemon(*co, *file, *wait, *json) : run_optimize(*file, *out);
  });
}

}  // namespace auvloop::cli
