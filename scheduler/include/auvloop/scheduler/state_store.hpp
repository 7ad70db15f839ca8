// SPDX-License-Identifier: GPL-3.0-or-later
// The daemon's persistent state in SQLite (WAL journal, synchronous = FULL, so a committed change
// survives a killed daemon and a power cut): jobs, optimisations and the index of cached results.
// Not thread-safe: the scheduler serialises every call under its own lock.
//
// Invariants: a job's state only moves forward (queued -> running -> succeeded | failed |
// cancelled), except that a daemon restart puts running jobs back to queued; an optimisation's
// `optimizer` column is the SurrogateOptimizer's JSON after every evaluation it has been told,
// written in the same transaction as the evaluation job's final state.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace SQLite {
class Database;
class Transaction;
}  // namespace SQLite

namespace auvloop::scheduler {

std::int64_t now_ms();  // Unix time, ms

struct JobRecord {
  std::int64_t id = 0;
  std::string name;
  std::string key;               // content hash
  std::string state = "queued";  // queued | running | succeeded | failed | cancelled
  // What the worker runs: {"bundle": SourceBundle} for a case; {"case": name, "gains": {...}} for
  // an evaluation, whose bundle is its optimisation's.
  nlohmann::json payload;
  std::string plant;
  double duration_s = 0;  // simulated
  double timeout_s = 0;   // wall
  bool cache_hit = false;
  std::string failure;
  std::optional<std::int64_t> optimization_id;
  int batch = -1, point = -1;  // evaluation (batch, point) of the optimisation
  std::int64_t created_ms = 0, started_ms = 0, finished_ms = 0;
  int attempts = 0;
  [[nodiscard]] bool active() const { return state == "queued" || state == "running"; }
};

struct OptimizationRecord {
  std::int64_t id = 0;
  std::string name;
  std::string state = "running";  // running | succeeded | failed | cancelled
  std::string failure;
  nlohmann::json bundle;     // the study's SourceBundle
  nlohmann::json optimizer;  // SurrogateOptimizer::to_json()
  double timeout_s = 0;      // per evaluation
  std::int64_t created_ms = 0, updated_ms = 0;
};

struct ResultRecord {
  std::string key, name, plant, status, failure;
  std::int64_t created_ms = 0;
  std::int64_t job_id = 0;
};

class StateStore {
 public:
  explicit StateStore(const std::filesystem::path& database);
  ~StateStore();
  StateStore(const StateStore&) = delete;
  StateStore& operator=(const StateStore&) = delete;

  // All changes made while the returned object lives are committed together by commit().
  class Transaction {
   public:
    explicit Transaction(StateStore& s);
    ~Transaction();  // rolls back unless committed
    void commit();

   private:
    std::unique_ptr<SQLite::Transaction> t_;
  };

  std::int64_t insert_job(JobRecord& j);  // sets j.id
  void update_job(const JobRecord& j);    // everything but the payload
  [[nodiscard]] std::optional<JobRecord> job(std::int64_t id) const;
  struct JobFilter {
    std::optional<std::int64_t> optimization_id;
    bool active_only = false;
    int limit = 200;  // newest first
  };
  // Without their payloads (null): job() has them.
  [[nodiscard]] std::vector<JobRecord> jobs(const JobFilter& f) const;
  // (id, key) of the queued jobs, oldest first (light: no payloads).
  [[nodiscard]] std::vector<std::pair<std::int64_t, std::string>> queued_jobs() const;
  // The newest job of evaluation (batch, point) of an optimisation.
  [[nodiscard]] std::optional<JobRecord> evaluation_job(std::int64_t optimization, int batch,
                                                        int point) const;
  // Jobs in `state`, or all of them.
  [[nodiscard]] std::int64_t count_jobs(const std::string& state = "") const;
  [[nodiscard]] std::int64_t count_optimizations(const std::string& state) const;
  [[nodiscard]] std::int64_t count_results() const;
  // Jobs put back to queued (those that were running when the daemon stopped).
  int requeue_running();

  std::int64_t insert_optimization(OptimizationRecord& o);
  void update_optimization(const OptimizationRecord& o);
  [[nodiscard]] std::optional<OptimizationRecord> optimization(std::int64_t id) const;
  [[nodiscard]] std::vector<OptimizationRecord> optimizations(int limit,
                                                              bool running_only = false) const;

  void record_result(const ResultRecord& r);  // insert or replace
  [[nodiscard]] std::vector<ResultRecord> results(int limit) const;
  [[nodiscard]] std::optional<ResultRecord> result(const std::string& key) const;
  void forget_result(const std::string& key);
  // Up to `limit` result keys starting with `prefix` (lower-case hex only).
  [[nodiscard]] std::vector<std::string> result_keys_with_prefix(const std::string& prefix,
                                                                 int limit) const;

 private:
  std::unique_ptr<SQLite::Database> db_;
};

}  // namespace auvloop::scheduler
