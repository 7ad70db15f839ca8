// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/scheduler/state_store.hpp"

#include <chrono>

#include <SQLiteCpp/SQLiteCpp.h>

namespace auvloop::scheduler {
namespace {
using nlohmann::json;

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS jobs (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  name TEXT NOT NULL,
  key TEXT NOT NULL,
  state TEXT NOT NULL,
  payload TEXT NOT NULL,
  plant TEXT NOT NULL,
  duration_s REAL NOT NULL,
  timeout_s REAL NOT NULL,
  cache_hit INTEGER NOT NULL DEFAULT 0,
  failure TEXT NOT NULL DEFAULT '',
  optimization_id INTEGER,
  batch INTEGER NOT NULL DEFAULT -1,
  point INTEGER NOT NULL DEFAULT -1,
  created_ms INTEGER NOT NULL,
  started_ms INTEGER NOT NULL DEFAULT 0,
  finished_ms INTEGER NOT NULL DEFAULT 0,
  attempts INTEGER NOT NULL DEFAULT 0);
CREATE INDEX IF NOT EXISTS jobs_by_state ON jobs(state, id);
CREATE INDEX IF NOT EXISTS jobs_by_evaluation ON jobs(optimization_id, batch, point, id);
CREATE TABLE IF NOT EXISTS optimizations (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  name TEXT NOT NULL,
  state TEXT NOT NULL,
  failure TEXT NOT NULL DEFAULT '',
  bundle TEXT NOT NULL,
  optimizer TEXT NOT NULL,
  timeout_s REAL NOT NULL,
  created_ms INTEGER NOT NULL,
  updated_ms INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS results (
  key TEXT PRIMARY KEY,
  name TEXT NOT NULL,
  plant TEXT NOT NULL,
  status TEXT NOT NULL,
  failure TEXT NOT NULL DEFAULT '',
  created_ms INTEGER NOT NULL,
  job_id INTEGER NOT NULL);
)sql";

constexpr const char* kJobColumns =
    "id, name, key, state, payload, plant, duration_s, timeout_s, cache_hit, failure, "
    "optimization_id, batch, point, created_ms, started_ms, finished_ms, attempts";
// The same without the payload (a listing has no use for it).
constexpr const char* kJobListColumns =
    "id, name, key, state, 'null', plant, duration_s, timeout_s, cache_hit, failure, "
    "optimization_id, batch, point, created_ms, started_ms, finished_ms, attempts";

JobRecord read_job(SQLite::Statement& q) {
  JobRecord j;
  j.id = q.getColumn(0).getInt64();
  j.name = q.getColumn(1).getString();
  j.key = q.getColumn(2).getString();
  j.state = q.getColumn(3).getString();
  j.payload = json::parse(q.getColumn(4).getString());
  j.plant = q.getColumn(5).getString();
  j.duration_s = q.getColumn(6).getDouble();
  j.timeout_s = q.getColumn(7).getDouble();
  j.cache_hit = q.getColumn(8).getInt() != 0;
  j.failure = q.getColumn(9).getString();
  if (!q.getColumn(10).isNull()) j.optimization_id = q.getColumn(10).getInt64();
  j.batch = q.getColumn(11).getInt();
  j.point = q.getColumn(12).getInt();
  j.created_ms = q.getColumn(13).getInt64();
  j.started_ms = q.getColumn(14).getInt64();
  j.finished_ms = q.getColumn(15).getInt64();
  j.attempts = q.getColumn(16).getInt();
  return j;
}

std::vector<JobRecord> read_jobs(SQLite::Statement& q) {
  std::vector<JobRecord> out;
  while (q.executeStep()) out.push_back(read_job(q));
  return out;
}

OptimizationRecord read_optimization(SQLite::Statement& q) {
  OptimizationRecord o;
  o.id = q.getColumn(0).getInt64();
  o.name = q.getColumn(1).getString();
  o.state = q.getColumn(2).getString();
  o.failure = q.getColumn(3).getString();
  o.bundle = json::parse(q.getColumn(4).getString());
  o.optimizer = json::parse(q.getColumn(5).getString());
  o.timeout_s = q.getColumn(6).getDouble();
  o.created_ms = q.getColumn(7).getInt64();
  o.updated_ms = q.getColumn(8).getInt64();
  return o;
}

constexpr const char* kOptimizationColumns =
    "id, name, state, failure, bundle, optimizer, timeout_s, created_ms, updated_ms";

ResultRecord read_result(SQLite::Statement& q) {
  return {q.getColumn(0).getString(), q.getColumn(1).getString(), q.getColumn(2).getString(),
          q.getColumn(3).getString(), q.getColumn(4).getString(), q.getColumn(5).getInt64(),
          q.getColumn(6).getInt64()};
}
constexpr const char* kResultColumns = "key, name, plant, status, failure, created_ms, job_id";
}  // namespace

std::int64_t now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

StateStore::StateStore(const std::filesystem::path& database)
    : db_(std::make_unique<SQLite::Database>(database.string(),
                                             SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE)) {
  db_->exec("PRAGMA journal_mode = WAL");
  // FULL: a commit is on disk before it returns, so a reboot loses nothing that was reported.
  db_->exec("PRAGMA synchronous = FULL");
  db_->exec("PRAGMA foreign_keys = ON");
  db_->setBusyTimeout(5000);
  SQLite::Transaction t(*db_);
  db_->exec(kSchema);
  t.commit();
}

StateStore::~StateStore() = default;

StateStore::Transaction::Transaction(StateStore& s)
    : t_(std::make_unique<SQLite::Transaction>(*s.db_)) {}
StateStore::Transaction::~Transaction() = default;
void StateStore::Transaction::commit() {
  t_->commit();
}

std::int64_t StateStore::insert_job(JobRecord& j) {
  SQLite::Statement q(*db_,
                      "INSERT INTO jobs (name, key, state, payload, plant, duration_s, timeout_s, "
                      "cache_hit, failure, optimization_id, batch, point, created_ms, started_ms, "
                      "finished_ms, attempts) VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)");
  q.bind(1, j.name);
  q.bind(2, j.key);
  q.bind(3, j.state);
  q.bind(4, j.payload.dump());
  q.bind(5, j.plant);
  q.bind(6, j.duration_s);
  q.bind(7, j.timeout_s);
  q.bind(8, j.cache_hit ? 1 : 0);
  q.bind(9, j.failure);
  if (j.optimization_id) {
    q.bind(10, *j.optimization_id);
  } else {
    q.bind(10);
  }
  q.bind(11, j.batch);
  q.bind(12, j.point);
  q.bind(13, j.created_ms);
  q.bind(14, j.started_ms);
  q.bind(15, j.finished_ms);
  q.bind(16, j.attempts);
  q.exec();
  j.id = db_->getLastInsertRowid();
  return j.id;
}

void StateStore::update_job(const JobRecord& j) {
  SQLite::Statement q(*db_,
                      "UPDATE jobs SET state = ?, cache_hit = ?, failure = ?, started_ms = ?, "
                      "finished_ms = ?, attempts = ? WHERE id = ?");
  q.bind(1, j.state);
  q.bind(2, j.cache_hit ? 1 : 0);
  q.bind(3, j.failure);
  q.bind(4, j.started_ms);
  q.bind(5, j.finished_ms);
  q.bind(6, j.attempts);
  q.bind(7, j.id);
  q.exec();
}

std::optional<JobRecord> StateStore::job(std::int64_t id) const {
  SQLite::Statement q(*db_, std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?");
  q.bind(1, id);
  if (!q.executeStep()) return std::nullopt;
  return read_job(q);
}

std::vector<JobRecord> StateStore::jobs(const JobFilter& f) const {
  std::string sql = std::string("SELECT ") + kJobListColumns + " FROM jobs WHERE 1";
  if (f.optimization_id) sql += " AND optimization_id = ?";
  if (f.active_only) sql += " AND state IN ('queued', 'running')";
  sql += " ORDER BY id DESC LIMIT ?";
  SQLite::Statement q(*db_, sql);
  int k = 1;
  if (f.optimization_id) q.bind(k++, *f.optimization_id);
  q.bind(k, f.limit);
  return read_jobs(q);
}

std::vector<std::pair<std::int64_t, std::string>> StateStore::queued_jobs() const {
  SQLite::Statement q(*db_, "SELECT id, key FROM jobs WHERE state = 'queued' ORDER BY id ASC");
  std::vector<std::pair<std::int64_t, std::string>> out;
  while (q.executeStep()) out.emplace_back(q.getColumn(0).getInt64(), q.getColumn(1).getString());
  return out;
}

std::optional<JobRecord> StateStore::evaluation_job(std::int64_t optimization, int batch,
                                                    int point) const {
  SQLite::Statement q(*db_, std::string("SELECT ") + kJobColumns +
                                " FROM jobs WHERE optimization_id = ? AND batch = ? AND point = ? "
                                "ORDER BY id DESC LIMIT 1");
  q.bind(1, optimization);
  q.bind(2, batch);
  q.bind(3, point);
  if (!q.executeStep()) return std::nullopt;
  return read_job(q);
}

std::int64_t StateStore::count_jobs(const std::string& state) const {
  if (state.empty()) return db_->execAndGet("SELECT COUNT(*) FROM jobs").getInt64();
  SQLite::Statement q(*db_, "SELECT COUNT(*) FROM jobs WHERE state = ?");
  q.bind(1, state);
  q.executeStep();
  return q.getColumn(0).getInt64();
}

std::int64_t StateStore::count_optimizations(const std::string& state) const {
  SQLite::Statement q(*db_, "SELECT COUNT(*) FROM optimizations WHERE state = ?");
  q.bind(1, state);
  q.executeStep();
  return q.getColumn(0).getInt64();
}

std::int64_t StateStore::count_results() const {
  return db_->execAndGet("SELECT COUNT(*) FROM results").getInt64();
}

int StateStore::requeue_running() {
  return db_->exec("UPDATE jobs SET state = 'queued' WHERE state = 'running'");
}

std::int64_t StateStore::insert_optimization(OptimizationRecord& o) {
  SQLite::Statement q(*db_,
                      "INSERT INTO optimizations (name, state, failure, bundle, optimizer, "
                      "timeout_s, created_ms, updated_ms) VALUES (?,?,?,?,?,?,?,?)");
  q.bind(1, o.name);
  q.bind(2, o.state);
  q.bind(3, o.failure);
  q.bind(4, o.bundle.dump());
  q.bind(5, o.optimizer.dump());
  q.bind(6, o.timeout_s);
  q.bind(7, o.created_ms);
  q.bind(8, o.updated_ms);
  q.exec();
  o.id = db_->getLastInsertRowid();
  return o.id;
}

void StateStore::update_optimization(const OptimizationRecord& o) {
  SQLite::Statement q(*db_,
                      "UPDATE optimizations SET state = ?, failure = ?, optimizer = ?, "
                      "updated_ms = ? WHERE id = ?");
  q.bind(1, o.state);
  q.bind(2, o.failure);
  q.bind(3, o.optimizer.dump());
  q.bind(4, o.updated_ms);
  q.bind(5, o.id);
  q.exec();
}

std::optional<OptimizationRecord> StateStore::optimization(std::int64_t id) const {
  SQLite::Statement q(
      *db_, std::string("SELECT ") + kOptimizationColumns + " FROM optimizations WHERE id = ?");
  q.bind(1, id);
  if (!q.executeStep()) return std::nullopt;
  return read_optimization(q);
}

std::vector<OptimizationRecord> StateStore::optimizations(int limit, bool running_only) const {
  SQLite::Statement q(*db_, std::string("SELECT ") + kOptimizationColumns + " FROM optimizations" +
                                (running_only ? " WHERE state = 'running'" : "") +
                                " ORDER BY id DESC LIMIT ?");
  q.bind(1, limit);
  std::vector<OptimizationRecord> out;
  while (q.executeStep()) out.push_back(read_optimization(q));
  return out;
}

void StateStore::record_result(const ResultRecord& r) {
  SQLite::Statement q(*db_, std::string("INSERT OR REPLACE INTO results (") + kResultColumns +
                                ") VALUES (?,?,?,?,?,?,?)");
  q.bind(1, r.key);
  q.bind(2, r.name);
  q.bind(3, r.plant);
  q.bind(4, r.status);
  q.bind(5, r.failure);
  q.bind(6, r.created_ms);
  q.bind(7, r.job_id);
  q.exec();
}

std::vector<ResultRecord> StateStore::results(int limit) const {
  SQLite::Statement q(*db_, std::string("SELECT ") + kResultColumns +
                                " FROM results ORDER BY created_ms DESC, key LIMIT ?");
  q.bind(1, limit);
  std::vector<ResultRecord> out;
  while (q.executeStep()) out.push_back(read_result(q));
  return out;
}

std::optional<ResultRecord> StateStore::result(const std::string& key) const {
  SQLite::Statement q(*db_,
                      std::string("SELECT ") + kResultColumns + " FROM results WHERE key = ?");
  q.bind(1, key);
  if (!q.executeStep()) return std::nullopt;
  return read_result(q);
}

std::vector<std::string> StateStore::result_keys_with_prefix(const std::string& prefix,
                                                             int limit) const {
  // Keys are hex, so a range query needs no escaping: prefix <= key < prefix + "g".
  SQLite::Statement q(*db_, "SELECT key FROM results WHERE key >= ? AND key < ? LIMIT ?");
  q.bind(1, prefix);
  q.bind(2, prefix + "g");
  q.bind(3, limit);
  std::vector<std::string> out;
  while (q.executeStep()) out.push_back(q.getColumn(0).getString());
  return out;
}

void StateStore::forget_result(const std::string& key) {
  SQLite::Statement q(*db_, "DELETE FROM results WHERE key = ?");
  q.bind(1, key);
  q.exec();
}

}  // namespace auvloop::scheduler
