// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop run` and `auvloop compare`: one manoeuvre on a plant, and runs side by side.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include <fmt/format.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"
#include "auvloop/results/run_directory.hpp"
#include "auvloop/scheduler/paths.hpp"
#include "cli.hpp"

namespace auvloop::cli {
namespace {
using nlohmann::json;

struct RunOptions {
  std::string case_file;
  std::string out;
  std::string plant;
  bool quiet = false;
  bool resume = false;
  double checkpoint_every = 0;  // s simulated; 0: the plant's default
  int threads = -1;             // -1: the case's [cfd] threads
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

// The bar, simulated time and, once a few seconds of wall clock give a rate, the ETA (from the
// rate since the first call: a resumed run's or a CFD straight run's own). On a terminal the bar
// is redrawn in place; into a file or a pipe (a batch job's log) a line is printed every
// kLogEvery seconds of wall clock instead.
class ProgressLine {
 public:
  ProgressLine(double total, bool terminal) : total_(total), terminal_(terminal) {}
  static constexpr double kLogEvery = 30;  // s
  void operator()(double t) {
    const auto now = std::chrono::steady_clock::now();
    if (!first_) first_ = std::pair{t, now};
    const double wall = std::chrono::duration<double>(now - first_->second).count();
    const double done = t - first_->first;
    std::string eta;
    if (wall > 3 && done > 0) {
      const double rate = done / wall;  // simulated s per wall s
      const auto left = static_cast<long>((total_ - t) / rate);
      eta = fmt::format(", {:.3g}x real time, ETA {}:{:02d}", rate, left / 60, left % 60);
    }
    if (!terminal_) {
      if (wall < next_log_) return;
      next_log_ = wall + kLogEvery;
      fmt::print(stderr, "  t = {:.2f} / {:.1f} s after {:.0f} s{}\n", t, total_, wall, eta);
      return;
    }
    const int width = 30;
    const int filled = static_cast<int>(width * std::clamp(t / total_, 0.0, 1.0));
    fmt::print(stderr, "\r  [{}{}] t = {:6.2f} / {:.1f} s{}   ",
               std::string(static_cast<std::size_t>(filled), '#'),
               std::string(static_cast<std::size_t>(width - filled), '.'), t, total_, eta);
  }

 private:
  double total_;
  bool terminal_;
  double next_log_ = kLogEvery;  // s of wall clock since the first call
  std::optional<std::pair<double, std::chrono::steady_clock::time_point>> first_;
};

int run_case_command(const RunOptions& o) {
  engine::CaseSpec spec = engine::load_case(o.case_file);
  if (!o.plant.empty()) spec.plant = engine::plant_kind_from_string(o.plant);
  if (o.threads >= 0) spec.cfd.threads = o.threads;  // not in the key: the same bits
  const std::string plant = engine::to_string(spec.plant);
  const std::string out = o.out.empty() ? fmt::format("out/{}-{}", spec.name, plant) : o.out;
  const bool bar = !o.quiet && isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  engine::CaseRunOptions options;
  if (!o.quiet) options.progress = ProgressLine(spec.duration, bar);
  options.checkpoint = out + ".checkpoint";
  options.checkpoint_every = o.checkpoint_every;
  options.checkpoint_key = results::content_hash(engine::canonical_json(spec));
  options.resume = o.resume;
  if (spec.plant == engine::PlantKind::cfd)
    options.straight_run = scheduler::default_state_dir() / "straight-runs" /
                           (results::content_hash(engine::straight_run_json(spec)) + ".flow");
  const bool stopped_run = std::filesystem::exists(options.checkpoint);
  if (stopped_run && !o.quiet)
    fmt::print(stderr, "{} a stopped run's checkpoint, {}\n",
               o.resume ? "continuing from" : "starting afresh beside",
               options.checkpoint.string());
  // The flow kept at [cfd] fields_at, beside the checkpoint until the run directory takes it; a
  // resume keeps what the stopped run wrote.
  if (spec.plant == engine::PlantKind::cfd && !spec.cfd.fields_at.empty()) {
    options.fields = out + ".fields";
    if (!(o.resume && stopped_run)) std::filesystem::remove_all(options.fields);
  }
  const engine::CaseRun run = engine::run_case(spec, options);
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
  report.fields = options.fields;
  const auto written = results::write_run_directory(out, report);
  std::filesystem::remove(options.checkpoint);  // the run's results are complete
  if (!options.fields.empty()) std::filesystem::remove_all(options.fields);
  if (written.fields_warning) fmt::print(stderr, "warning: {}\n", *written.fields_warning);
  if (run.loop.checkpoint_warning)
    fmt::print(stderr, "warning: {}\n", *run.loop.checkpoint_warning);
  if (run.straight_run_warning) fmt::print(stderr, "warning: {}\n", *run.straight_run_warning);
  if (run.fields_warning) fmt::print(stderr, "warning: {}\n", *run.fields_warning);
  if (!o.quiet) {
    fmt::print("{} ({}, {} plant, dt {} s, {} s simulated in {:.3f} s)\n", spec.name,
               spec.manoeuvre_type(), plant, spec.dt, run.loop.final_time, wall);
    if (!run.straight_run.empty())
      fmt::print("  straight run before t = 0: {}\n", run.straight_run);
    if (!run.wall_clock.empty()) {
      double plant_total = 0;
      for (const auto& [phase, seconds] : run.wall_clock)
        if (phase.rfind("of which", 0) != 0) plant_total += seconds;
      std::string split;
      for (const auto& [phase, seconds] : run.wall_clock)
        split += fmt::format("{}{} {:.0f} %", split.empty() ? "" : ", ", phase,
                             plant_total > 0 ? 100 * seconds / plant_total : 0.0);
      fmt::print("  the plant's {:.0f} s of wall clock: {}\n", plant_total, split);
    }
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
  run->add_option("--threads", o->threads,
                  "The CFD plant's threads (overrides [cfd] threads; 0: every core the process "
                  "may use). The results are bitwise the same for any number")
      ->check(CLI::Range(0, 256));
  run->add_flag("--resume", o->resume,
                "Continue a stopped run from its checkpoint (OUT.checkpoint), bitwise as if it "
                "had not stopped; without one, start afresh");
  run->add_option("--checkpoint-every", o->checkpoint_every,
                  "Simulated seconds between checkpoints (default: 1 on the CFD plant, none on "
                  "the others)")
      ->check(CLI::PositiveNumber);
  run->footer(
      "Writes manifest.json, timeseries.csv, metrics.json and plots (PNG, SVG) into the result\n"
      "directory, replacing an earlier result there only once the new one is complete. A CFD\n"
      "run writes a checkpoint beside it (OUT.checkpoint) every simulated second; if the run is\n"
      "stopped (Ctrl-C, a reboot), the same command with --resume continues it; a checkpoint\n"
      "of the case file as it was before an edit is refused. Progress (simulated time, speed\n"
      "against real time, ETA) is a bar on a terminal and a line every 30 s in a log file.\n"
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
