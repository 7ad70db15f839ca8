// SPDX-License-Identifier: GPL-3.0-or-later
// The daemon's overheads, measured against a real auvloopd on a temporary socket:
//   - throughput: trivial cases (0.1 s simulated) submitted at once, jobs finished per second;
//   - dispatch latency: submit -> worker started, and submit -> result, one case at a time;
//   - cache-hit latency: resubmitting a finished case (completes in the reply);
// with two baselines measured in the same run: the same case run in-process (what a job costs
// without the daemon) and a bare Status RPC (the transport's round trip).
//   bench_scheduler [--jobs N] [--slots S]
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <grpcpp/grpcpp.h>

#include "auvloop/engine/case.hpp"
#include "auvloop/v1/scheduler.grpc.pb.h"

extern char** environ;

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Stats {
  double median, p95;
};
Stats stats(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return {v[v.size() / 2], v[std::min(v.size() - 1, v.size() * 95 / 100)]};
}

std::string trivial_case(int i) {
  return fmt::format(
      "name = \"bench\"\n[time]\ndt = 0.01\nduration = {:.4f}\n[manoeuvre]\ntype = "
      "\"heading-step\"\ntarget_heading = 90\n[controller]\nkp = 1.5\nki = 0.6\nkd = 1.0\n",
      0.1 + 0.0001 * i);  // distinct durations: distinct content keys
}

class BenchDaemon {
 public:
  BenchDaemon(int slots) {
    dir_ = fs::temp_directory_path() / fmt::format("auvloop-bench-{}", getpid());
    fs::create_directories(dir_);
    const std::string socket = (dir_ / "d.sock").string();
    std::vector<std::string> args{AUVLOOPD, "--state-dir", (dir_ / "state").string(), "--socket",
                                  socket,   "--slots",     std::to_string(slots),     "--no-plots"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 2, (dir_ / "daemon.log").c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0600);
    posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    for (int i = 0; i < 1000; ++i) {
      stub_ = auvloop::v1::Scheduler::NewStub(
          grpc::CreateChannel("unix:" + socket, grpc::InsecureChannelCredentials()));
      if (status_ok()) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    throw std::runtime_error("auvloopd did not start");
  }
  ~BenchDaemon() {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
    fs::remove_all(dir_);
  }
  bool status_ok() {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(1));
    auvloop::v1::DaemonStatus s;
    return stub_->Status(&ctx, auvloop::v1::StatusRequest(), &s).ok();
  }
  auvloop::v1::Job submit(const std::string& toml) {
    auvloop::v1::SubmitCaseRequest req;
    req.mutable_source()->set_source_name("bench.toml");
    req.mutable_source()->set_toml(toml);
    grpc::ClientContext ctx;
    auvloop::v1::Job job;
    if (!stub_->SubmitCase(&ctx, req, &job).ok()) throw std::runtime_error("submit failed");
    return job;
  }
  auvloop::v1::Job wait(const std::string& id) {
    auvloop::v1::IdRequest req;
    req.set_id(id);
    for (;;) {
      grpc::ClientContext ctx;
      auvloop::v1::Job job;
      stub_->GetJob(&ctx, req, &job);
      if (job.state() >= auvloop::v1::SUCCEEDED) return job;
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  }

 private:
  fs::path dir_;
  pid_t pid_ = -1;
  std::unique_ptr<auvloop::v1::Scheduler::Stub> stub_;
};
}  // namespace

int main(int argc, char** argv) {
  int jobs = 200, slots = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--jobs") jobs = std::stoi(argv[i + 1]);
    if (a == "--slots") slots = std::stoi(argv[i + 1]);
  }
  // Baseline 1: the case in-process.
  std::vector<double> in_process;
  for (int i = 0; i < 50; ++i) {
    const auto t0 = Clock::now();
    auto c = auvloop::engine::parse_case(trivial_case(i), "bench.toml", fs::path("."));
    auvloop::engine::run_case(c);
    in_process.push_back(ms_since(t0));
  }
  BenchDaemon d(slots);
  // Baseline 2: the bare RPC round trip.
  std::vector<double> rpc;
  for (int i = 0; i < 200; ++i) {
    const auto t0 = Clock::now();
    d.status_ok();
    rpc.push_back(ms_since(t0));
  }
  // Dispatch latency, one case at a time on an idle daemon.
  std::vector<double> to_start, to_result;
  for (int i = 0; i < 30; ++i) {
    const auto t0 = Clock::now();
    const auto job = d.submit(trivial_case(100000 + i));
    const auto done = d.wait(job.id());
    to_result.push_back(ms_since(t0));
    to_start.push_back(static_cast<double>(done.started_ms() - done.created_ms()));
  }
  // Cache hits: the same cases again.
  std::vector<double> hit;
  for (int i = 0; i < 30; ++i) {
    const auto t0 = Clock::now();
    const auto job = d.submit(trivial_case(100000 + i));
    hit.push_back(ms_since(t0));
    if (!job.cache_hit()) throw std::runtime_error("expected a cache hit");
  }
  // Throughput.
  const auto t0 = Clock::now();
  std::vector<std::string> ids;
  for (int i = 0; i < jobs; ++i) ids.push_back(d.submit(trivial_case(i)).id());
  const double submit_ms = ms_since(t0);
  for (const auto& id : ids) d.wait(id);
  const double total_s = ms_since(t0) / 1000;

  const auto ip = stats(in_process), rt = stats(rpc), st = stats(to_start), rs = stats(to_result),
             ch = stats(hit);
  fmt::print("auvloopd overheads ({} slots, trivial case: 0.1 s simulated, no plots)\n\n", slots);
  fmt::print("{:<44} {:>10} {:>10}\n", "", "median", "p95");
  fmt::print("{:<44} {:>8.2f}ms {:>8.2f}ms\n", "baseline: the case in-process", ip.median, ip.p95);
  fmt::print("{:<44} {:>8.2f}ms {:>8.2f}ms\n", "baseline: Status RPC round trip", rt.median,
             rt.p95);
  fmt::print("{:<44} {:>8.2f}ms {:>8.2f}ms\n", "dispatch: submit -> worker started", st.median,
             st.p95);
  fmt::print("{:<44} {:>8.2f}ms {:>8.2f}ms\n", "submit -> result (idle daemon)", rs.median, rs.p95);
  fmt::print("{:<44} {:>8.2f}ms {:>8.2f}ms\n", "cache hit: submit -> completed reply", ch.median,
             ch.p95);
  fmt::print("\nthroughput: {} jobs in {:.2f} s = {:.1f} jobs/s (submitting them took {:.0f} ms)\n",
             jobs, total_s, jobs / total_s, submit_ms);
  fmt::print(
      "ratios: per-job cost / in-process run = {:.0f}; cache hit / RPC round trip = {:.1f}\n",
      rs.median / ip.median, ch.median / rt.median);
  return 0;
}
