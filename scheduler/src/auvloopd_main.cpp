// SPDX-License-Identifier: GPL-3.0-or-later
// auvloopd: the scheduler daemon (docs/scheduler.md). `auvloopd worker ...` is the child process
// the daemon starts for each case; users never call it.
#include <unistd.h>

#include <climits>
#include <cstdlib>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "auvloop/scheduler/paths.hpp"
#include "auvloop/scheduler/server.hpp"
#include "auvloop/scheduler/worker.hpp"

namespace {
namespace fs = std::filesystem;
using namespace auvloop::scheduler;

constexpr const char* kFooter = R"(Files:
  STATE_DIR/state.db       jobs, optimisations, result index (SQLite, WAL)
  STATE_DIR/cache/         cached results, one directory per content key
  STATE_DIR/jobs/jN/       each job's input (job.json) and worker log (worker.log)
  STATE_DIR/executions.log one line per case actually computed
  STATE_DIR/token          the TCP bearer token (with --tcp), mode 0600

Usually started through `auvloop daemon start`. Stop it with `auvloop daemon stop`, SIGTERM or
Ctrl-C: running cases are stopped and queued again for the next start. A killed daemon (even
SIGKILL) loses nothing that finished and resumes its optimisations when started again.

Exit codes: 0 stopped cleanly, 2 bad command line, 4 cannot start (the message says why).)";

fs::path self_executable() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return "auvloopd";
  return fs::path(std::string(buf, static_cast<std::size_t>(n)));
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "auvloopd: the auvloop scheduler daemon (queue, worker pool, result cache, "
      "optimisation driver)",
      "auvloopd"};
  app.footer(kFooter);
  DaemonOptions o;
  std::string state_dir = default_state_dir().string(), socket = default_socket().string();
  app.add_option("--state-dir", state_dir, "State directory (env AUVLOOP_STATE_DIR)")
      ->capture_default_str();
  app.add_option("--socket", socket, "Unix socket to listen on (env AUVLOOP_SOCKET)")
      ->capture_default_str();
  app.add_option("--tcp", o.tcp_port,
                 "Also listen on 127.0.0.1:PORT (0: any free port, written to STATE_DIR/tcp-port); "
                 "clients must send the token in STATE_DIR/token")
      ->check(CLI::Range(0, 65535));
  app.add_option("--slots", o.slots, "Cases run at once (default: one per core)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--timeout", o.timeout_s, "Default wall-time limit per case, s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();

  bool no_plots = false;
  app.add_flag("--no-plots", no_plots,
               "Store results without plots (gnuplot costs more than a derivative-plant case); "
               "`auvloop results plot` makes them on request");
  WorkerArgs w;
  auto* worker = app.add_subcommand("worker", "(internal) run one job; started by the daemon");
  worker->group("");  // hidden from --help
  worker->add_option("--job", w.job_file)->required();
  worker->add_option("--cache", w.cache_root)->required();
  worker->add_option("--executions", w.executions_log);
  worker->add_option("--progress-fd", w.progress_fd);
  worker->add_option("--parent-pid", w.parent_pid);
  worker->add_flag("!--no-plots", w.plots);
  CLI11_PARSE(app, argc, argv);
  if (*worker) return run_worker(w);
  o.state_dir = fs::absolute(state_dir);
  o.socket = fs::absolute(socket);
  o.worker_executable = self_executable();
  o.plots = !no_plots;
  return run_daemon(o);
}
