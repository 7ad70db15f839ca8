// SPDX-License-Identifier: GPL-3.0-or-later
// The daemon's core, independent of the RPC layer: the job queue and its dispatch onto an
// execution backend, the result cache, and the optimisation driver (docs/scheduler.md).
//
// Every public method is thread-safe (one lock). Every state change is committed to the
// StateStore before the method returns, so a daemon killed at any moment restarts where it
// stopped: running jobs are queued again, finished ones are never run again (their results are
// in the cache even when the kill came between the worker's store and the daemon's commit), and
// running optimisations are replayed from their recorded evaluations.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "auvloop/results/cache.hpp"
#include "auvloop/scheduler/backend.hpp"
#include "auvloop/scheduler/bundle.hpp"
#include "auvloop/scheduler/state_store.hpp"
#include "auvloop/scheduler/study.hpp"
#include "auvloop/v1/scheduler.pb.h"

namespace auvloop::scheduler {

// A request the scheduler refuses; `kind` maps onto an RPC status code.
class RequestError : public std::runtime_error {
 public:
  enum class Kind {
    invalid_argument,
    not_found,
    failed_precondition,
    resource_exhausted,
    unavailable
  };
  RequestError(Kind k, const std::string& message) : std::runtime_error(message), kind(k) {}
  Kind kind;
};

struct SchedulerConfig {
  std::filesystem::path state_dir;  // state.db, cache/, jobs/, executions.log
  int slots = 1;                    // jobs running at once
  double default_timeout_s = 24 * 3600;
  std::filesystem::path worker_executable;  // runs `EXE worker ...`
  bool plots = true;  // false: results are stored without plots (made on request)
  // Shown by status():
  std::string socket;
  int tcp_port = 0;
};

// Limits on what one request may carry.
inline constexpr std::size_t kMaxSourceBytes = 1 << 20;  // per file
inline constexpr std::size_t kMaxSourceFiles = 16;
// Evaluations one optimisation may ask for (initial points + iterations x batch size): beyond
// this the Kriging fits alone (cubic in the number of points) would take days.
inline constexpr long kMaxEvaluations = 2000;

class Scheduler {
 public:
  Scheduler(SchedulerConfig config, std::unique_ptr<ExecutionBackend> backend);
  ~Scheduler();  // stop(false)
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  // Recovers the persistent state and starts dispatching.
  void start();
  // Stops dispatching; running jobs are left to finish (drain) or killed, and are queued again.
  void stop(bool drain);

  v1::Job submit_case(const SourceBundle& source, double timeout_s);
  v1::Optimization submit_optimization(const SourceBundle& source, double timeout_s);

  v1::Job job(std::int64_t id);
  std::vector<v1::Job> jobs(const StateStore::JobFilter& filter);
  v1::Optimization optimization(std::int64_t id, bool with_evaluations);
  std::vector<v1::Optimization> optimizations(int limit);
  int cancel_job(std::int64_t id);
  int cancel_optimization(std::int64_t id);
  v1::Optimization resume(std::int64_t id);

  std::vector<v1::Result> results(int limit);
  // `key`: 64 hex digits. Throws RequestError (not_found) when not cached or corrupt.
  v1::Result result(const std::string& key, bool with_manifest);
  std::string result_key_of_job(std::int64_t id);
  // The full key of a unique prefix (at least 6 hex digits) of a cached result's key.
  std::string result_key_of_prefix(const std::string& prefix);
  std::filesystem::path result_dir(const std::string& key);

  v1::DaemonStatus status();

  // Blocks until the state changes after `seen` (or the timeout); returns the new version.
  std::uint64_t wait_for_change(std::uint64_t seen, std::chrono::milliseconds timeout);
  std::uint64_t version();
  bool stopping();

  struct Runtime;  // a running optimisation in memory: study, optimizer, record (opaque)

 private:
  using Lock = std::unique_lock<std::mutex>;

  void dispatch_loop();
  void launch_ready(Lock& lock);
  void launch(JobRecord& job);
  bool complete_from_cache(JobRecord& job);
  // Appends the job's line to executions.log unless the log has one for its key (a worker stopped
  // between storing its result and logging it; executions_log.hpp). Reads the log whole: only for
  // jobs whose worker may have been cut short.
  void log_execution_once(const JobRecord& job, const nlohmann::json& manifest);
  // A worker that did not end on its own: when its result is stored, logs its execution once.
  void log_stored_execution(const JobRecord& job);
  void on_progress(const std::string& id, double t, double total);
  void on_finished(const std::string& id, const ExitInfo& exit);
  // Stores the final state, indexes the cached run (when the job ended with one, as `run`) and
  // tells the job's optimisation.
  void finish_job(JobRecord& job, const results::StoredRun* run = nullptr);
  std::string failure_text(const JobRecord& job, const ExitInfo& exit) const;
  // Recording a job's end threw (and was rolled back): records it as failed without telling its
  // optimisation, which stops with the reason; never throws.
  void record_failed_end(std::int64_t id, const std::string& why);
  void changed();
  // Runs `f` in one transaction. Should it throw, the in-memory optimisations are dropped with
  // the rolled-back changes (they are replayed from the store when next needed), so memory never
  // runs ahead of the database. Defined in scheduler_runtime.hpp.
  template <class F>
  void atomically(F&& f);

  // Optimisation driver (optimization_driver.cpp); all with the lock held.
  Runtime& runtime(std::int64_t id);
  void drive(std::int64_t id);
  // `run`: the job's cached run when the caller has it already (saves a checksum pass).
  void tell(std::int64_t id, const JobRecord& job, const results::StoredRun* run = nullptr);
  JobRecord evaluation_job(const OptimizationRecord& rec, const Runtime& rt,
                           const optimizer::Batch& batch, std::size_t point);
  v1::Optimization to_proto(const OptimizationRecord& rec, bool with_evaluations);
  v1::Job to_proto(const JobRecord& job);

  SchedulerConfig config_;
  std::unique_ptr<ExecutionBackend> backend_;
  results::ResultCache cache_;
  std::mutex mutex_;
  std::condition_variable wake_dispatcher_, state_changed_;
  std::unique_ptr<StateStore> store_;
  std::map<std::int64_t, std::string> running_;  // job id -> key
  std::map<std::int64_t, double> progress_;      // job id -> simulated time (s)
  std::map<std::int64_t, std::unique_ptr<Runtime>> runtimes_;
  std::uint64_t version_ = 0;
  bool started_ = false, stopping_ = false, draining_ = false, driving_ = false;
  bool dispatcher_exit_ = false;  // after stop(): the workers are gone
  std::chrono::steady_clock::time_point started_at_;
  std::thread dispatcher_;
};

// "j12" -> 12 (kind 'j') ; throws RequestError(invalid_argument) for anything else.
std::int64_t parse_id(const std::string& id, char kind);
std::string job_id(std::int64_t id);
std::string optimization_id(std::int64_t id);

}  // namespace auvloop::scheduler
