// SPDX-License-Identifier: GPL-3.0-or-later
// The job queue: submission, cache hits, dispatch onto the backend, completion.
#include "auvloop/scheduler/scheduler.hpp"

#include <unistd.h>

#include <charconv>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "auvloop/geometry/file_io.hpp"
#include "auvloop/geometry/input.hpp"
#include "auvloop/results/run_directory.hpp"
#include "auvloop/scheduler/worker.hpp"
#include "executions_log.hpp"
#include "scheduler_runtime.hpp"

namespace auvloop::scheduler {
namespace fs = std::filesystem;
using nlohmann::json;
using Kind = RequestError::Kind;

std::int64_t parse_id(const std::string& id, char kind) {
  std::int64_t n = 0;
  const bool ok =
      id.size() >= 2 && id.size() <= 20 && id[0] == kind &&
      std::from_chars(id.data() + 1, id.data() + id.size(), n).ptr == id.data() + id.size() &&
      n > 0;
  if (!ok) {
    throw RequestError(Kind::invalid_argument,
                       fmt::format("'{}' is not a {} id (expected {}<number>)", id.substr(0, 64),
                                   kind == 'j' ? "job" : "optimisation", kind));
  }
  return n;
}
void check_source_size(const SourceBundle& s) {
  if (s.toml.size() > kMaxSourceBytes || s.source_name.size() > 4096 ||
      s.files.size() > kMaxSourceFiles) {
    throw RequestError(Kind::invalid_argument,
                       fmt::format("the request is too large (at most {} files of {} bytes)",
                                   kMaxSourceFiles, kMaxSourceBytes));
  }
  for (const auto& [name, text] : s.files) {
    if (name.size() > 4096 || text.size() > kMaxSourceBytes) {
      throw RequestError(Kind::invalid_argument, "an attached file is too large");
    }
  }
}

std::string job_id(std::int64_t id) {
  return fmt::format("j{}", id);
}
std::string optimization_id(std::int64_t id) {
  return fmt::format("o{}", id);
}

namespace {
// The last lines of a worker's log, for a failure message.
std::string log_tail(const fs::path& log, std::size_t max_lines = 6) {
  std::ifstream in(log);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line.substr(0, 300));
    if (lines.size() > max_lines) lines.erase(lines.begin());
  }
  std::string out;
  for (const auto& l : lines) out += "\n  | " + l;
  return out;
}

fs::path job_dir(const SchedulerConfig& c, std::int64_t id) {
  return c.state_dir / "jobs" / job_id(id);
}
}  // namespace

Scheduler::Scheduler(SchedulerConfig config, std::unique_ptr<ExecutionBackend> backend)
    : config_(std::move(config)),
      backend_(std::move(backend)),
      cache_((fs::create_directories(config_.state_dir / "cache"), config_.state_dir / "cache")) {
  fs::create_directories(config_.state_dir / "jobs");
  store_ = std::make_unique<StateStore>(config_.state_dir / "state.db");
  backend_->set_callbacks(
      {[this](const std::string& id, double t, double total) { on_progress(id, t, total); },
       [this](const std::string& id, const ExitInfo& e) { on_finished(id, e); }});
}

Scheduler::~Scheduler() {
  stop(false);
}

void Scheduler::start() {
  Lock lock(mutex_);
  const int requeued = store_->requeue_running();
  if (requeued > 0)
    spdlog::info("{} job(s) that were running when the daemon stopped are queued again", requeued);
  for (const auto& rec : store_->optimizations(1 << 30, true)) {
    try {
      atomically([&] { drive(rec.id); });
      spdlog::info("optimisation {} ({}) continues", optimization_id(rec.id), rec.name);
    } catch (const std::exception& e) {
      spdlog::error("optimisation {} cannot continue: {}", optimization_id(rec.id), e.what());
    }
  }
  started_ = true;
  started_at_ = std::chrono::steady_clock::now();
  dispatcher_ = std::thread([this] { dispatch_loop(); });
}

