// SPDX-License-Identifier: GPL-3.0-or-later
// The optimisation driver: asks the optimizer for a batch, turns each point into a job, tells the
// optimizer each result as the job ends, and records the optimizer's state in the same
// transaction. The optimizer's proposals are a pure function of its configuration and the
// evaluations told so far, so after a restart replaying the recorded state gives the same batch
// again; jobs already queued, running or finished for it are found by (batch, point).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "auvloop/geometry/input.hpp"
#include "auvloop/results/run_directory.hpp"
#include "auvloop/scheduler/scheduler.hpp"
#include "scheduler_runtime.hpp"

namespace auvloop::scheduler {
using nlohmann::json;
using Kind = RequestError::Kind;

namespace {
std::size_t told_count(const optimizer::SurrogateOptimizer& opt) {
  std::size_t n = opt.evaluations().size();
  for (const auto& r : opt.pending_results()) n += r ? 1U : 0U;
  return n;
}

void save(Scheduler::Runtime& rt, StateStore& store) {
  rt.record.optimizer = rt.optimizer.to_json();
  rt.record.updated_ms = now_ms();
  store.update_optimization(rt.record);
}
}  // namespace

v1::Optimization Scheduler::submit_optimization(const SourceBundle& source, double timeout_s) {
  check_source_size(source);
  Study study;
  try {
    study = parse_study_bundle(source);
  } catch (const input::InputError& e) {
    throw RequestError(Kind::invalid_argument, fmt::format("invalid optimisation:\n{}", e.what()));
  }
  const long evaluations = study.config.initial_points +
                           static_cast<long>(study.config.max_iterations) * study.config.batch_size;
  if (evaluations > kMaxEvaluations) {
    throw RequestError(Kind::invalid_argument,
                       fmt::format("the optimisation may ask for {} evaluations (initial_points + "
                                   "max_iterations x batch_size); at most {} are accepted",
                                   evaluations, kMaxEvaluations));
  }
  OptimizationRecord rec;
  rec.name = study.name;
  rec.bundle = to_json(source);
  optimizer::SurrogateOptimizer opt(study.config);
  rec.optimizer = opt.to_json();
  rec.timeout_s = timeout_s > 0 ? timeout_s : config_.default_timeout_s;
  rec.created_ms = rec.updated_ms = now_ms();
  Lock lock(mutex_);
  if (stopping_) throw RequestError(Kind::failed_precondition, "the daemon is shutting down");
  atomically([&] {
    store_->insert_optimization(rec);
    runtimes_[rec.id] = std::make_unique<Runtime>(Runtime{std::move(study), std::move(opt), rec});
    drive(rec.id);
  });
  changed();
  wake_dispatcher_.notify_all();
  return to_proto(*store_->optimization(rec.id), false);
}

Scheduler::Runtime& Scheduler::runtime(std::int64_t id) {
  if (const auto it = runtimes_.find(id); it != runtimes_.end()) return *it->second;
  auto rec = store_->optimization(id);
  if (!rec)
    throw RequestError(Kind::not_found, fmt::format("no optimisation {}", optimization_id(id)));
  // Replaying the evaluations refits the surrogate batch by batch: the proposals come out the
  // same, bit for bit, as those of the run that recorded them.
  Study study = parse_study_bundle(bundle_from_json(rec->bundle));
  auto opt = optimizer::SurrogateOptimizer::from_json(rec->optimizer);
  auto& rt = runtimes_[id];
  rt = std::make_unique<Runtime>(Runtime{std::move(study), std::move(opt), std::move(*rec)});
  return *rt;
}

void Scheduler::drive(std::int64_t id) {
  Runtime& rt = runtime(id);
  if (rt.record.state != "running") return;
  driving_ = true;  // results found on the way are told, not driven again (no recursion)
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{driving_};
  for (;;) {
    const auto batch = rt.optimizer.ask();
    if (!batch) {
      const bool found = rt.optimizer.best().has_value();
      rt.record.state = found ? "succeeded" : "failed";
      rt.record.failure = found ? "" : "no evaluation succeeded";
      save(rt, *store_);
      spdlog::info("optimisation {} ({}) ended: {}", optimization_id(id), rt.record.name,
                   rt.optimizer.stop_reason());
      runtimes_.erase(id);
      return;
    }
    const std::size_t before = told_count(rt.optimizer);
    const auto partial = rt.optimizer.pending_results();
    for (std::size_t i = 0; i < batch->points.size(); ++i) {
      if (i < partial.size() && partial[i]) continue;
      if (rt.study.function) {  // a test function costs nothing: evaluate it here
        rt.optimizer.tell_one(*batch, i, rt.study.function->f(batch->points[i]));
        continue;
      }
      auto job = store_->evaluation_job(id, batch->index, static_cast<int>(i));
      if (job && job->active()) continue;
      // A cancelled job (with its optimisation, perhaps still stopping) is replaced on resume.
      if (job && job->state != "cancelled") {
        tell(id, *job);  // it ended, but the daemon stopped before the optimizer heard of it
        continue;
      }
      JobRecord fresh = evaluation_job(rt.record, rt, *batch, i);
      store_->insert_job(fresh);
      complete_from_cache(fresh);  // tells, when cached
    }
    save(rt, *store_);
    if (told_count(rt.optimizer) == before) return;  // waiting for jobs
  }
}

void Scheduler::tell(std::int64_t id, const JobRecord& job, const results::StoredRun* run) {
  if (!runtimes_.contains(id)) {  // an ended optimisation needs no replay to ignore a result
    const auto rec = store_->optimization(id);
    if (!rec || rec->state != "running") return;
  }
  Runtime& rt = runtime(id);
  if (rt.record.state != "running") return;  // cancelled: the result stays in the cache
  // Only the newest job of an evaluation speaks for it (an older one was replaced on resume).
  const auto newest = store_->evaluation_job(id, job.batch, job.point);
  if (!newest || newest->id != job.id) return;
  const auto batch = rt.optimizer.ask();
  const auto point = static_cast<std::size_t>(job.point);
  if (!batch || batch->index != job.batch || point >= batch->points.size()) return;
  const auto partial = rt.optimizer.pending_results();
  if (point < partial.size() && partial[point]) return;
  Outcome o;
  if (job.state == "succeeded") {
    std::optional<results::StoredRun> looked_up;
    if (!run) looked_up = cache_.lookup(job.key).run;  // a recovered job: read it back
    const results::StoredRun* r = run ? run : (looked_up ? &*looked_up : nullptr);
    o = r ? objective_from_metrics(rt.study, r->metrics, job.duration_s)
          : Outcome{std::nullopt, "the result vanished from the cache"};
  } else {
    o.failure = job.failure.empty() ? job.state : job.failure;
  }
  rt.optimizer.tell_one(*batch, point, o.value, o.failure);
  save(rt, *store_);
  changed();
  if (!driving_) drive(id);  // the next batch, once this one is complete
}

JobRecord Scheduler::evaluation_job(const OptimizationRecord& rec, const Runtime& rt,
                                    const optimizer::Batch& batch, std::size_t point) {
  const Eigen::VectorXd& x = batch.points[point];
  json gains = json::object();
  for (std::size_t k = 0; k < rt.study.config.names.size(); ++k) {
    gains[rt.study.config.names[k]] = x[static_cast<Eigen::Index>(k)];
  }
  const engine::CaseSpec spec = with_gains(rt.study, x);
  JobRecord j;
  j.name = fmt::format("{} #{}.{} {}", rec.name, batch.index, point, batch.origins[point]);
  j.key = results::content_hash(engine::canonical_json(spec));
  // The study's files are stored once, with the optimisation; launch() adds them for the worker.
  j.payload = {{"case", rt.study.case_name}, {"gains", gains}};
  j.plant = engine::to_string(spec.plant);
  j.duration_s = spec.duration;
  j.timeout_s = rec.timeout_s;
  j.optimization_id = rec.id;
  j.batch = batch.index;
  j.point = static_cast<int>(point);
  j.created_ms = now_ms();
  return j;
}

int Scheduler::cancel_optimization(std::int64_t id) {
  Lock lock(mutex_);
  auto rec = store_->optimization(id);
  if (!rec)
    throw RequestError(Kind::not_found, fmt::format("no optimisation {}", optimization_id(id)));
  if (rec->state != "running") return 0;
  std::vector<std::int64_t> running;
  int n = 0;
  atomically([&] {
    rec->state = "cancelled";
    rec->failure = "cancelled by the user";
    rec->updated_ms = now_ms();
    store_->update_optimization(*rec);
    runtimes_.erase(id);
    // Recorded before the workers are stopped, so a daemon killed meanwhile does not run them.
    for (auto& job : store_->jobs({id, true, 1 << 30})) {
      if (job.state == "running") running.push_back(job.id);
      job.state = "cancelled";
      job.failure = "the optimisation was cancelled";
      job.finished_ms = now_ms();
      store_->update_job(job);
      ++n;
    }
  });
  for (const auto j : running) backend_->cancel(job_id(j));
  changed();
  return n;
}

v1::Optimization Scheduler::resume(std::int64_t id) {
  Lock lock(mutex_);
  auto rec = store_->optimization(id);
  if (!rec)
    throw RequestError(Kind::not_found, fmt::format("no optimisation {}", optimization_id(id)));
  if (rec->state == "running") {
    throw RequestError(Kind::failed_precondition,
                       fmt::format("optimisation {} is running already", optimization_id(id)));
  }
  if (rec->state == "succeeded") {
    throw RequestError(Kind::failed_precondition,
                       fmt::format("optimisation {} has finished ({}); nothing to resume",
                                   optimization_id(id), rec->optimizer.value("stop_reason", "")));
  }
  atomically([&] {
    rec->state = "running";
    rec->failure.clear();
    rec->updated_ms = now_ms();
    store_->update_optimization(*rec);
    runtimes_.erase(id);
    drive(id);
  });
  changed();
  wake_dispatcher_.notify_all();
  return to_proto(*store_->optimization(id), false);
}

v1::Optimization Scheduler::optimization(std::int64_t id, bool with_evaluations) {
  Lock lock(mutex_);
  auto rec = store_->optimization(id);
  if (!rec)
    throw RequestError(Kind::not_found, fmt::format("no optimisation {}", optimization_id(id)));
  return to_proto(*rec, with_evaluations);
}

std::vector<v1::Optimization> Scheduler::optimizations(int limit) {
  Lock lock(mutex_);
  std::vector<v1::Optimization> out;
  for (const auto& rec : store_->optimizations(limit)) out.push_back(to_proto(rec, false));
  return out;
}

v1::Optimization Scheduler::to_proto(const OptimizationRecord& rec, bool with_evaluations) {
  static const std::map<std::string, v1::State> states{{"running", v1::RUNNING},
                                                       {"succeeded", v1::SUCCEEDED},
                                                       {"failed", v1::FAILED},
                                                       {"cancelled", v1::CANCELLED}};
  v1::Optimization p;
  p.set_id(optimization_id(rec.id));
  p.set_name(rec.name);
  p.set_state(states.at(rec.state));
  p.set_failure(rec.failure);
  const json& o = rec.optimizer;
  p.set_stop_reason(o.value("stop_reason", ""));
  const auto config = optimizer::config_from_json(o.at("config"));
  for (const auto& n : config.names) p.add_parameter_names(n);
  p.set_initial_points(config.initial_points);
  p.set_max_batches(config.max_iterations + 1);
  if (const auto it = runtimes_.find(rec.id); it != runtimes_.end()) {
    p.set_objective(it->second->study.objective_text());
  }
  int batch = 0, failed = 0, done = 0;
  for (const auto& e : o.at("evaluations")) {
    const int b = e.at("batch").get<int>();
    batch = std::max(batch, b);
    ++done;
    failed += e.at("value").is_null() ? 1 : 0;
    if (!with_evaluations) continue;
    auto* pe = p.add_evaluations();
    pe->set_batch(b);
    pe->set_point(e.at("point").get<int>());
    pe->set_origin(e.value("origin", ""));
    const auto x = e.at("x").get<std::vector<double>>();
    for (std::size_t k = 0; k < x.size() && k < config.names.size(); ++k) {
      (*pe->mutable_parameters())[config.names[k]] = x[k];
    }
    pe->set_has_value(!e.at("value").is_null());
    if (pe->has_value()) pe->set_value(e["value"].get<double>());
    pe->set_failure(e.value("failure", ""));
    if (const auto job = store_->evaluation_job(rec.id, b, pe->point())) {
      pe->set_job_id(job_id(job->id));
    }
  }
  for (const auto& job : store_->jobs({rec.id, true, 1 << 30})) {
    batch = std::max(batch, job.batch);
    if (job.state == "running") {
      p.set_evaluations_running(p.evaluations_running() + 1);
    } else {
      p.set_evaluations_queued(p.evaluations_queued() + 1);
    }
  }
  p.set_batch(batch);
  p.set_evaluations_done(done);
  p.set_evaluations_failed(failed);
  if (o.contains("best") && o["best"].is_object()) {
    p.set_has_best(true);
    p.set_best_value(o["best"]["value"].get<double>());
    const auto x = o["best"]["x"].get<std::vector<double>>();
    for (std::size_t k = 0; k < x.size() && k < config.names.size(); ++k) {
      (*p.mutable_best_parameters())[config.names[k]] = x[k];
    }
  }
  p.set_created_ms(rec.created_ms);
  p.set_updated_ms(rec.updated_ms);
  return p;
}

}  // namespace auvloop::scheduler
