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
#include "auvloop/optimizer/test_functions.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"
#include "auvloop/results/run_directory.hpp"
#include "cli.hpp"

namespace auvloop::cli {
namespace {
namespace fs = std::filesystem;
using input::Range;
using nlohmann::json;

// The indices an objective may use, and where they live in metrics.json.
const std::vector<std::pair<std::string, std::string>>& objective_indices() {
  static const std::vector<std::pair<std::string, std::string>> m{
      {"itae", "itae_deg_s2"},
      {"iae", "iae_deg_s"},
      {"ise", "ise_deg2_s"},
      {"overshoot", "overshoot_percent"},
      {"settling_time", "settling_time_s"},
      {"rise_time", "rise_time_s"},
      {"rudder_variation", "rudder.total_variation_deg"}};
  return m;
}

std::vector<std::string> index_names() {
  std::vector<std::string> n;
  for (const auto& [k, v] : objective_indices()) n.push_back(k);
  return n;
}

struct Study {
  std::string name;
  std::optional<engine::CaseSpec> base_case;        // a case, or ...
  std::optional<optimizer::TestFunction> function;  // ... a test function
  optimizer::OptimizerConfig config;
  std::map<std::string, double> weights;                     // objective = sum w * index
  std::optional<double> max_overshoot, max_saturation_time;  // constraints
};

// A metric from metrics.json by dotted path; "not settled" counts as the whole run's duration.
std::optional<double> metric(const json& m, const std::string& path, double duration) {
  const json* node = &m;
  std::size_t start = 0;
  while (start <= path.size()) {
    const auto dot = path.find('.', start);
    const std::string key = path.substr(start, dot - start);
    if (!node->contains(key)) return std::nullopt;
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  if (node->is_null()) return path == "settling_time_s" ? std::optional(duration) : std::nullopt;
  return node->get<double>();
}

Study read_study(const fs::path& path) {
  auto doc = input::Document::load(path);
  auto root = doc.root();
  Study s;
  s.name = root.text("name");
  root.text_or("description", "");
  auto problem = root.table("problem");
  const std::string type = problem.choice("type", {"case", "test-function"});
  auto& c = s.config;
  if (type == "case") {
    const std::string case_file = problem.text("case");
    try {
      s.base_case = engine::load_case(path.parent_path() / case_file);
      if (!std::holds_alternative<engine::HeadingStepSpec>(s.base_case->manoeuvre)) {
        problem.fail("case", "only heading-step cases have gains to tune");
      }
    } catch (const input::InputError& e) {
      problem.fail("case", fmt::format("the case cannot be used:\n{}", e.what()));
    }
    for (auto p : root.tables("parameter", 1, 3)) {
      c.names.push_back(p.choice("name", {"kp", "ki", "kd"}));
      const double lo = p.number("lower", Range::non_negative(), "");
      const double hi = p.number("upper", Range::non_negative(), "");
      if (!(hi > lo))
        p.fail("upper",
               fmt::format("must exceed lower = {:g} (bounds reversed or of zero width)", lo));
      c.lower.conservativeResize(c.lower.size() + 1);
      c.upper.conservativeResize(c.upper.size() + 1);
      c.lower[c.lower.size() - 1] = lo;
      c.upper[c.upper.size() - 1] = hi;
      p.finish();
    }
  } else {
    const std::string fname =
        problem.choice("function", {"branin", "goldstein-price", "hartmann3", "hartmann6"});
    s.function = optimizer::test_function(fname);
    c.lower = s.function->lower;
    c.upper = s.function->upper;
    for (Eigen::Index k = 0; k < c.lower.size(); ++k) c.names.push_back(fmt::format("x{}", k + 1));
    root.ignore("parameter");
  }
  problem.finish();
  if (auto obj = root.optional_table("objective")) {
    const std::string index = obj->choice_or("index", "itae",
                                             {"itae", "iae", "ise", "overshoot", "settling_time",
                                              "rise_time", "rudder_variation", "weighted"});
    if (index == "weighted") {
      auto w = obj->table("weights");
      for (const auto& name : index_names()) {
        if (w.has(name)) s.weights[name] = w.number(name, Range::non_negative(), "");
      }
      w.finish();
      if (s.weights.empty())
        obj->fail("weights", "give at least one weight (itae, overshoot, ...)");
    } else {
      s.weights[index] = 1.0;
    }
    obj->finish();
  } else {
    s.weights["itae"] = 1.0;
  }
  if (auto con = root.optional_table("constraints")) {
    if (con->has("max_overshoot"))
      s.max_overshoot = con->number("max_overshoot", Range::non_negative(), "%");
    if (con->has("max_time_at_saturation"))
      s.max_saturation_time = con->number("max_time_at_saturation", Range::non_negative(), "s");
    con->finish();
  }
  if (auto o = root.optional_table("optimizer")) {
    c.initial_points = static_cast<int>(o->integer_or("initial_points", 20, 2, 10000));
    c.max_iterations = static_cast<int>(o->integer_or("max_iterations", 15, 0, 10000));
    c.epsilon = o->number_or("epsilon", 1e-3, Range::non_negative(), "");
    c.relative_epsilon = o->boolean_or("relative_epsilon", false);
    c.patience = static_cast<int>(o->integer_or("patience", 1, 1, 1000));
    c.batch_size = static_cast<int>(o->integer_or("batch_size", 2, 1, 64));
    c.solver = o->choice_or("solver", "pso", {"pso", "nlopt"});
    c.failure_policy = o->choice_or("failure_policy", "classify", {"classify", "impute"});
    c.seed = static_cast<std::uint64_t>(
        o->integer_or("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));
    if (auto t = o->optional_numbers("theta_bounds", 2, 2, Range::positive(), "")) {
      c.kriging.theta_min = (*t)[0];
      c.kriging.theta_max = (*t)[1];
      if (c.kriging.theta_min >= c.kriging.theta_max)
        o->fail("theta_bounds", "the lower bound must be below the upper");
    }
    o->finish();
  }
  root.finish();
  doc.check();
  return s;
}

struct Outcome {
  std::optional<double> value;
  std::string failure;
  json metrics;
};

engine::CaseSpec with_gains(const Study& s, const Eigen::VectorXd& x) {
  engine::CaseSpec c = *s.base_case;
  auto& gains = std::get<engine::HeadingStepSpec>(c.manoeuvre).gains;
  for (std::size_t k = 0; k < s.config.names.size(); ++k) {
    const double v = x[static_cast<Eigen::Index>(k)];
    const auto& n = s.config.names[k];
    (n == "kp" ? gains.kp : n == "ki" ? gains.ki : gains.kd) = v;
  }
  return c;
}

Outcome evaluate(const Study& s, const Eigen::VectorXd& x) {
  if (s.function) return {s.function->f(x), "", json::object()};
  const engine::CaseSpec c = with_gains(s, x);
  const engine::CaseRun run = engine::run_case(c);
  if (run.loop.failure) return {std::nullopt, *run.loop.failure, json::object()};
  Outcome o;
  o.metrics = results::manoeuvre_metrics(c, run.loop.series);
  double total = 0;
  for (const auto& [name, w] : s.weights) {
    const auto path =
        std::find_if(objective_indices().begin(), objective_indices().end(), [&](const auto& p) {
          return p.first == name;
        })->second;
    const auto v = metric(o.metrics, path, c.duration);
    if (!v) return {std::nullopt, "index " + name + " is undefined for this response", o.metrics};
    total += w * *v;
  }
  if (s.max_overshoot && o.metrics["overshoot_percent"].get<double>() > *s.max_overshoot) {
    o.failure = fmt::format("overshoot {:.3g} % exceeds the limit {:g} %",
                            o.metrics["overshoot_percent"].get<double>(), *s.max_overshoot);
    return o;
  }
  if (s.max_saturation_time &&
      o.metrics["rudder"]["time_at_saturation_s"].get<double>() > *s.max_saturation_time) {
    o.failure = fmt::format("rudder saturated for {:.3g} s, more than {:g} s",
                            o.metrics["rudder"]["time_at_saturation_s"].get<double>(),
                            *s.max_saturation_time);
    return o;
  }
  o.value = total;
  return o;
}

std::string point_text(const Study& s, const Eigen::VectorXd& x) {
  std::string t;
  for (std::size_t k = 0; k < s.config.names.size(); ++k) {
    t += fmt::format("{}{} {:.4g}", k ? ", " : "", s.config.names[k],
                     x[static_cast<Eigen::Index>(k)]);
  }
  return t;
}

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
  const Study study = read_study(file);
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
      const Outcome o = evaluate(study, x);
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
               best ? *best->value : std::nan(""), best ? point_text(study, best->x) : "-");
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
             point_text(study, best->x));
  convergence_plot(out, opt, study.name);
  if (study.base_case) {
    // Before (the case's own gains) and after (the best gains), as runs, plots and a table.
    std::vector<results::StoredRun> runs;
    for (const auto& [label, c] : {std::pair{std::string("before"), *study.base_case},
                                   std::pair{std::string("after"), with_gains(study, best->x)}}) {
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
    const auto g1 = std::get<engine::HeadingStepSpec>(with_gains(study, best->x).manoeuvre).gains;
    fmt::print("\n{:<28} {:>14} {:>14}\n", "", "before", "after");
    fmt::print("{:<28} {:>14} {:>14}\n", "Kp / Ki / Kd",
               fmt::format("{:.3g}/{:.3g}/{:.3g}", g0.kp, g0.ki, g0.kd),
               fmt::format("{:.3g}/{:.3g}/{:.3g}", g1.kp, g1.ki, g1.kd));
    for (const auto& [label, key] : {std::pair{"ITAE (deg s^2)", "itae_deg_s2"},
                                     {"rise time (s)", "rise_time_s"},
                                     {"settling time (s)", "settling_time_s"},
                                     {"peak (deg)", "peak_deg"},
                                     {"overshoot (%)", "overshoot_percent"}}) {
      auto cell = [&](const json& m) {
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
  auto* cmd = app.add_subcommand(
      "optimize", "Tune PID gains (or a test function) with the Kriging surrogate optimizer");
  cmd->add_option("file", *file, "Optimisation file (TOML); see examples/pid-optimization.toml")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out,-o", *out, "Output directory (default: out/NAME)");
  cmd->footer(
      "Runs in-process on the case's plant: the Latin hypercube first, then EI + MSP batches "
      "until\n"
      "the best value improves by less than epsilon (patience iterations in a row) or the\n"
      "iteration limit. Writes optimization.json after every batch, then convergence plots and,\n"
      "for a case, before/after runs and their comparison.\n"
      "Example: auvloop optimize examples/pid-optimization.toml");
  cmd->callback([file, out, &exit_code] { exit_code = run_optimize(*file, *out); });
}

}  // namespace auvloop::cli
