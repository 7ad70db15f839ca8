// SPDX-License-Identifier: GPL-3.0-or-later
#include "job_views.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

namespace auvloop::cli {
namespace {
using Clock = std::chrono::steady_clock;

std::string bar(double fraction, int width = 28) {
  const int filled = static_cast<int>(std::lround(width * std::clamp(fraction, 0.0, 1.0)));
  return "[" + std::string(static_cast<std::size_t>(filled), '#') +
         std::string(static_cast<std::size_t>(width - filled), '.') + "]";
}

std::string params_text(const google::protobuf::Map<std::string, double>& p,
                        const google::protobuf::RepeatedPtrField<std::string>& order) {
  std::string t;
  for (const auto& n : order) {
    const auto it = p.find(n);
    if (it != p.end()) t += fmt::format("{}{} {:.4g}", t.empty() ? "" : ", ", n, it->second);
  }
  return t;
}

// The ETA from the progress rate seen since watching began.
struct Eta {
  Clock::time_point t0 = Clock::now();
  double f0 = -1;
  std::string operator()(double f) {
    if (f0 < 0) f0 = f;
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    if (f <= f0 || dt < 0.5 || f >= 1) return "";
    return ", ETA " + duration_text(dt * (1 - f) / (f - f0));
  }
};

std::string job_line(const v1::Job& j, Eta& eta) {
  if (j.state() == v1::QUEUED) {
    return fmt::format(
        "{} {}: queued{}", j.id(), j.name(),
        j.waiting_for().empty() ? "" : " (waits for the identical " + j.waiting_for() + ")");
  }
  if (j.state() == v1::RUNNING) {
    const double f = j.duration_s() > 0 ? j.simulated_time_s() / j.duration_s() : 0;
    return fmt::format("{} {} {:3.0f} %  t = {:.1f} / {:.1f} s{}", j.id(), bar(f), 100 * f,
                       j.simulated_time_s(), j.duration_s(), eta(f));
  }
  return fmt::format("{} {}: {}{}", j.id(), j.name(), state_text(j.state()),
                     j.cache_hit() ? " (from the cache)" : "");
}

std::string optimization_line(const v1::Optimization& o, Eta& eta) {
  // The budget: the initial design plus at most max_batches - 1 infill batches of the points
  // seen so far per batch; the bar measures evaluations against the budget, the run may stop
  // earlier (epsilon rule).
  const int per_batch =
      o.batch() > 0
          ? std::max(1, (o.evaluations_done() - o.initial_points()) / std::max(1, o.batch()))
          : 2;
  const int budget = o.initial_points() + (o.max_batches() - 1) * per_batch;
  const double f = budget > 0 ? static_cast<double>(o.evaluations_done()) / budget : 0;
  std::string best = o.has_best()
                         ? fmt::format("  best {:.6g} at {}", o.best_value(),
                                       params_text(o.best_parameters(), o.parameter_names()))
                         : "";
  if (finished(o.state())) {
    return fmt::format("{} {}: {} after {} evaluations ({} failed){}{}", o.id(), o.name(),
                       state_text(o.state()), o.evaluations_done(), o.evaluations_failed(),
                       o.stop_reason().empty() ? "" : " - " + o.stop_reason(), best);
  }
  return fmt::format("{} {} batch {}/{}  {} done ({} failed), {} running, {} queued{}{}", o.id(),
                     bar(f, 20), o.batch(), o.max_batches(), o.evaluations_done(),
                     o.evaluations_failed(), o.evaluations_running(), o.evaluations_queued(),
                     eta(f), best);
}
}  // namespace

std::string duration_text(double s) {
  if (s < 10) return fmt::format("{:.2f} s", s);
  if (s < 60) return fmt::format("{:.0f} s", s);
  if (s < 3600) return fmt::format("{:.0f} min {:02.0f} s", std::floor(s / 60), std::fmod(s, 60));
  return fmt::format("{:.0f} h {:02.0f} min", std::floor(s / 3600), std::fmod(s, 3600) / 60);
}

std::string state_text(v1::State s) {
  switch (s) {
    case v1::QUEUED:
      return "queued";
    case v1::RUNNING:
      return "running";
    case v1::SUCCEEDED:
      return "succeeded";
    case v1::FAILED:
      return "failed";
    case v1::CANCELLED:
      return "cancelled";
    default:
      return "unknown";
  }
}

bool finished(v1::State s) {
  return s == v1::SUCCEEDED || s == v1::FAILED || s == v1::CANCELLED;
}

void print_job_table_header() {
  fmt::print("{:<8} {:<10} {:>9} {:<12} {}\n", "ID", "STATE", "PROGRESS", "PLANT", "NAME");
}

void print_job_row(const v1::Job& j) {
  const std::string progress =
      j.state() == v1::RUNNING && j.duration_s() > 0
          ? fmt::format("{:.0f} %", 100 * j.simulated_time_s() / j.duration_s())
      : j.cache_hit() ? "cached"
                      : "";
  fmt::print("{:<8} {:<10} {:>9} {:<12} {}\n", j.id(), state_text(j.state()), progress, j.plant(),
             j.name());
}

void print_job(const v1::Job& j) {
  fmt::print("{} {}: {}{}\n", j.id(), j.name(), state_text(j.state()),
             j.cache_hit() ? " (from the cache, nothing was run)" : "");
  fmt::print("  key       {}\n", j.key());
  fmt::print("  plant     {}, {:g} s simulated\n", j.plant(), j.duration_s());
  if (j.state() == v1::RUNNING) {
    fmt::print("  progress  t = {:.2f} / {:.2f} s\n", j.simulated_time_s(), j.duration_s());
  }
  if (!j.waiting_for().empty()) fmt::print("  waits for the identical job {}\n", j.waiting_for());
  if (!j.optimization_id().empty()) {
    fmt::print("  part of   {} (batch {}, point {})\n", j.optimization_id(), j.batch(), j.point());
  }
  if (j.started_ms() > 0 && j.finished_ms() >= j.started_ms()) {
    fmt::print("  wall time {}\n",
               duration_text(static_cast<double>(j.finished_ms() - j.started_ms()) / 1000));
  }
  if (!j.failure().empty()) fmt::print("  reason    {}\n", j.failure());
  if (!j.result_path().empty()) fmt::print("  result    {}\n", j.result_path());
  if (j.attempts() > 0) fmt::print("  log       {}\n", j.log_path());
}

void print_optimization(const v1::Optimization& o) {
  Eta eta;
  fmt::print("{}\n", optimization_line(o, eta));
  if (!o.failure().empty()) fmt::print("  reason: {}\n", o.failure());
  if (o.evaluations().empty()) return;
  fmt::print("\n  {:>5} {:>5} {:<8} {:<36} {:>14} {}\n", "BATCH", "POINT", "ORIGIN", "PARAMETERS",
             "OBJECTIVE", "JOB");
  for (const auto& e : o.evaluations()) {
    fmt::print("  {:>5} {:>5} {:<8} {:<36} {:>14} {}{}\n", e.batch(), e.point(), e.origin(),
               params_text(e.parameters(), o.parameter_names()),
               e.has_value() ? fmt::format("{:.6g}", e.value()) : "failed", e.job_id(),
               e.failure().empty() ? "" : "  (" + e.failure().substr(0, 80) + ")");
  }
}

v1::State watch(DaemonClient& client, const std::string& id, bool quiet) {
  v1::IdRequest req;
  req.set_id(id);
  auto ctx = client.context(true);
  auto reader = client.stub().Watch(ctx.get(), req);
  const bool tty = isatty(STDERR_FILENO) != 0;
  Eta eta;
  v1::WatchEvent ev;
  v1::State state = v1::STATE_UNSPECIFIED;
  std::string last;
  auto printed = Clock::now();
  while (reader->Read(&ev)) {
    const std::string line =
        ev.has_job() ? job_line(ev.job(), eta) : optimization_line(ev.optimization(), eta);
    const v1::State now = ev.has_job() ? ev.job().state() : ev.optimization().state();
    const bool state_changed = now != state;
    state = now;
    if (quiet || line == last) continue;
    if (tty) {
      fmt::print(stderr, "\r\033[K{}", line);
    } else if (state_changed || Clock::now() - printed > std::chrono::seconds(2)) {
      fmt::print(stderr, "{}\n", line);  // a log file gets a line per change, at most every 2 s
      printed = Clock::now();
    }
    last = line;
  }
  if (tty && !quiet) fmt::print(stderr, "\n");
  client.check(reader->Finish());
  return state;
}

}  // namespace auvloop::cli
