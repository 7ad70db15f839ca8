// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop submit | jobs | status | watch | cancel | resume`: work on the daemon.
#include <fmt/format.h>

#include "auvloop/scheduler/bundle.hpp"
#include "cli.hpp"
#include "daemon_connection.hpp"
#include "job_views.hpp"

namespace auvloop::cli {
namespace {

int exit_code_of(v1::State s) {
  return s == v1::SUCCEEDED ? kOk : kFailed;
}

struct SubmitOptions {
  ConnectOptions connect;
  std::string file;
  bool wait = false, json = false;
  double timeout_s = 0;
};

int submit(const SubmitOptions& o) {
  // The case is validated here first, so mistakes are reported against the user's own files.
  const auto bundle = scheduler::bundle_case_file(o.file);
  DaemonClient c = connect(o.connect);
  v1::SubmitCaseRequest req;
  *req.mutable_source() = scheduler::to_proto(bundle);
  req.set_timeout_s(o.timeout_s);
  auto job = c.call(&v1::Scheduler::Stub::SubmitCase, req);
  if (!o.wait) {
    print_json_or(job, o.json, [](const v1::Job& j) {
      fmt::print("{} {}: {}{}\n", j.id(), j.name(), state_text(j.state()),
                 j.cache_hit() ? " (from the cache, nothing was run)" : "");
      if (!finished(j.state())) fmt::print("follow it with: auvloop watch {}\n", j.id());
    });
    return finished(job.state()) ? exit_code_of(job.state()) : kOk;
  }
  watch(c, job.id(), o.json);
  job = c.call(&v1::Scheduler::Stub::GetJob, id_request(job.id()));
  print_json_or(job, o.json, print_job);
  return exit_code_of(job.state());
}

int submit_optimization(const ConnectOptions& co, const std::string& file, bool wait, bool json) {
  const auto bundle = scheduler::bundle_study_file(file);
  DaemonClient c = connect(co);
  v1::SubmitOptimizationRequest req;
  *req.mutable_source() = scheduler::to_proto(bundle);
  // No deadline: the daemon proposes the first batch before it replies.
  auto opt = c.call(&v1::Scheduler::Stub::SubmitOptimization, req, true);
  if (!wait) {
    print_json_or(opt, json, [](const v1::Optimization& o) {
      fmt::print("{} {}: {}\nfollow it with: auvloop watch {}\n", o.id(), o.name(),
                 state_text(o.state()), o.id());
    });
    return kOk;
  }
  watch(c, opt.id(), json);
  opt = c.call(&v1::Scheduler::Stub::GetOptimization, id_request(opt.id()));
  print_json_or(opt, json, print_optimization);
  return exit_code_of(opt.state());
}

int list_jobs(const ConnectOptions& co, bool all, const std::string& opt, int limit, bool json) {
  DaemonClient c(co);
  v1::ListJobsRequest req;
  req.set_active_only(!all);
  req.set_optimization_id(opt);
  req.set_limit(limit);
  print_json_or(c.call(&v1::Scheduler::Stub::ListJobs, req), json,
                [all](const v1::ListJobsResponse& resp) {
                  if (resp.jobs().empty()) {
                    fmt::print("no {}jobs{}\n", all ? "" : "queued or running ",
                               all ? "" : " (--all lists finished ones too)");
                    return;
                  }
                  print_job_table_header();
                  for (const auto& j : resp.jobs()) print_job_row(j);
                });
  return kOk;
}

int show_status(const ConnectOptions& co, const std::string& id, bool json) {
  DaemonClient c(co);
  if (id.starts_with("o")) {
    print_json_or(c.call(&v1::Scheduler::Stub::GetOptimization, id_request(id)), json,
                  print_optimization);
  } else {
    print_json_or(c.call(&v1::Scheduler::Stub::GetJob, id_request(id)), json, print_job);
  }
  return kOk;
}

constexpr const char* kIdHelp = "A job (jN) or an optimisation (oN)";
}  // namespace

int optimize_on_daemon(const ConnectOptions& co, const std::string& file, bool wait, bool json) {
  return submit_optimization(co, file, wait, json);
}

void register_job_commands(CLI::App& app, int& exit_code) {
  auto s = std::make_shared<SubmitOptions>();
  auto* submit_cmd = app.add_subcommand("submit", "Queue a case on the daemon");
  submit_cmd->add_option("case", s->file, "Case file (TOML)")->required()->check(CLI::ExistingFile);
  submit_cmd->add_flag("--wait,-w", s->wait, "Follow its progress until it ends");
  submit_cmd->add_option("--timeout", s->timeout_s, "Wall-time limit, s (default: the daemon's)")
      ->check(CLI::PositiveNumber);
  submit_cmd->add_flag("--json", s->json, "Machine-readable output");
  add_connect_options(submit_cmd, s->connect, true);
  submit_cmd->footer(
      "A case computed before (same content key: canonical case + engine version) completes at\n"
      "once from the cache; an identical case in flight is run once for both.\n"
      "Exit codes: 0 queued (or succeeded with --wait), 4 failed, 5 no daemon.\n"
      "Example: auvloop submit examples/heading-step.toml --wait");
  submit_cmd->callback([s, &exit_code] { exit_code = submit(*s); });

  auto co = std::make_shared<ConnectOptions>();
  auto all = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  auto opt = std::make_shared<std::string>();
  auto limit = std::make_shared<int>(50);
  auto* jobs_cmd = app.add_subcommand("jobs", "List queued and running jobs (--all: every job)");
  jobs_cmd->add_flag("--all,-a", *all, "Include finished jobs");
  jobs_cmd->add_option("--optimization", *opt, "Only the evaluations of optimisation oN");
  jobs_cmd->add_option("--limit", *limit, "At most this many, newest first")->capture_default_str();
  jobs_cmd->add_flag("--json", *json, "Machine-readable output");
  add_connect_options(jobs_cmd, *co);
  jobs_cmd->callback([=, &exit_code] { exit_code = list_jobs(*co, *all, *opt, *limit, *json); });

  auto id = std::make_shared<std::string>();
  auto* status_cmd = app.add_subcommand("status", "Show a job or an optimisation");
  status_cmd->add_option("id", *id, kIdHelp)->required();
  status_cmd->add_flag("--json", *json, "Machine-readable output");
  add_connect_options(status_cmd, *co);
  status_cmd->callback([=, &exit_code] { exit_code = show_status(*co, *id, *json); });

  auto* watch_cmd =
      app.add_subcommand("watch", "Follow a job or an optimisation with progress bars");
  watch_cmd->add_option("id", *id, kIdHelp)->required();
  add_connect_options(watch_cmd, *co);
  watch_cmd->footer("Exit codes: 0 it succeeded, 4 it failed or was cancelled.");
  watch_cmd->callback([=, &exit_code] {
    DaemonClient c(*co);
    exit_code = exit_code_of(watch(c, *id));
  });

  auto* cancel_cmd = app.add_subcommand("cancel", "Cancel a job or an optimisation (and its jobs)");
  cancel_cmd->add_option("id", *id, kIdHelp)->required();
  add_connect_options(cancel_cmd, *co);
  cancel_cmd->callback([=] {
    DaemonClient c(*co);
    const auto resp = c.call(&v1::Scheduler::Stub::Cancel, id_request(*id));
    fmt::print("{}: {} job(s) cancelled\n", *id, resp.jobs_cancelled());
  });

  auto wait = std::make_shared<bool>(false);
  auto* resume_cmd = app.add_subcommand("resume", "Continue a cancelled or failed optimisation");
  resume_cmd->add_option("id", *id, "An optimisation (oN)")->required();
  resume_cmd->add_flag("--wait,-w", *wait, "Follow it until it ends");
  add_connect_options(resume_cmd, *co);
  resume_cmd->footer(
      "Nothing that finished runs again: the optimizer replays its recorded evaluations and\n"
      "queues only what is missing. (After a daemon restart, running optimisations resume by\n"
      "themselves.)");
  resume_cmd->callback([=, &exit_code] {
    DaemonClient c(*co);
    const auto o = c.call(&v1::Scheduler::Stub::Resume, id_request(*id), true);
    fmt::print("{} {}: resumed at batch {} with {} evaluations recorded\n", o.id(), o.name(),
               o.batch(), o.evaluations_done());
    if (*wait) exit_code = exit_code_of(watch(c, o.id()));
  });
}

}  // namespace auvloop::cli