void Scheduler::stop(bool drain) {
  {
    Lock lock(mutex_);
    if (!started_ || stopping_) return;
    stopping_ = true;
    draining_ = drain;
    if (drain) {
      state_changed_.wait(lock, [this] { return running_.empty(); });
    }
  }
  // Workers first (SIGTERM, then SIGKILL after the grace period); their jobs stay `running` in the
  // store and are queued again at the next start. The dispatcher thread outlives them because
  // the workers it spawned die with it (PR_SET_PDEATHSIG is tied to the spawning thread).
  backend_->stop_all();
  {
    Lock lock(mutex_);
    dispatcher_exit_ = true;
  }
  wake_dispatcher_.notify_all();
  if (dispatcher_.joinable()) dispatcher_.join();
  Lock lock(mutex_);
  changed();
}

void Scheduler::changed() {
  ++version_;
  state_changed_.notify_all();
}

bool Scheduler::stopping() {
  Lock lock(mutex_);
  return stopping_;
}

std::uint64_t Scheduler::version() {
  Lock lock(mutex_);
  return version_;
}

std::uint64_t Scheduler::wait_for_change(std::uint64_t seen, std::chrono::milliseconds timeout) {
  Lock lock(mutex_);
  state_changed_.wait_for(lock, timeout, [&] { return version_ != seen; });
  return version_;
}

v1::Job Scheduler::submit_case(const SourceBundle& source, double timeout_s) {
  check_source_size(source);
  engine::CaseSpec spec;
  try {
    spec = parse_case_bundle(source);
  } catch (const input::InputError& e) {
    throw RequestError(Kind::invalid_argument, fmt::format("invalid case:\n{}", e.what()));
  }
  JobRecord job;
  job.name = spec.name;
  job.key = results::content_hash(engine::canonical_json(spec));
  job.payload = {{"bundle", to_json(source)}};
  job.plant = engine::to_string(spec.plant);
  job.duration_s = spec.duration;
  job.timeout_s = timeout_s > 0 ? timeout_s : config_.default_timeout_s;
  job.created_ms = now_ms();
  Lock lock(mutex_);
  if (stopping_) throw RequestError(Kind::failed_precondition, "the daemon is shutting down");
  atomically([&] {
    store_->insert_job(job);
    complete_from_cache(job);
  });
  changed();
  wake_dispatcher_.notify_all();
  return to_proto(job);
}

// Completes a job from the cache when its result is there; a corrupt entry is removed (and the
// job computed again).
bool Scheduler::complete_from_cache(JobRecord& job) {
  const auto hit = cache_.lookup(job.key);
  if (hit.state == results::ResultCache::State::corrupt) {
    spdlog::warn("cache entry {} is corrupt ({}); it is removed and computed again", job.key,
                 hit.problem);
    cache_.remove(job.key);
    store_->forget_result(job.key);
    return false;
  }
  if (hit.state != results::ResultCache::State::valid) return false;
  const auto& m = hit.run->manifest;
  // Its own result only when it had run before. A job queued again after a daemon restart
  // (queued, attempts > 0) may have a worker killed between storing its result and logging its
  // execution: only then is the log read (it grows for the daemon's life), and a missing line
  // recorded. A worker that ended on its own (running) has logged.
  job.cache_hit = job.state != "running" && job.attempts == 0;
  if (job.state != "running" && job.attempts > 0) log_execution_once(job, m);
  job.state = m.value("failure", json()).is_string() ? "failed" : "succeeded";
  job.failure = job.state == "failed" ? m["failure"].get<std::string>() : "";
  job.finished_ms = now_ms();
  if (job.started_ms == 0) job.started_ms = job.finished_ms;
  finish_job(job, &*hit.run);
  return true;
}

void Scheduler::log_execution_once(const JobRecord& job, const json& manifest) {
  const auto log = config_.state_dir / "executions.log";
  if (!execution_logged(log, job.key))
    append_execution(log, job.key, job.name, manifest.value("wall_time_s", 0.0));
}

void Scheduler::log_stored_execution(const JobRecord& job) {
  const auto hit = cache_.lookup(job.key);
  if (hit.state == results::ResultCache::State::valid) log_execution_once(job, hit.run->manifest);
}

void Scheduler::finish_job(JobRecord& job, const results::StoredRun* run) {
  store_->update_job(job);
  progress_.erase(job.id);
  if (run) {  // the job ended with a (verified) cached run: index it
    const auto existing = store_->result(job.key);
    store_->record_result({job.key, job.name, job.plant,
                           job.state == "succeeded" ? "completed" : "failed", job.failure,
                           existing ? existing->created_ms : job.finished_ms,
                           existing ? existing->job_id : job.id});
  }
  if (job.optimization_id) tell(*job.optimization_id, job, run);
}

