// SPDX-License-Identifier: GPL-3.0-or-later
// How the client reaches auvloopd: the Unix socket (default) or loopback TCP with the token, the
// same flags and environment variables as the daemon's, and errors that say what to do.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <grpcpp/grpcpp.h>
#include <CLI/CLI.hpp>

#include "auvloop/v1/scheduler.grpc.pb.h"

namespace auvloop::cli {

struct ConnectOptions {
  std::string socket;     // empty: scheduler::default_socket()
  std::string state_dir;  // empty: scheduler::default_state_dir()
  std::string tcp;        // "PORT" or "127.0.0.1:PORT": use TCP with STATE_DIR/token
  bool start = false;     // start a daemon when none answers
  double timeout_s = 10;  // per call (not for watch)
};

// Adds --socket, --state-dir, --tcp (and --start when `with_start`) to a command.
void add_connect_options(CLI::App* cmd, ConnectOptions& o, bool with_start = false);

// Thrown when no daemon answers; main() turns it into exit code 5.
class DaemonUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// An RPC that the daemon refused: main() turns INVALID_ARGUMENT into exit code 3, NOT_FOUND and
// FAILED_PRECONDITION into 4.
class RpcError : public std::runtime_error {
 public:
  RpcError(grpc::StatusCode c, const std::string& message) : std::runtime_error(message), code(c) {}
  grpc::StatusCode code;
};

class DaemonClient {
 public:
  explicit DaemonClient(const ConnectOptions& o);
  v1::Scheduler::Stub& stub() { return *stub_; }
  // A context with the token (TCP) and a deadline (none when `streaming`).
  std::unique_ptr<grpc::ClientContext> context(bool streaming = false) const;
  // Throws DaemonUnavailable / RpcError for a failed status.
  void check(const grpc::Status& s) const;
  // One unary call, checked: c.call(&v1::Scheduler::Stub::GetJob, request). `long_call`: no
  // deadline (the daemon may take long, e.g. proposing a batch).
  template <class Response, class Request>
  Response call(grpc::Status (v1::Scheduler::Stub::*method)(grpc::ClientContext*, const Request&,
                                                            Response*),
                const Request& request, bool long_call = false) {
    Response response;
    auto ctx = context(long_call);
    check(((*stub_).*method)(ctx.get(), request, &response));
    return response;
  }
  [[nodiscard]] const std::string& target() const { return target_; }

 private:
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Scheduler::Stub> stub_;
  std::string target_, token_;
  double timeout_s_;
};

std::filesystem::path resolved_socket(const ConnectOptions& o);
std::filesystem::path resolved_state_dir(const ConnectOptions& o);

// Starts auvloopd in the background (its log in STATE_DIR/daemon.log) and waits until it answers.
void start_daemon(const ConnectOptions& o, const std::vector<std::string>& extra_args);
// Connects, starting a daemon first when o.start and none answers.
DaemonClient connect(const ConnectOptions& o);

// Proto message as indented JSON (for --json).
std::string to_json_text(const google::protobuf::Message& m);
v1::IdRequest id_request(const std::string& id);
// Prints `m` as JSON when `json`, else as `human` prints it.
template <class Message, class Human>
void print_json_or(const Message& m, bool json, Human&& human) {
  if (json) {
    std::printf("%s\n", to_json_text(m).c_str());
  } else {
    human(m);
  }
}

}  // namespace auvloop::cli
