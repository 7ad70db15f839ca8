// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop submit | jobs | status | watch | cancel | resume`: work on the daemon.
#include <fmt/format.h>

#include "auvloop/scheduler/bundle.hpp"
#include "cli.hpp"
#include "daemon_connection.hpp"
#include "job_views.hpp"

namespace auvloop::cli {
namespace {

v1::CaseSource to_source(const scheduler::SourceBundle& b) {
  v1::CaseSource s;
  s.set_source_name(b.source_name);
  s.set_toml(b.toml);
  for (const auto& [name, text] : b.files) (*s.mutable_files())[name] = text;
  return s;
}

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
  *req.mutable_source() = to_source(bundle);
  req.set_timeout_s(o.timeout_s);
  v1::Job job;
  auto ctx = c.context();
  c.check(c.stub().SubmitCase(ctx.get(), req, &job));
  if (!o.wait) {
    if (o.json) {
      fmt::print("{}\n", to_json_text(job));
    } else {
      fmt::print("{} {}: {}{}\n", job.id(), job.name(), state_text(job.state()),
                 job.cache_hit() ? " (from the cache, nothing was run)" : "");
      if (!finished(job.state())) fmt::print("follow it with: auvloop watch {}\n", job.id());
    }
    return finished(job.state()) ? exit_code_of(job.state()) : kOk;
  }
  watch(c, job.id(), o.json);
  v1::IdRequest id;
  id.set_id(job.id());
  auto ctx2 = c.context();
  c.check(c.stub().GetJob(ctx2.get(), id, &job));
  if (o.json) {
    fmt::print("{}\n", to_json_text(job));
  } else {
    print_job(job);
  }
  return exit_code_of(job.state());
}

int submit_optimization(const ConnectOptions& co, const std::string& file, bool wait, bool json) {
  const auto bundle = scheduler::bundle_study_file(file);
  DaemonClient c = connect(co);
  v1::SubmitOptimizationRequest req;
  *req.mutable_source() = to_source(bundle);
  v1::Optimization opt;
  auto ctx = c.context(true);  // the first batch is proposed before the reply
  c.check(c.stub().SubmitOptimization(ctx.get(), req, &opt));
  if (!wait) {
    if (json) {
      fmt::print("{}\n", to_json_text(opt));
    } else {
      fmt::print("{} {}: {}\nfollow it with: auvloop watch {}\n", opt.id(), opt.name(),
                 state_text(opt.state()), opt.id());
    }
    return kOk;
  }
  watch(c, opt.id(), json);
  v1::IdRequest id;
  id.set_id(opt.id());
  auto ctx2 = c.context();
  c.check(c.stub().GetOptimization(ctx2.get(), id, &opt));
  if (json) {
    fmt::print("{}\n", to_json_text(opt));
  } else {
    print_optimization(opt);
  }
  return exit_code_of(opt.state());
}

int list_jobs(const ConnectOptions& co, bool all, const std::string& opt, int limit, bool json) {
  DaemonClient c(co);
  v1::ListJobsRequest req;
  req.set_active_only(!all);
  req.set_optimization_id(opt);
  req.set_limit(limit);
  v1::ListJobsResponse resp;
  auto ctx = c.context();
  c.check(c.stub().ListJobs(ctx.get(), req, &resp));
  if (json) {
    fmt::print("{}\n", to_json_text(resp));
    return kOk;
  }
  if (resp.jobs().empty()) {
    fmt::print("no {}jobs{}\n", all ? "" : "queued or running ",
               all ? "" : " (--all lists finished ones too)");
    return kOk;
  }
  print_job_table_header();
  for (const auto& j : resp.jobs()) print_job_row(j);
  return kOk;
}

int show_status(const ConnectOptions& co, const std::string& id, bool json) {
  DaemonClient c(co);
  v1::IdRequest req;
  req.set_id(id);
  auto ctx = c.context();
  if (id.starts_with("o")) {
    v1::Optimization o;
    c.check(c.stub().GetOptimization(ctx.get(), req, &o));
    if (json) {
      fmt::print("{}\n", to_json_text(o));
    } else {
      print_optimization(o);
    }
    return kOk;
  }
  v1::Job j;
  c.check(c.stub().GetJob(ctx.get(), req, &j));
  if (json) {
    fmt::print("{}\n", to_json_text(j));
  } else {
    print_job(j);
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
    v1::IdRequest req;
    req.set_id(*id);
    v1::CancelResponse resp;
    auto ctx = c.context();
    c.check(c.stub().Cancel(ctx.get(), req, &resp));
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
    v1::IdRequest req;
    req.set_id(*id);
    v1::Optimization o;
    auto ctx = c.context(true);
    c.check(c.stub().Resume(ctx.get(), req, &o));
    fmt::print("{} {}: resumed at batch {} with {} evaluations recorded\n", o.id(), o.name(),
               o.batch(), o.evaluations_done());
    if (*wait) exit_code = exit_code_of(watch(c, o.id()));
  });
}

}  // namespace auvloop::cli