void Scheduler::dispatch_loop() {
  Lock lock(mutex_);
  while (!dispatcher_exit_) {
    try {
      if (!stopping_) launch_ready(lock);
    } catch (const std::exception& e) {
      spdlog::error("dispatch: {}", e.what());  // never let one bad job stop the daemon
    }
    wake_dispatcher_.wait_for(lock, std::chrono::milliseconds(500));
  }
}

void Scheduler::launch_ready(Lock& /*lock*/) {
  if (static_cast<int>(running_.size()) >= config_.slots) return;
  std::set<std::string> busy;
  for (const auto& [id, key] : running_) busy.insert(key);
  for (const auto& [id, key] : store_->queued_jobs()) {
    if (static_cast<int>(running_.size()) >= config_.slots) break;
    if (busy.contains(key)) continue;  // an identical job runs: this one waits for its result
    auto job = store_->job(id);
    if (!job || job->state != "queued") continue;
    atomically([&] {
      if (!complete_from_cache(*job)) {
        launch(*job);
        busy.insert(key);
      }
    });
    changed();
  }
}

void Scheduler::launch(JobRecord& job) {
  const fs::path dir = job_dir(config_, job.id);
  fs::create_directories(dir);
  json payload = job.payload;
  if (job.optimization_id && !payload.contains("bundle")) {  // stored once, with the optimisation
    // The running optimisation holds its record in memory; reading it back would parse the
    // optimizer's whole state for every launch.
    if (const auto it = runtimes_.find(*job.optimization_id); it != runtimes_.end()) {
      payload["bundle"] = it->second->record.bundle;
    } else if (const auto rec = store_->optimization(*job.optimization_id)) {
      payload["bundle"] = rec->bundle;
    } else {
      throw std::runtime_error(fmt::format("job {}: its optimisation is gone", job_id(job.id)));
    }
  }
  write_file_atomically(dir / "job.json",
                        json{{"key", job.key}, {"payload", payload}}.dump() + "\n");
  job.state = "running";
  job.started_ms = now_ms();
  ++job.attempts;
  std::vector<std::string> argv{config_.worker_executable.string(),
                                "worker",
                                "--job",
                                (dir / "job.json").string(),
                                "--cache",
                                (config_.state_dir / "cache").string(),
                                "--executions",
                                (config_.state_dir / "executions.log").string(),
                                "--progress-fd",
                                "3",
                                "--parent-pid",
                                std::to_string(getpid())};
  if (!config_.plots) argv.emplace_back("--no-plots");
  try {
    backend_->start({job_id(job.id), argv, dir / "worker.log", job.timeout_s});
    running_[job.id] = job.key;
    store_->update_job(job);
  } catch (const std::exception& e) {
    job.state = "failed";
    job.failure = fmt::format("the worker could not be started: {}", e.what());
    job.finished_ms = now_ms();
    finish_job(job);
  }
}

void Scheduler::on_progress(const std::string& id, double t, double /*total*/) {
  Lock lock(mutex_);
  progress_[parse_id(id, 'j')] = t;
  changed();
}

std::string Scheduler::failure_text(const JobRecord& job, const ExitInfo& exit) const {
  const fs::path log = job_dir(config_, job.id) / "worker.log";
  if (exit.timed_out) {
    return fmt::format("timed out after {:g} s (the worker was stopped); log: {}{}", job.timeout_s,
                       log.string(), log_tail(log));
  }
  return fmt::format("the worker {}; log: {}{}",
                     exit.signal ? exit.describe() : "ended with " + exit.describe(), log.string(),
                     log_tail(log));
}

