// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/scheduler/study.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "auvloop/geometry/input.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"

namespace auvloop::scheduler {
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

// A metric from metrics.json by dotted path; "not settled" counts as the whole run's duration.
std::optional<double> metric(const json& m, const std::string& path, double duration) {
  const json* node = &m;
  std::size_t start = 0;
  while (start <= path.size()) {
    const auto dot = path.find('.', start);
    const std::string key = path.substr(start, dot - start);
    if (!node->is_object() || !node->contains(key)) return std::nullopt;
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  if (node->is_null()) return path == "settling_time_s" ? std::optional(duration) : std::nullopt;
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

void read_problem(input::Table root, Study& s, const std::string& source_name,
                  const FileSource& files) {
  auto problem = root.table("problem");
  const std::string type = problem.choice("type", {"case", "test-function"});
  auto& c = s.config;
  if (type == "case") {
    s.case_name = bundled_name("", problem.text("case"));
    try {
      const std::string shown = (fs::path(source_name).parent_path() / s.case_name).string();
      s.base_case = parse_bundled_case(files, s.case_name, shown);
      if (!std::holds_alternative<engine::HeadingStepSpec>(s.base_case->manoeuvre)) {
        problem.fail("case", "only heading-step cases have gains to tune");
      }
    } catch (const input::InputError& e) {
      problem.fail("case", fmt::format("the case cannot be used:\n{}", e.what()));
    } catch (const std::invalid_argument& e) {
      problem.fail("case", e.what());
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
}

void read_objective(input::Table root, Study& s) {
  if (auto obj = root.optional_table("objective")) {
    const std::string index = obj->choice_or("index", "itae",
                                             {"itae", "iae", "ise", "overshoot", "settling_time",
                                              "rise_time", "rudder_variation", "weighted"});
    if (index == "weighted") {
      auto w = obj->table("weights");
      for (const auto& [name, path] : objective_indices()) {
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
}

void read_optimizer(input::Table root, optimizer::OptimizerConfig& c) {
  auto o = root.optional_table("optimizer");
  if (!o) return;
  c.initial_points = static_cast<int>(o->integer_or("initial_points", 20, 2, 10000));
  c.max_iterations = static_cast<int>(o->integer_or("max_iterations", 15, 0, 10000));
  c.epsilon = o->number_or("epsilon", 1e-3, Range::non_negative(), "");
  c.relative_epsilon = o->boolean_or("relative_epsilon", false);
  c.patience = static_cast<int>(o->integer_or("patience", 1, 1, 1000));
  c.batch_size = static_cast<int>(o->integer_or("batch_size", 2, 1, 64));
  c.solver = o->choice_or("solver", "pso", {"pso", "nlopt"});
  c.failure_policy = o->choice_or("failure_policy", "classify", {"classify", "impute"});
  c.output_transform =
      o->choice_or("output_transform", c.output_transform, {"none", "log", "auto"});
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
}  // namespace

std::string Study::objective_text() const {
  if (weights.size() == 1 && weights.begin()->second == 1.0) return weights.begin()->first;
  std::string t;
  for (const auto& [index, w] : weights)
    t += fmt::format("{}{:g}*{}", t.empty() ? "" : " + ", w, index);
  return t;
}

Study parse_study(std::string_view text, const std::string& source_name, const FileSource& files) {
  auto doc = input::Document::parse(text, source_name);
  auto root = doc.root();
  Study s;
  s.name = root.text("name");
  root.text_or("description", "");
  read_problem(root, s, source_name, files);
  read_objective(root, s);
  read_optimizer(root, s.config);
  root.finish();
  doc.check();
  return s;
}

Study parse_study_bundle(const SourceBundle& bundle) {
  return parse_study(bundle.toml, bundle.source_name, bundle_files(bundle));
}

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

Outcome objective_from_metrics(const Study& s, const json& metrics, double duration) {
  Outcome o;
  o.metrics = metrics;
  double total = 0;
  for (const auto& [index_name, w] : s.weights) {
    const std::string& name = index_name;  // (clang 14 cannot capture a structured binding)
    const auto& indices = objective_indices();
    const auto it = std::find_if(indices.begin(), indices.end(),
                                 [&](const auto& p) { return p.first == name; });
    const auto v = metric(metrics, it->second, duration);
    if (!v) return {std::nullopt, "index " + name + " is undefined for this response", metrics};
    total += w * *v;
  }
  const auto overshoot = metric(metrics, "overshoot_percent", duration);
  if (s.max_overshoot && overshoot && *overshoot > *s.max_overshoot) {
    o.failure =
        fmt::format("overshoot {:.3g} % exceeds the limit {:g} %", *overshoot, *s.max_overshoot);
    return o;
  }
  const auto saturated = metric(metrics, "rudder.time_at_saturation_s", duration);
  if (s.max_saturation_time && saturated && *saturated > *s.max_saturation_time) {
    o.failure = fmt::format("rudder saturated for {:.3g} s, more than {:g} s", *saturated,
                            *s.max_saturation_time);
    return o;
  }
  o.value = total;
  return o;
}

Outcome evaluate_in_process(const Study& s, const Eigen::VectorXd& x) {
  if (s.function) return {s.function->f(x), "", json::object()};
  const engine::CaseSpec c = with_gains(s, x);
  const engine::CaseRun run = engine::run_case(c);
  if (run.loop.failure) return {std::nullopt, *run.loop.failure, json::object()};
  return objective_from_metrics(s, results::manoeuvre_metrics(c, run.loop.series), c.duration);
}

std::string point_text(const Study& s, const Eigen::VectorXd& x) {
  std::string t;
  for (std::size_t k = 0; k < s.config.names.size(); ++k) {
    t += fmt::format("{}{} {:.4g}", k ? ", " : "", s.config.names[k],
                     x[static_cast<Eigen::Index>(k)]);
  }
  return t;
}

}  // namespace auvloop::scheduler
