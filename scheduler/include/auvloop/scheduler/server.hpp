// SPDX-License-Identifier: GPL-3.0-or-later
// auvloopd: the scheduler served over gRPC (proto/auvloop/v1/scheduler.proto) on a Unix domain
// socket with owner-only permissions, and on loopback TCP with a bearer token when asked.
#pragma once

#include <filesystem>
#include <string>

namespace auvloop::scheduler {

struct DaemonOptions {
  std::filesystem::path state_dir;
  std::filesystem::path socket;
  int tcp_port = -1;  // -1: no TCP; 0: any free port (written to STATE_DIR/tcp-port)
  int slots = 0;      // 0: one per core
  double timeout_s = 24 * 3600;
  bool plots = true;
  std::filesystem::path worker_executable;
};

// Runs until SIGTERM / SIGINT or a Shutdown request; returns the process exit code. Refuses to
// start (exit code 4, with a message) when another daemon holds the state directory or listens
// on the socket.
int run_daemon(const DaemonOptions& options);

}  // namespace auvloop::scheduler