void Scheduler::on_finished(const std::string& id_text, const ExitInfo& exit) {
  Lock lock(mutex_);
  // Whatever happens below, watchers and a draining stop() must hear of it (declared after the
  // lock, so it runs while the lock is still held).
  struct Notify {
    Scheduler& s;
    ~Notify() {
      s.changed();
      s.wake_dispatcher_.notify_all();
    }
  } notify{*this};
  const std::int64_t id = parse_id(id_text, 'j');
  running_.erase(id);
  // A stop that kills its workers leaves their jobs `running`: queued again at the next start.
  // A draining stop records them as they end. A cancelled job was recorded when it was cancelled.
  if (stopping_ && !draining_) return;
  try {
    auto job = store_->job(id);
    if (!job) return;
    // A worker timed out, cancelled or killed may have stored its result and not logged it yet.
    if (!exit.ok()) log_stored_execution(*job);
    if (job->state != "running") return;  // cancelled: recorded when it was cancelled
    atomically([&] {
      job->finished_ms = now_ms();
      // A result stored before the worker was stopped is complete (stored atomically, verified
      // on lookup): the job ends with it, whatever cut the worker short afterwards.
      if (!complete_from_cache(*job)) {
        job->state = "failed";
        job->failure = exit.ok() ? "the worker ended without storing a usable result; log: " +
                                       (job_dir(config_, id) / "worker.log").string()
                                 : failure_text(*job, exit);
        finish_job(*job);
      }
    });
  } catch (const std::exception& e) {
    spdlog::error("job {}: recording its end failed: {}", id_text, e.what());
    record_failed_end(id, e.what());
  }
}

void Scheduler::record_failed_end(std::int64_t id, const std::string& why) {
  try {
    auto job = store_->job(id);
    if (!job || job->state != "running") return;
    atomically([&] {
      job->state = "failed";
      job->failure = "the daemon could not record its end: " + why;
      job->finished_ms = now_ms();
      store_->update_job(*job);
      progress_.erase(id);
      if (!job->optimization_id) return;
      auto rec = store_->optimization(*job->optimization_id);
      if (!rec || rec->state != "running") return;
      rec->state = "failed";
      rec->failure = fmt::format(
          "job {} could not be recorded: {} (`auvloop resume {}` "
          "continues once the cause is fixed)",
          job_id(id), why, optimization_id(rec->id));
      rec->updated_ms = now_ms();
      store_->update_optimization(*rec);
      runtimes_.erase(rec->id);
    });
  } catch (const std::exception& e) {
    spdlog::error("job {}: recording it as failed failed too: {}", job_id(id), e.what());
  }
}

int Scheduler::cancel_job(std::int64_t id) {
  Lock lock(mutex_);
  auto job = store_->job(id);
  if (!job) throw RequestError(Kind::not_found, fmt::format("no job {}", job_id(id)));
  if (!job->active()) return 0;
  // Recorded before the worker is stopped, so a daemon killed meanwhile does not run it again.
  const bool running = job->state == "running";
  atomically([&] {
    job->state = "cancelled";
    job->failure = "cancelled by the user";
    job->finished_ms = now_ms();
    finish_job(*job);
  });
  if (running) backend_->cancel(job_id(id));
  changed();
  return 1;
}

v1::Job Scheduler::job(std::int64_t id) {
  Lock lock(mutex_);
  auto job = store_->job(id);
  if (!job) throw RequestError(Kind::not_found, fmt::format("no job {}", job_id(id)));
  return to_proto(*job);
}

std::vector<v1::Job> Scheduler::jobs(const StateStore::JobFilter& filter) {
  Lock lock(mutex_);
  std::vector<v1::Job> out;
  for (const auto& j : store_->jobs(filter)) out.push_back(to_proto(j));
  return out;
}

v1::Job Scheduler::to_proto(const JobRecord& j) {
  v1::Job p;
  p.set_id(job_id(j.id));
  p.set_name(j.name);
  static const std::map<std::string, v1::State> states{{"queued", v1::QUEUED},
                                                       {"running", v1::RUNNING},
                                                       {"succeeded", v1::SUCCEEDED},
                                                       {"failed", v1::FAILED},
                                                       {"cancelled", v1::CANCELLED}};
  p.set_state(states.at(j.state));
  p.set_key(j.key);
  p.set_cache_hit(j.cache_hit);
  p.set_failure(j.failure);
  const auto it = progress_.find(j.id);
  p.set_simulated_time_s(j.state == "succeeded"  ? j.duration_s
                         : it != progress_.end() ? it->second
                                                 : 0.0);
  p.set_duration_s(j.duration_s);
  p.set_created_ms(j.created_ms);
  p.set_started_ms(j.started_ms);
  p.set_finished_ms(j.finished_ms);
  if (j.optimization_id) {
    p.set_optimization_id(optimization_id(*j.optimization_id));
    p.set_batch(j.batch);
    p.set_point(j.point);
  }
  p.set_log_path((job_dir(config_, j.id) / "worker.log").string());
  if (j.state == "succeeded" || j.cache_hit) p.set_result_path(cache_.path_of(j.key).string());
  if (j.state == "queued") {
    for (const auto& [rid, key] : running_) {
      if (key == j.key) p.set_waiting_for(job_id(rid));
    }
  }
  p.set_plant(j.plant);
  p.set_attempts(j.attempts);
  return p;
}

