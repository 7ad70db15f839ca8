// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop daemon start|stop|status`.
#include <chrono>
#include <thread>

#include <fmt/format.h>

#include "cli.hpp"
#include "daemon_connection.hpp"
#include "job_views.hpp"

namespace auvloop::cli {
namespace {

struct StartOptions {
  int slots = 0;
  int tcp_port = -1;
  double timeout_s = 0;
};

void print_status(const v1::DaemonStatus& s) {
  fmt::print("auvloopd {} (pid {}), up {}\n", s.version(), s.pid(), duration_text(s.uptime_s()));
  fmt::print("  socket      {}\n", s.socket());
  if (s.tcp_port() > 0) fmt::print("  tcp         127.0.0.1:{}\n", s.tcp_port());
  fmt::print("  state       {}\n", s.state_dir());
  fmt::print("  slots       {} ({} running, {} queued)\n", s.slots(), s.running(), s.queued());
  fmt::print("  jobs        {} in all; {} optimisation(s) running\n", s.jobs_total(),
             s.optimizations_active());
  fmt::print("  cache       {} result(s) in {}/cache\n", s.cache_entries(), s.state_dir());
}

v1::DaemonStatus fetch_status(DaemonClient& c) {
  return c.call(&v1::Scheduler::Stub::Status, v1::StatusRequest());
}

int start(const ConnectOptions& o, const StartOptions& s) {
  try {
    DaemonClient c(o);
    const auto status = fetch_status(c);
    fmt::print("a daemon is running already:\n");
    print_status(status);
    return kOk;
  } catch (const DaemonUnavailable&) {
  }
  std::vector<std::string> args;
  if (s.slots > 0) args.insert(args.end(), {"--slots", std::to_string(s.slots)});
  if (s.tcp_port >= 0) args.insert(args.end(), {"--tcp", std::to_string(s.tcp_port)});
  if (s.timeout_s > 0) args.insert(args.end(), {"--timeout", fmt::format("{}", s.timeout_s)});
  start_daemon(o, args);
  DaemonClient c(o);
  fmt::print("started:\n");
  print_status(fetch_status(c));
  return kOk;
}

int stop(const ConnectOptions& o, bool drain) {
  DaemonClient c(o);
  v1::ShutdownRequest req;
  req.set_drain(drain);
  v1::ShutdownResponse resp;
  auto ctx = drain ? c.context(true) : c.context();
  const auto st = c.stub().Shutdown(ctx.get(), req, &resp);
  // A daemon going away may cut its own reply short: what counts is that it goes.
  if (st.error_code() != grpc::StatusCode::CANCELLED) c.check(st);
  // Wait until it is gone, so that a following `daemon start` finds the socket free.
  // A drain lasts as long as the running cases; otherwise the daemon is gone within seconds.
  for (int i = 0; drain || i < 200; ++i) {
    if (drain && i % 200 == 199) fmt::print(stderr, "waiting for the running cases to end...\n");
    try {
      DaemonClient probe(o);
      fetch_status(probe);
    } catch (const DaemonUnavailable&) {
      fmt::print("stopped{}\n",
                 drain ? "" : " (running cases are queued again for the next start)");
      return kOk;
    } catch (const RpcError& e) {
      if (e.code != grpc::StatusCode::CANCELLED) throw;  // it is shutting down: wait
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  fmt::print(stderr, "the daemon was asked to stop but still answers\n");
  return kFailed;
}
}  // namespace

void register_daemon_commands(CLI::App& app, int& exit_code) {
  auto* daemon =
      app.add_subcommand("daemon", "Start, stop or query the scheduler daemon (auvloopd)");
  daemon->require_subcommand(1);
  daemon->footer(
      "The daemon queues cases and optimisations, runs them in worker processes, caches every\n"
      "result by content and resumes interrupted optimisations after a restart "
      "(docs/scheduler.md).");
  auto o = std::make_shared<ConnectOptions>();
  auto s = std::make_shared<StartOptions>();
  auto* start_cmd = daemon->add_subcommand("start", "Start auvloopd in the background");
  add_connect_options(start_cmd, *o);
  start_cmd->add_option("--slots", s->slots, "Cases run at once (default: one per core)")
      ->check(CLI::Range(1, 1024));
  start_cmd
      ->add_option("--listen-tcp", s->tcp_port,
                   "Also listen on loopback TCP PORT (0: any), with a token in STATE_DIR/token")
      ->check(CLI::Range(0, 65535));
  start_cmd->add_option("--timeout", s->timeout_s, "Default wall-time limit per case, s")
      ->check(CLI::PositiveNumber);
  start_cmd->callback([o, s, &exit_code] { exit_code = start(*o, *s); });

  auto drain = std::make_shared<bool>(false);
  auto* stop_cmd = daemon->add_subcommand("stop", "Stop the daemon");
  add_connect_options(stop_cmd, *o);
  stop_cmd->add_flag("--drain", *drain, "Wait for running cases to finish first");
  stop_cmd->callback([o, drain, &exit_code] { exit_code = stop(*o, *drain); });

  auto json = std::make_shared<bool>(false);
  auto* status_cmd = daemon->add_subcommand("status", "Show the daemon's state");
  add_connect_options(status_cmd, *o);
  status_cmd->add_flag("--json", *json, "Machine-readable output");
  status_cmd->callback([o, json] {
    DaemonClient c(*o);
    print_json_or(fetch_status(c), *json, print_status);
  });
}

}  // namespace auvloop::cli
