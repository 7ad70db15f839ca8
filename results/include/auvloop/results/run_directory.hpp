// SPDX-License-Identifier: GPL-3.0-or-later
// The on-disk result of one run (docs/results.md):
//   manifest.json    inputs (canonical case), content hash, versions, wall time, status, checksums
//   timeseries.csv   every recorded signal, one header line "name [unit]"
//   metrics.json     the manoeuvre's indices
//   *.png, *.svg     heading, rudder, trajectory, speed and drift angle (gnuplot)
// The directory is assembled under a scratch name beside the target and renamed into place, so
// a reader sees either the previous result or the complete new one.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "auvloop/engine/time_series.hpp"

namespace auvloop::results {

inline constexpr const char* kEngineVersion = "auvloop-engine 0.1.0";

struct RunReport {
  std::string name;
  nlohmann::json canonical_case;
  engine::TimeSeries series;
  nlohmann::json metrics;
  std::string plant;
  double wall_time_s = 0;
  std::optional<std::string> failure;  // the run diverged: series ends at the last good step
  // A CFD run's kept flow (engine::CaseRunOptions::fields; empty: none): copied into the run
  // directory's fields/ (ParaView: fields/flow.pvd) and drawn as stern-speed-t<T>.png and
  // rudder-pressure-t<T>.png.
  std::filesystem::path fields;
};

// SHA-256 (hex) of the canonical case JSON and the engine version: equal inputs, equal key.
std::string content_hash(const nlohmann::json& canonical_case);
std::string sha256_hex(std::string_view data);

struct WriteOutcome {
  std::vector<std::string> files;
  std::optional<std::string> plot_warning;    // plots skipped (gnuplot missing or failed)
  std::optional<std::string> fields_warning;  // the kept flow could not be read (RunReport::fields)
};

struct WriteOptions {
  // false: no gnuplot run (it costs more than a derivative-plant case); the script is kept as
  // kDeferredPlotScript so that the plots can be made later (`auvloop results plot`).
  bool plots = true;
};
inline constexpr const char* kDeferredPlotScript = "plots-deferred.gp";

WriteOutcome write_run_directory(const std::filesystem::path& dir, const RunReport& report,
                                 WriteOptions options = {});

// Reads a run directory back (for compare): the manifest, metrics and time series.
struct StoredRun {
  std::filesystem::path dir;
  nlohmann::json manifest;
  nlohmann::json metrics;
  engine::TimeSeries series;
};
StoredRun read_run_directory(const std::filesystem::path& dir);

// Runs a gnuplot script in `dir` (prepends the common settings); returns a warning when plots
// could not be made (gnuplot missing or failing), nothing on success.
std::optional<std::string> run_gnuplot(const std::filesystem::path& dir, const std::string& script);

// Overlays several runs in the standard plots, written to `dir` (atomically, like a run).
WriteOutcome write_comparison(const std::filesystem::path& dir, const std::vector<StoredRun>& runs,
                              const std::vector<std::string>& labels);

}  // namespace auvloop::results
