// SPDX-License-Identifier: GPL-3.0-or-later
#include "daemon_connection.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <climits>
#include <cstring>
#include <fstream>
#include <thread>

#include <fmt/format.h>
#include <google/protobuf/util/json_util.h>

#include "auvloop/scheduler/paths.hpp"

extern char** environ;

namespace auvloop::cli {
namespace fs = std::filesystem;

fs::path resolved_socket(const ConnectOptions& o) {
  return o.socket.empty() ? scheduler::default_socket() : fs::path(o.socket);
}
fs::path resolved_state_dir(const ConnectOptions& o) {
  return o.state_dir.empty() ? scheduler::default_state_dir() : fs::path(o.state_dir);
}

void add_connect_options(CLI::App* cmd, ConnectOptions& o, bool with_start) {
  cmd->add_option("--socket", o.socket, "Daemon socket (env AUVLOOP_SOCKET; default per user)")
      ->group("Daemon connection");
  cmd->add_option("--state-dir", o.state_dir,
                  "Daemon state directory, for the TCP token (env AUVLOOP_STATE_DIR)")
      ->group("Daemon connection");
  cmd->add_option("--tcp", o.tcp, "Connect over loopback TCP: PORT or 127.0.0.1:PORT")
      ->group("Daemon connection");
  if (with_start) {
    cmd->add_flag("--start", o.start, "Start a daemon (default settings) if none is running")
        ->group("Daemon connection");
  }
}

DaemonClient::DaemonClient(const ConnectOptions& o) : timeout_s_(o.timeout_s) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  args.SetMaxSendMessageSize(64 << 20);
  if (!o.tcp.empty()) {
    target_ = o.tcp.find(':') == std::string::npos ? "127.0.0.1:" + o.tcp : o.tcp;
    const fs::path token_file = resolved_state_dir(o) / scheduler::kTokenFile;
    std::ifstream in(token_file);
    if (!(in >> token_)) {
      throw DaemonUnavailable(
          fmt::format("cannot read the daemon's token from {} (pass --state-dir of the daemon)",
                      token_file.string()));
    }
  } else {
    const fs::path socket = resolved_socket(o);
    scheduler::check_socket_directory(socket);
    target_ = "unix:" + socket.string();
  }
  channel_ = grpc::CreateCustomChannel(target_, grpc::InsecureChannelCredentials(), args);
  stub_ = v1::Scheduler::NewStub(channel_);
}

std::unique_ptr<grpc::ClientContext> DaemonClient::context(bool streaming) const {
  auto ctx = std::make_unique<grpc::ClientContext>();
  if (!token_.empty()) ctx->AddMetadata("authorization", "Bearer " + token_);
  if (!streaming) {
    ctx->set_deadline(std::chrono::system_clock::now() +
                      std::chrono::milliseconds(static_cast<long>(timeout_s_ * 1000)));
  }
  return ctx;
}

void DaemonClient::check(const grpc::Status& s) const {
  if (s.ok()) return;
  if (s.error_code() == grpc::StatusCode::UNAVAILABLE) {
    throw DaemonUnavailable(fmt::format(
        "no auvloop daemon answers on {}.\n  Start one with:  auvloop daemon start\n  (or add "
        "--start to this command; --socket / AUVLOOP_SOCKET choose another daemon)",
        target_));
  }
  throw RpcError(s.error_code(), s.error_message());
}

namespace {
fs::path daemon_executable() {
  if (const char* v = std::getenv("AUVLOOP_DAEMON"); v && *v) return v;
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n > 0) {
    const fs::path self(std::string(buf, static_cast<std::size_t>(n)));
    // Installed side by side, or in the build tree (client/ beside scheduler/).
    for (const auto& p : {self.parent_path() / "auvloopd",
                          self.parent_path().parent_path() / "scheduler" / "auvloopd"}) {
      if (fs::exists(p)) return p;
    }
  }
  return "auvloopd";  // from PATH
}

bool answers(const ConnectOptions& o) {
  try {
    DaemonClient c(o);
    auto ctx = c.context();
    v1::DaemonStatus s;
    return c.stub().Status(ctx.get(), v1::StatusRequest(), &s).ok();
  } catch (const DaemonUnavailable&) {
    return false;
  }
}
}  // namespace

void start_daemon(const ConnectOptions& o, const std::vector<std::string>& extra_args) {
  const fs::path state = resolved_state_dir(o);
  fs::create_directories(state);
  const fs::path log = state / scheduler::kDaemonLog;
  std::vector<std::string> args{daemon_executable().string(), "--state-dir", state.string(),
                                "--socket", resolved_socket(o).string()};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0600);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSID);  // outlives this terminal session
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, argv[0], &fa, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    throw DaemonUnavailable(fmt::format("cannot start {}: {}", args[0], std::strerror(rc)));
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  ConnectOptions probe = o;
  probe.timeout_s = 1;
  while (std::chrono::steady_clock::now() < deadline) {
    if (answers(probe)) return;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {  // it gave up: say why
      std::ifstream in(log);
      std::string line, last;
      while (std::getline(in, line)) last = line;
      throw DaemonUnavailable(fmt::format("the daemon did not start: {}", last));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  throw DaemonUnavailable(
      fmt::format("the daemon did not answer within 20 s; see {}", log.string()));
}

DaemonClient connect(const ConnectOptions& o) {
  if (o.start && o.tcp.empty() && !answers(o)) {
    fmt::print(stderr, "starting auvloopd (state in {})\n", resolved_state_dir(o).string());
    start_daemon(o, {});
  }
  return DaemonClient(o);
}

v1::IdRequest id_request(const std::string& id) {
  v1::IdRequest r;
  r.set_id(id);
  return r;
}

std::string to_json_text(const google::protobuf::Message& m) {
  std::string out;
  google::protobuf::util::JsonPrintOptions p;
  p.add_whitespace = true;
  p.preserve_proto_field_names = true;
  p.always_print_primitive_fields = true;
  (void)google::protobuf::util::MessageToJsonString(m, &out, p);
  return out;
}

}  // namespace auvloop::cli
