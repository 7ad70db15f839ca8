// SPDX-License-Identifier: GPL-3.0-or-later
// The local backend: posix_spawn (safe in a multi-threaded process, unlike fork), one monitor
// thread per child that reads its progress pipe, enforces the timeout and reaps it.
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "auvloop/scheduler/backend.hpp"

extern char** environ;

namespace auvloop::scheduler {

std::string ExitInfo::describe() const {
  if (cancelled) return "cancelled";
  if (timed_out) return "timed out";
  if (signal != 0) {
    const char* name = sigabbrev_np(signal);
    return fmt::format("killed by signal {} (SIG{})", signal, name ? name : "?");
  }
  return fmt::format("exit code {}", exit_code);
}

namespace {
using Clock = std::chrono::steady_clock;

struct Child {
  pid_t pid = -1;
  int progress_fd = -1;
  std::atomic<bool> cancel{false};
};

// A pipe whose ends are above 3 and close-on-exec, so that dup2 onto fd 3 in the child always
// clears the flag and no other child inherits either end.
std::pair<int, int> progress_pipe() {
  int p[2];
  if (pipe2(p, O_CLOEXEC) != 0) throw std::runtime_error(std::strerror(errno));
  int r = fcntl(p[0], F_DUPFD_CLOEXEC, 10), w = fcntl(p[1], F_DUPFD_CLOEXEC, 10);
  close(p[0]);
  close(p[1]);
  return {r, w};
}

class LocalProcessBackend final : public ExecutionBackend {
 public:
  explicit LocalProcessBackend(LocalProcessOptions o) : options_(o) {}
  ~LocalProcessBackend() override { stop_all(); }

  void set_callbacks(Callbacks c) override { callbacks_ = std::move(c); }
  [[nodiscard]] std::string name() const override { return "local"; }

  void start(const LaunchSpec& spec) override {
    const int log = open(spec.log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
    if (log < 0) {
      throw std::runtime_error(
          fmt::format("cannot open the log {}: {}", spec.log_path.string(), std::strerror(errno)));
    }
    auto [r, w] = progress_pipe();
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, log, 1);
    posix_spawn_file_actions_adddup2(&fa, log, 2);
    posix_spawn_file_actions_adddup2(&fa, w, 3);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);  // its own group: kill it whole
    posix_spawnattr_setpgroup(&attr, 0);
    std::vector<char*> argv;
    for (const auto& a : spec.argv) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, argv[0], &fa, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&attr);
    close(log);
    close(w);
    if (rc != 0) {
      close(r);
      throw std::runtime_error(fmt::format("cannot start {}: {}", spec.argv[0], std::strerror(rc)));
    }
    auto child = std::make_shared<Child>();
    child->pid = pid;
    child->progress_fd = r;
    std::lock_guard lock(mutex_);
    children_[spec.job_id] = child;
    ++active_;
    std::thread([this, id = spec.job_id, child, timeout = spec.timeout_s] {
      monitor(id, *child, timeout);
    }).detach();
  }

  void cancel(const std::string& job_id) override {
    std::lock_guard lock(mutex_);
    const auto it = children_.find(job_id);
    if (it != children_.end()) it->second->cancel = true;
  }

  void stop_all() override {
    std::unique_lock lock(mutex_);
    for (auto& [id, c] : children_) c->cancel = true;
    ended_.wait(lock, [this] { return active_ == 0; });
  }

 private:
  void monitor(const std::string& id, Child& c, double timeout_s) {
    const auto start = Clock::now();
    std::string buffer;
    ExitInfo exit;
    std::optional<Clock::time_point> term_sent;
    bool eof = false;
    for (;;) {
      if (!eof) eof = read_progress(id, c.progress_fd, buffer);
      int status = 0;
      if (waitpid(c.pid, &status, WNOHANG) == c.pid) {
        if (!eof) read_progress(id, c.progress_fd, buffer);
        if (WIFEXITED(status)) exit.exit_code = WEXITSTATUS(status);
        if (WIFSIGNALED(status)) exit.signal = WTERMSIG(status);
        break;
      }
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      const bool over = timeout_s > 0 && elapsed > timeout_s;
      if ((c.cancel || over) && !term_sent) {
        exit.cancelled = c.cancel && !over;
        exit.timed_out = over;
        kill(-c.pid, SIGTERM);
        term_sent = Clock::now();
      } else if (term_sent && std::chrono::duration<double>(Clock::now() - *term_sent).count() >
                                  options_.kill_grace_s) {
        kill(-c.pid, SIGKILL);
      }
      if (eof) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(-c.pid, SIGKILL);  // anything the job left behind in its group
    close(c.progress_fd);
    if (term_sent && exit.signal == 0 && exit.exit_code == 0) exit.cancelled |= !exit.timed_out;
    {
      std::lock_guard lock(mutex_);
      children_.erase(id);
    }
    guarded(id, [&] {
      if (callbacks_.finished) callbacks_.finished(id, exit);
    });
    std::lock_guard lock(mutex_);
    --active_;
    ended_.notify_all();
  }

  // A callback that throws must not end the monitor thread (std::terminate) nor leave active_
  // counting it: the error is logged and the monitor goes on.
  template <class F>
  static void guarded(const std::string& id, F&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      spdlog::error("job {}: {}", id, e.what());
    } catch (...) {
      spdlog::error("job {}: unknown error in a callback", id);
    }
  }

  // Reads what is available (waiting up to 50 ms); returns true at end of file.
  bool read_progress(const std::string& id, int fd, std::string& buffer) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) return false;
    char chunk[4096];
    const ssize_t n = read(fd, chunk, sizeof chunk);
    if (n <= 0) return true;
    buffer.append(chunk, static_cast<std::size_t>(n));
    std::size_t eol;
    while ((eol = buffer.find('\n')) != std::string::npos) {
      double t = 0, total = 0;
      if (std::sscanf(buffer.substr(0, eol).c_str(), "progress %lf %lf", &t, &total) == 2 &&
          callbacks_.progress) {
        guarded(id, [&] { callbacks_.progress(id, t, total); });
      }
      buffer.erase(0, eol + 1);
    }
    if (buffer.size() > 65536) buffer.clear();  // a job writing garbage: drop it
    return false;
  }

  LocalProcessOptions options_;
  Callbacks callbacks_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Child>> children_;
  int active_ = 0;  // monitor threads still running (they are detached)
  std::condition_variable ended_;
};
}  // namespace

std::unique_ptr<ExecutionBackend> make_local_process_backend(LocalProcessOptions options) {
  return std::make_unique<LocalProcessBackend>(options);
}

}  // namespace auvloop::scheduler
