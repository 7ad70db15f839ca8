// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/scheduler/worker.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>

#include <fmt/format.h>

#include "auvloop/geometry/file_io.hpp"
#include "auvloop/geometry/input.hpp"
#include "auvloop/results/cache.hpp"
#include "auvloop/results/manoeuvre_metrics.hpp"
#include "auvloop/scheduler/bundle.hpp"
#include "executions_log.hpp"

namespace auvloop::scheduler {
namespace {
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Test hook (docs/scheduler.md): AUVLOOP_WORKER_FAILPOINT="abort:NAME,hang:OTHER,hang-stored:THIRD"
// aborts, or sleeps until killed, when the case is called NAME (OTHER) before it runs, or sleeps
// until killed after storing its result and before logging its execution (THIRD). Lets the tests
// crash and hang real workers.
void failpoint(const std::string& stage, const std::string& case_name) {
  const char* fp = std::getenv("AUVLOOP_WORKER_FAILPOINT");
  if (!fp) return;
  const std::string list = std::string(",") + fp + ",";
  if (stage == "start" && list.find(",abort:" + case_name + ",") != std::string::npos) std::abort();
  const std::string hang = stage == "start" ? ",hang:" : ",hang-stored:";
  if (list.find(hang + case_name + ",") != std::string::npos) {
    for (;;) pause();
  }
}

class ProgressChannel {
 public:
  explicit ProgressChannel(int fd, double total) : fd_(fd), total_(total) {}
  void operator()(double t) {
    const auto now = Clock::now();
    if (fd_ < 0 || (now - last_ < std::chrono::milliseconds(200) && t < total_)) return;
    last_ = now;
    const std::string line = fmt::format("progress {:.6g} {:.6g}\n", t, total_);
    if (write(fd_, line.data(), line.size()) < 0) fd_ = -1;  // the daemon stopped listening
  }

 private:
  int fd_;
  double total_;
  Clock::time_point last_{};
};

}  // namespace

engine::CaseSpec case_from_payload(const json& payload) {
  const SourceBundle bundle = bundle_from_json(payload.at("bundle"));
  // An optimisation's evaluation names its case inside the optimisation's bundle.
  engine::CaseSpec c =
      payload.contains("case")
          ? parse_bundled_case(bundle_files(bundle), payload["case"], payload["case"])
          : parse_case_bundle(bundle);
  if (payload.contains("gains")) {
    auto* step = std::get_if<engine::HeadingStepSpec>(&c.manoeuvre);
    if (!step) throw std::invalid_argument("gains given for a case that is not a heading step");
    for (const auto& [name, value] : payload["gains"].items()) {
      const double v = value.get<double>();
      if (name == "kp") {
        step->gains.kp = v;
      } else if (name == "ki") {
        step->gains.ki = v;
      } else if (name == "kd") {
        step->gains.kd = v;
      } else {
        throw std::invalid_argument("unknown gain " + name);
      }
    }
  }
  return c;
}

int run_worker(const WorkerArgs& args) {
  // Die with the daemon: a killed daemon re-queues this job when it restarts, so a worker left
  // running would compute it twice.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (args.parent_pid != 0 && getppid() != args.parent_pid) return 4;
  engine::CaseSpec c;
  std::string key;
  try {
    const json job = json::parse(input::read_file(args.job_file));
    key = job.at("key").get<std::string>();
    c = case_from_payload(job.at("payload"));
  } catch (const std::exception& e) {
    fmt::print(stderr, "worker: the job cannot be read:\n{}\n", e.what());
    return 3;
  }
  const json canonical = engine::canonical_json(c);
  if (results::content_hash(canonical) != key) {
    fmt::print(stderr,
               "worker: the case's content key differs from the daemon's ({}): "
               "different auvloop versions?\n",
               key);
    return 3;
  }
  failpoint("start", c.name);
  fmt::print("worker: {} ({}), {:g} s simulated at dt {:g} s\n", c.name, key, c.duration, c.dt);
  ProgressChannel progress(args.progress_fd, c.duration);
  const auto start = Clock::now();
  // A CFD case: its straight run shared through the state directory (beside the cache), and a
  // checkpoint in the job's directory, from which a job queued again after a stop continues.
  engine::CaseRunOptions options;
  options.progress = [&](double t) { progress(t); };
  if (c.plant == engine::PlantKind::cfd) {
    options.straight_run = args.cache_root.parent_path() / "straight-runs" /
                           (results::content_hash(engine::straight_run_json(c)) + ".flow");
    options.checkpoint = args.job_file.parent_path() / "loop.checkpoint";
    options.checkpoint_key = key;
    options.resume = true;
    if (!c.cfd.fields_at.empty()) options.fields = args.job_file.parent_path() / "fields";
  }
  engine::CaseRun run;
  try {
    run = engine::run_case(c, options);
  } catch (const engine::CheckpointError& e) {  // a damaged or foreign checkpoint: afresh
    fmt::print(stderr, "worker: {}; starting afresh\n", e.what());
    std::error_code ignored;
    std::filesystem::remove(options.checkpoint, ignored);
    if (!options.fields.empty()) std::filesystem::remove_all(options.fields, ignored);
    options.resume = false;
    run = engine::run_case(c, options);
  }
  if (!run.straight_run.empty()) fmt::print("worker: straight run {}\n", run.straight_run);
  if (run.straight_run_warning) fmt::print(stderr, "worker: {}\n", *run.straight_run_warning);
  if (run.fields_warning) fmt::print(stderr, "worker: {}\n", *run.fields_warning);
  if (run.loop.resumed_at >= 0)
    fmt::print("worker: resumed at step {} from {}\n", run.loop.resumed_at,
               options.checkpoint.string());
  progress(c.duration);
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  results::RunReport report{
      c.name,         canonical, run.loop.series, results::manoeuvre_metrics(c, run.loop.series),
      run.plant_name, wall,      run.loop.failure};
  report.fields = options.fields;
  try {
    results::ResultCache(args.cache_root).store(report, {.plots = args.plots});
  } catch (const std::exception& e) {
    fmt::print(stderr, "worker: the result cannot be stored: {}\n", e.what());
    return 4;
  }
  if (!options.checkpoint.empty()) {
    std::error_code ignored;
    std::filesystem::remove(options.checkpoint, ignored);
    if (!options.fields.empty()) std::filesystem::remove_all(options.fields, ignored);
  }
  failpoint("stored", c.name);
  append_execution(args.executions_log, key, c.name, wall);
  fmt::print("worker: {} in {:.3f} s{}\n", run.loop.failure ? "failed" : "done", wall,
             run.loop.failure ? ": " + *run.loop.failure : "");
  return 0;
}

}  // namespace auvloop::scheduler
