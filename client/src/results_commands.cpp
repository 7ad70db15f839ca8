// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop results list|show|export|plot`: the daemon's result cache.
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "auvloop/geometry/file_io.hpp"
#include "auvloop/results/run_directory.hpp"
#include "cli.hpp"
#include "daemon_connection.hpp"
#include "job_views.hpp"

namespace auvloop::cli {
namespace {
namespace fs = std::filesystem;

std::string time_text(std::int64_t ms) {
  const std::time_t t = static_cast<std::time_t>(ms / 1000);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M", std::localtime(&t));
  return buf;
}

int list(const ConnectOptions& co, int limit, bool json) {
  DaemonClient c(co);
  v1::ListResultsRequest req;
  req.set_limit(limit);
  const auto resp = c.call(&v1::Scheduler::Stub::ListResults, req);
  if (json) {
    fmt::print("{}\n", to_json_text(resp));
    return kOk;
  }
  if (resp.results().empty()) {
    fmt::print("the cache is empty\n");
    return kOk;
  }
  fmt::print("{:<16} {:<16} {:<10} {:<11} {}\n", "KEY", "CREATED", "STATUS", "PLANT", "NAME");
  for (const auto& r : resp.results()) {
    fmt::print("{:<16} {:<16} {:<10} {:<11} {}\n", r.key().substr(0, 16), time_text(r.created_ms()),
               r.status(), r.plant(), r.name());
  }
  return kOk;
}

int show(const ConnectOptions& co, const std::string& id, bool json) {
  DaemonClient c(co);
  const auto r = c.call(&v1::Scheduler::Stub::GetResult, id_request(id));
  if (json) {
    fmt::print("{}\n", to_json_text(r));
    return kOk;
  }
  fmt::print("{} ({}, {})\n  key   {}\n  path  {}\n", r.name(), r.plant(), r.status(), r.key(),
             r.path());
  if (!r.failure().empty()) fmt::print("  failure: {}\n", r.failure());
  const auto m = nlohmann::json::parse(r.metrics_json(), nullptr, false);
  if (m.is_object()) {
    for (const auto& [k, v] : m.items()) {
      if (v.is_number()) fmt::print("  {:<28} {:.6g}\n", k, v.get<double>());
      if (v.is_null()) fmt::print("  {:<28} {}\n", k, "n/a (not reached)");
    }
  }
  return kOk;
}

// Writes the result's files (those `keep` accepts) to `out`; returns their paths.
std::vector<fs::path> export_files(const ConnectOptions& co, const std::string& id,
                                   const fs::path& out, bool (*keep)(const std::string&)) {
  DaemonClient c(co);
  auto ctx = c.context(true);
  auto reader = c.stub().ExportResult(ctx.get(), id_request(id));
  fs::create_directories(out);
  std::vector<fs::path> written;
  std::ofstream file;
  std::string current;
  v1::FileChunk chunk;
  while (reader->Read(&chunk)) {
    // Names come from the daemon: accept plain file names only.
    if (chunk.path().empty() || chunk.path().find('/') != std::string::npos ||
        chunk.path() == "." || chunk.path() == ".." || !keep(chunk.path())) {
      continue;
    }
    if (chunk.path() != current) {
      file.close();
      current = chunk.path();
      file.open(out / current, std::ios::binary | std::ios::trunc);
      written.push_back(out / current);
    }
    file.write(chunk.data().data(), static_cast<std::streamsize>(chunk.data().size()));
  }
  file.close();
  c.check(reader->Finish());
  return written;
}

bool any_file(const std::string&) {
  return true;
}
bool plot_file(const std::string& n) {
  return n.ends_with(".png") || n.ends_with(".svg");
}
}  // namespace

void register_results_commands(CLI::App& app, int& exit_code) {
  auto* results = app.add_subcommand("results", "Inspect the daemon's result cache");
  results->require_subcommand(1);
  results->footer(
      "A result is named by its content key (64 hex digits, or a unique prefix of 6 or more) or "
      "by\n"
      "the id of the job that produced it (jN). Results are run directories (docs/results.md)\n"
      "under STATE_DIR/cache/.");
  auto co = std::make_shared<ConnectOptions>();
  auto json = std::make_shared<bool>(false);
  auto limit = std::make_shared<int>(50);
  auto id = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();

  auto* list_cmd = results->add_subcommand("list", "List cached results, newest first");
  list_cmd->add_option("--limit", *limit, "At most this many")->capture_default_str();
  list_cmd->add_flag("--json", *json, "Machine-readable output");
  add_connect_options(list_cmd, *co);
  list_cmd->callback([=, &exit_code] { exit_code = list(*co, *limit, *json); });

  auto* show_cmd = results->add_subcommand("show", "Show a result's indices");
  show_cmd->add_option("id", *id, "Result key or job id")->required();
  show_cmd->add_flag("--json", *json, "Machine-readable output (metrics and manifest)");
  add_connect_options(show_cmd, *co);
  show_cmd->callback([=, &exit_code] { exit_code = show(*co, *id, *json); });

  auto* export_cmd = results->add_subcommand("export", "Copy a result's files to a directory");
  export_cmd->add_option("id", *id, "Result key or job id")->required();
  export_cmd->add_option("--out,-o", *out, "Directory to write")->required();
  add_connect_options(export_cmd, *co);
  export_cmd->callback([=] {
    const auto files = export_files(*co, *id, *out, any_file);
    fmt::print("{} file(s) written to {}/\n", files.size(), *out);
  });

  auto* plot_cmd = results->add_subcommand("plot", "Fetch a result's plots (PNG and SVG)");
  plot_cmd->add_option("id", *id, "Result key or job id")->required();
  plot_cmd->add_option("--out,-o", *out, "Directory to write (default: out/plots-ID)");
  add_connect_options(plot_cmd, *co);
  plot_cmd->callback([=] {
    const fs::path dir =
        out->empty() ? fs::path("out") / ("plots-" + id->substr(0, 16)) : fs::path(*out);
    auto files = export_files(*co, *id, dir, plot_file);
    if (files.empty()) {  // stored without plots (auvloopd --no-plots): make them here
      export_files(*co, *id, dir, any_file);
      const fs::path script = dir / results::kDeferredPlotScript;
      if (!fs::exists(script))
        throw std::runtime_error("the result has neither plots nor a plot script");
      if (auto w = results::run_gnuplot(dir, read_file_text(script))) throw std::runtime_error(*w);
      for (const auto& e : fs::directory_iterator(dir)) {
        if (plot_file(e.path().filename().string())) files.push_back(e.path());
      }
      std::sort(files.begin(), files.end());
    }
    for (const auto& f : files) fmt::print("{}\n", f.string());
  });
}

}  // namespace auvloop::cli