std::vector<v1::Result> Scheduler::results(int limit) {
  Lock lock(mutex_);
  std::vector<v1::Result> out;
  for (const auto& r : store_->results(limit)) {
    v1::Result p;
    p.set_key(r.key);
    p.set_name(r.name);
    p.set_plant(r.plant);
    p.set_status(r.status);
    p.set_failure(r.failure);
    p.set_created_ms(r.created_ms);
    p.set_path(cache_.path_of(r.key).string());
    out.push_back(std::move(p));
  }
  return out;
}

v1::Result Scheduler::result(const std::string& key, bool with_manifest) {
  // Verified (checksummed) without the lock: the cache's entries are written atomically.
  const auto hit = cache_.lookup(key);
  Lock lock(mutex_);
  if (hit.state == results::ResultCache::State::missing) {
    throw RequestError(Kind::not_found, fmt::format("no cached result {}", key));
  }
  if (hit.state == results::ResultCache::State::corrupt) {
    throw RequestError(Kind::failed_precondition,
                       fmt::format("the cached result {} is corrupt: {} (resubmit the case to "
                                   "compute it again)",
                                   key, hit.problem));
  }
  const auto& m = hit.run->manifest;
  v1::Result p;
  p.set_key(key);
  p.set_name(m.value("name", ""));
  p.set_plant(m.value("plant", ""));
  p.set_status(m.value("status", ""));
  if (m.contains("failure") && m["failure"].is_string()) p.set_failure(m["failure"]);
  p.set_metrics_json(hit.run->metrics.dump(2));
  if (with_manifest) p.set_manifest_json(m.dump(2));
  p.set_path(hit.run->dir.string());
  if (const auto r = store_->result(key)) p.set_created_ms(r->created_ms);
  return p;
}

std::string Scheduler::result_key_of_job(std::int64_t id) {
  Lock lock(mutex_);
  auto job = store_->job(id);
  if (!job) throw RequestError(Kind::not_found, fmt::format("no job {}", job_id(id)));
  if (job->active()) {
    throw RequestError(Kind::failed_precondition,
                       fmt::format("job {} has not finished yet ({})", job_id(id), job->state));
  }
  return job->key;
}

std::string Scheduler::result_key_of_prefix(const std::string& prefix) {
  Lock lock(mutex_);
  const auto keys = store_->result_keys_with_prefix(prefix, 2);
  if (keys.empty())
    throw RequestError(Kind::not_found, fmt::format("no cached result {}...", prefix));
  if (keys.size() > 1) {
    throw RequestError(
        Kind::invalid_argument,
        fmt::format("{} is the start of several result keys: give more digits", prefix));
  }
  return keys.front();
}

fs::path Scheduler::result_dir(const std::string& key) {
  return cache_.path_of(key);
}

v1::DaemonStatus Scheduler::status() {
  Lock lock(mutex_);
  v1::DaemonStatus s;
  s.set_version(results::kEngineVersion);
  s.set_pid(getpid());
  s.set_uptime_s(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_at_).count());
  s.set_slots(config_.slots);
  s.set_running(static_cast<int>(running_.size()));
  s.set_queued(static_cast<int>(store_->count_jobs("queued")));
  s.set_state_dir(config_.state_dir.string());
  s.set_socket(config_.socket);
  s.set_tcp_port(config_.tcp_port);
  s.set_jobs_total(store_->count_jobs());
  s.set_cache_entries(store_->count_results());
  s.set_optimizations_active(static_cast<int>(store_->count_optimizations("running")));
  return s;
}

}  // namespace auvloop::scheduler
