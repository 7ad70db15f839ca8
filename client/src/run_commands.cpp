// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop run` and `auvloop compare`: one manoeuvre on a plant, and runs side by side.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>

#include <fmt/format.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"
#include "auvloop/results/run_directory.hpp"
#include "cli.hpp"

namespace auvloop::cli {
namespace {
using nlohmann::json;

struct RunOptions {
  std::string case_file;
  std::string out;
  std::string plant;
  bool quiet = false;
  std::vector<std::string> dirs;
  std::vector<std::string> labels;
};

// "itae_deg_s2" -> value text; nested objects are flattened with a dotted prefix.
void flatten(const json& j, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>& out) {
  for (const auto& [key, value] : j.items()) {
    const std::string name = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      flatten(value, name, out);
    } else if (value.is_null()) {
      out.emplace_back(name, name.find("settling") != std::string::npos ? "not settled" : "n/a");
    } else if (value.is_number()) {
      out.emplace_back(name, fmt::format("{:.6g}", value.get<double>()));
    } else if (value.is_array()) {
      std::string s;
      for (const auto& v : value)
        s += (s.empty() ? "" : " ") +
             (v.is_number() ? fmt::format("{:.4g}", v.get<double>()) : v.dump());
      out.emplace_back(name, s.empty() ? "-" : s);
    } else {
      out.emplace_back(name, value.is_string() ? value.get<std::string>() : value.dump());
    }
  }
}

void progress_line(double t, double total) {
  const int width = 30;
  const int filled = static_cast<int>(width * std::min(1.0, t / total));
  fmt::print(stderr, "\r  [{}{}] t = {:6.1f} / {:.1f} s",
             std::string(static_cast<std::size_t>(filled), '#'),
             std::string(static_cast<std::size_t>(width - filled), '.'), t, total);
}

int run_case_command(const RunOptions& o) {
  engine::CaseSpec spec = engine::load_case(o.case_file);
  if (!o.plant.empty()) spec.plant = engine::plant_kind_from_string(o.plant);
  const std::string plant = engine::to_string(spec.plant);
  const std::string out = o.out.empty() ? fmt::format("out/{}-{}", spec.name, plant) : o.out;
  const bool bar = !o.quiet && isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  const engine::CaseRun run =
      engine::run_case(spec, bar ? [&](double t) { progress_line(t, spec.duration); }
                                 : std::function<void(double)>{});
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (bar) fmt::print(stderr, "\r{:60}\r", "");

  results::RunReport report{spec.name,       engine::canonical_json(spec),
                            run.loop.series, results::manoeuvre_metrics(spec, run.loop.series),
                            run.plant_name,  wall,
                            run.loop.failure};
  if (!run.eigenvalues.empty()) {
    json eig = json::array();
    for (const auto& e : run.eigenvalues) eig.push_back({e.real(), e.imag()});
    report.metrics["linearization_eigenvalues_per_s"] = eig;
  }
  const auto written = results::write_run_directory(out, report);
  if (!o.quiet) {
    fmt::print("{} ({}, {} plant, dt {} s, {} s simulated in {:.3f} s)\n", spec.name,
               spec.manoeuvre_type(), plant, spec.dt, run.loop.final_time, wall);
    std::vector<std::pair<std::string, std::string>> rows;
    flatten(report.metrics, "", rows);
    for (const auto& [k, v] : rows) fmt::print("  {:<40} {}\n", k, v);
    fmt::print("results: {}/ ({})\n", out, fmt::join(written.files, ", "));
  }
  if (written.plot_warning) fmt::print(stderr, "warning: {}\n", *written.plot_warning);
  if (run.loop.failure) {
    fmt::print(stderr, "error: {}\n(the time series up to the last good step is in {})\n",
               *run.loop.failure, out);
    return kFailed;
  }
  return kOk;
}

int compare_command(const RunOptions& o) {
  std::vector<results::StoredRun> runs;
  std::vector<std::string> labels = o.labels;
  for (const auto& d : o.dirs) runs.push_back(results::read_run_directory(d));
  if (!labels.empty() && labels.size() != runs.size()) {
    throw CLI::ValidationError("--label",
                               fmt::format("{} labels for {} runs", labels.size(), runs.size()));
  }
  for (std::size_t i = labels.size(); i < runs.size(); ++i) {
    labels.push_back(fmt::format("{} ({})", runs[i].manifest.value("name", "run"),
                                 runs[i].manifest.value("plant", "?")));
  }
  const auto written = results::write_comparison(o.out, runs, labels);
  // Indices side by side: one row per index, one column per run.
  std::vector<std::vector<std::pair<std::string, std::string>>> cols(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    // Status first: indices of a diverged run cover only the time before it diverged.
    const auto& t = runs[i].series["t"].values;
    cols[i].emplace_back("status", runs[i].manifest.value("status", "?"));
    cols[i].emplace_back("simulated_s", fmt::format("{:.6g}", t.empty() ? 0.0 : t.back()));
    flatten(runs[i].metrics, "", cols[i]);
  }
  fmt::print("{:<36}", "index");
  for (const auto& l : labels) fmt::print(" {:>24}", l.substr(0, 24));
  fmt::print("\n");
  for (const auto& row : cols.front()) {
    const std::string& key = row.first;
    fmt::print("{:<36}", key.substr(0, 36));
    for (const auto& c : cols) {
      const auto it =
          std::find_if(c.begin(), c.end(), [&](const auto& kv) { return kv.first == key; });
      fmt::print(" {:>24}", it == c.end() ? "-" : it->second.substr(0, 24));
    }
    fmt::print("\n");
  }
  fmt::print("plots: {}/ ({})\n", o.out, fmt::join(written.files, ", "));
  if (written.plot_warning) fmt::print(stderr, "warning: {}\n", *written.plot_warning);
  return kOk;
}

}  // namespace

void register_run_commands(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunOptions>();
  auto* run = app.add_subcommand("run", "Run one manoeuvre (a case file) and write its results");
  run->add_option("case", o->case_file, "Case file (TOML); see examples/ and docs/case-file.md")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("--out,-o", o->out, "Result directory (default: out/NAME-PLANT)");
  run->add_option("--plant", o->plant, "Override the case's plant")
      ->check(CLI::IsMember({"derivative", "linearized", "cfd"}));
  run->add_flag("--quiet,-q", o->quiet, "Print nothing but errors");
  run->footer(
      "Writes manifest.json, timeseries.csv, metrics.json and plots (PNG, SVG) into the result\n"
      "directory, replacing an earlier result there only once the new one is complete.\n"
      "Example: auvloop run examples/heading-step.toml --plant linearized");
  run->callback([o, &exit_code] { exit_code = run_case_command(*o); });

  auto* cmp = app.add_subcommand(
      "compare", "Overlay runs in the same plots and print their indices side by side");
  cmp->add_option("dirs", o->dirs, "Result directories written by auvloop run")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmp->add_option("--out,-o", o->out, "Directory for the comparison plots")->required();
  cmp->add_option("--label", o->labels, "One label per run (default: name and plant)");
  cmp->footer(
      "Example: auvloop compare out/heading-step-derivative out/heading-step-linearized --out "
      "out/compare");
  cmp->callback([o, &exit_code] { exit_code = compare_command(*o); });
}

}  // namespace auvloop::cli
