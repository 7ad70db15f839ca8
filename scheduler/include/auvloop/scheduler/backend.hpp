// SPDX-License-Identifier: GPL-3.0-or-later
// Where cases run. The scheduler hands a backend a command line per job and hears back progress
// and the way the job ended; the first backend runs each job as a local child process (so a
// crash, hang or divergence never takes the daemon down). A cluster backend (Slurm) would
// implement the same interface with sbatch / squeue / scancel.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace auvloop::scheduler {

struct LaunchSpec {
  std::string job_id;
  std::vector<std::string> argv;   // argv[0]: the executable's path
  std::filesystem::path log_path;  // stdout and stderr, appended
  double timeout_s = 0;            // wall time; 0: none
};

struct ExitInfo {
  int exit_code = 0;  // when exited normally
  int signal = 0;     // when killed by a signal
  bool timed_out = false;
  bool cancelled = false;
  [[nodiscard]] bool ok() const {
    return signal == 0 && exit_code == 0 && !timed_out && !cancelled;
  }
  [[nodiscard]] std::string describe() const;  // "exit code 3", "killed by signal 6 (SIGABRT)", ...
};

class ExecutionBackend {
 public:
  struct Callbacks {
    // Progress lines "progress T TOTAL" that the job writes to its progress channel.
    std::function<void(const std::string& job_id, double t, double total)> progress;
    // Called once per started job, from a backend thread, after the job has ended.
    std::function<void(const std::string& job_id, const ExitInfo& exit)> finished;
  };
  virtual ~ExecutionBackend() = default;
  virtual void set_callbacks(Callbacks callbacks) = 0;
  // Throws std::runtime_error when the job cannot be started.
  virtual void start(const LaunchSpec& spec) = 0;
  // Terminates a job (SIGTERM, then SIGKILL after a grace period); `finished` follows.
  virtual void cancel(const std::string& job_id) = 0;
  // Kills every job and waits for their `finished` callbacks.
  virtual void stop_all() = 0;
  [[nodiscard]] virtual std::string name() const = 0;
};

struct LocalProcessOptions {
  double kill_grace_s = 2.0;  // between SIGTERM and SIGKILL
};
// Jobs as child processes in their own process group; the progress channel is file descriptor 3.
std::unique_ptr<ExecutionBackend> make_local_process_backend(LocalProcessOptions options = {});

}  // namespace auvloop::scheduler
