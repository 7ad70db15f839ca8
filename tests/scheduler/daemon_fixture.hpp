// SPDX-License-Identifier: GPL-3.0-or-later
// A real auvloopd on a temporary socket and state directory, for integration tests.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "auvloop/v1/scheduler.grpc.pb.h"
#include "temp_dir.hpp"

extern char** environ;

namespace auvloop::test {

class Daemon {
 public:
  explicit Daemon(std::vector<std::string> extra_args = {},
                  std::map<std::string, std::string> env = {})
      : extra_(std::move(extra_args)), env_(std::move(env)) {
    // Short: a Unix socket path has at most 107 bytes.
    socket_ = dir_.path() / "d.sock";
    state_ = dir_.path() / "state";
  }
  ~Daemon() { kill9(); }
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  void start() {
    std::vector<std::string> args{AUVLOOPD, "--state-dir", state_.string(), "--socket",
                                  socket_.string()};
    args.insert(args.end(), extra_.begin(), extra_.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> envs;
    for (char** e = environ; *e; ++e) envs.emplace_back(*e);
    for (const auto& [k, v] : env_) envs.push_back(k + "=" + v);
    std::vector<char*> envp;
    for (auto& e : envs) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    const std::string log = (dir_.path() / "daemon.log").string();
    posix_spawn_file_actions_addopen(&fa, 2, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0600);
    if (posix_spawn(&pid_, argv[0], &fa, nullptr, argv.data(), envp.data()) != 0) {
      throw std::runtime_error("cannot start auvloopd");
    }
    posix_spawn_file_actions_destroy(&fa);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
      // A fresh channel per attempt: a failed one backs off for seconds before reconnecting.
      channel_ =
          grpc::CreateChannel("unix:" + socket_.string(), grpc::InsecureChannelCredentials());
      stub_ = v1::Scheduler::NewStub(channel_);
      v1::DaemonStatus s;
      auto c = ctx(1);
      if (stub_->Status(c.get(), v1::StatusRequest(), &s).ok()) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    throw std::runtime_error("auvloopd did not answer within 30 s");
  }

  void kill9() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  // SIGTERM; returns the exit status.
  int stop() {
    ::kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return status;
  }
  // Waits for the daemon to exit by itself; false if it still runs after `timeout_s`.
  bool wait_exit(double timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::milliseconds(static_cast<long>(timeout_s * 1000));
    while (std::chrono::steady_clock::now() < deadline) {
      if (waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = -1;
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }
  [[nodiscard]] bool alive() const { return pid_ > 0 && ::kill(pid_, 0) == 0; }

  v1::Scheduler::Stub& stub() { return *stub_; }
  static std::unique_ptr<grpc::ClientContext> ctx(double timeout_s = 60) {
    auto c = std::make_unique<grpc::ClientContext>();
    c->set_deadline(std::chrono::system_clock::now() +
                    std::chrono::milliseconds(static_cast<long>(timeout_s * 1000)));
    return c;
  }
  [[nodiscard]] const std::filesystem::path& state_dir() const { return state_; }
  [[nodiscard]] const std::filesystem::path& socket() const { return socket_; }
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_.path(); }

  // Keys of the cases actually computed (the workers' accounting log).
  [[nodiscard]] std::vector<std::string> executions() const {
    std::ifstream in(state_ / "executions.log");
    std::vector<std::string> keys;
    for (std::string key, rest; in >> key && std::getline(in, rest);) keys.push_back(key);
    return keys;
  }

  v1::Job submit(const std::string& toml, double timeout_s = 0,
                 std::map<std::string, std::string> files = {}) {
    v1::SubmitCaseRequest req;
    req.mutable_source()->set_source_name("case.toml");
    req.mutable_source()->set_toml(toml);
    for (const auto& [k, v] : files) (*req.mutable_source()->mutable_files())[k] = v;
    req.set_timeout_s(timeout_s);
    v1::Job job;
    auto c = ctx();
    const auto st = stub_->SubmitCase(c.get(), req, &job);
    if (!st.ok()) throw std::runtime_error("SubmitCase: " + st.error_message());
    return job;
  }

  v1::Job job(const std::string& id) {
    v1::IdRequest req;
    req.set_id(id);
    v1::Job job;
    auto c = ctx();
    const auto st = stub_->GetJob(c.get(), req, &job);
    if (!st.ok()) throw std::runtime_error("GetJob: " + st.error_message());
    return job;
  }

  v1::Optimization optimization(const std::string& id) {
    v1::IdRequest req;
    req.set_id(id);
    v1::Optimization o;
    auto c = ctx();
    const auto st = stub_->GetOptimization(c.get(), req, &o);
    if (!st.ok()) throw std::runtime_error("GetOptimization: " + st.error_message());
    return o;
  }

  static bool finished(v1::State s) {
    return s == v1::SUCCEEDED || s == v1::FAILED || s == v1::CANCELLED;
  }

  // Polls `get` until what it returns has finished (or the timeout); returns the last answer.
  template <class Get>
  static auto wait_until_finished(Get&& get, double timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::milliseconds(static_cast<long>(timeout_s * 1000));
    for (;;) {
      auto item = get();
      if (finished(item.state()) || std::chrono::steady_clock::now() > deadline) return item;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  // Cancels a job or an optimisation; returns the number of jobs cancelled.
  int cancel(const std::string& id) {
    v1::IdRequest req;
    req.set_id(id);
    v1::CancelResponse resp;
    auto c = ctx();
    const auto st = stub_->Cancel(c.get(), req, &resp);
    if (!st.ok()) throw std::runtime_error("Cancel: " + st.error_message());
    return resp.jobs_cancelled();
  }

  // Polls a job until a worker runs it (at most 5 s); returns its last state.
  v1::State wait_running(const std::string& id) {
    for (int i = 0; i < 500 && job(id).state() != v1::RUNNING; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return job(id).state();
  }
  v1::Job wait_job(const std::string& id, double timeout_s = 120) {
    return wait_until_finished([&] { return job(id); }, timeout_s);
  }
  v1::Optimization wait_optimization(const std::string& id, double timeout_s = 300) {
    return wait_until_finished([&] { return optimization(id); }, timeout_s);
  }

 private:
  TempDir dir_;
  std::filesystem::path socket_, state_;
  std::vector<std::string> extra_;
  std::map<std::string, std::string> env_;
  pid_t pid_ = -1;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Scheduler::Stub> stub_;
};

// A heading-step case; `extra` lines are appended (later keys override nothing: use distinct
// values through the arguments).
inline std::string heading_case(const std::string& name, double duration = 10, double dt = 0.01,
                                double target_deg = 90, const std::string& plant = "derivative") {
  return "name = \"" + name + "\"\nplant = \"" + plant + "\"\n[time]\ndt = " + std::to_string(dt) +
         "\nduration = " + std::to_string(duration) +
         "\n[manoeuvre]\ntype = \"heading-step\"\ntarget_heading = " + std::to_string(target_deg) +
         "\n[controller]\nkp = 1.5\nki = 0.6\nkd = 1.0\n";
}

}  // namespace auvloop::test
