// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/scheduler/server.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <fstream>
#include <thread>

#include <fmt/format.h>
#include <grpcpp/grpcpp.h>
#include <spdlog/spdlog.h>

#include "auvloop/geometry/file_io.hpp"
#include "auvloop/scheduler/paths.hpp"
#include "auvloop/scheduler/scheduler.hpp"
#include "service.hpp"

namespace auvloop::scheduler {
namespace fs = std::filesystem;

namespace {
class DaemonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Holds an exclusive lock on STATE_DIR/auvloopd.lock for the daemon's lifetime.
int lock_state_dir(const fs::path& dir) {
  const fs::path path = dir / kLockFile;
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0)
    throw DaemonError(fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    std::ifstream in(path);
    std::string pid;
    std::getline(in, pid);
    close(fd);
    throw DaemonError(
        fmt::format("another auvloopd (pid {}) uses the state directory {}", pid, dir.string()));
  }
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd, 0) != 0 || write(fd, pid.data(), pid.size()) < 0) {
    spdlog::warn("cannot record the pid in {}", path.string());
  }
  return fd;
}

bool someone_listens(const fs::path& socket) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, socket.c_str(), sizeof addr.sun_path - 1);
  const bool ok = connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  close(fd);
  return ok;
}

void prepare_socket(const fs::path& socket) {
  if (socket.string().size() >= sizeof(sockaddr_un::sun_path)) {
    throw DaemonError(
        fmt::format("the socket path {} is too long for a Unix socket (at most {} "
                    "bytes); choose a shorter --socket",
                    socket.string(), sizeof(sockaddr_un::sun_path) - 1));
  }
  fs::create_directories(socket.parent_path());
  check_socket_directory(socket);
  if (fs::exists(fs::symlink_status(socket))) {
    if (someone_listens(socket)) {
      throw DaemonError(fmt::format("another daemon listens on {}", socket.string()));
    }
    fs::remove(socket);  // left by a daemon that was killed
  }
}

std::string new_token() {
  std::ifstream in("/dev/urandom", std::ios::binary);
  unsigned char bytes[32];
  in.read(reinterpret_cast<char*>(bytes), sizeof bytes);
  if (in.gcount() != sizeof bytes) throw DaemonError("cannot read /dev/urandom for the token");
  std::string hex;
  for (unsigned char b : bytes) hex += fmt::format("{:02x}", b);
  return hex;
}

// SIGTERM and SIGINT are taken by a thread that asks for a clean shutdown.
sigset_t termination_signals() {
  sigset_t s;
  sigemptyset(&s);
  sigaddset(&s, SIGTERM);
  sigaddset(&s, SIGINT);
  return s;
}

int default_slots() {
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}
}  // namespace

int run_daemon(const DaemonOptions& o) {
  umask(077);  // everything the daemon creates, the socket included, is the owner's alone
  sigset_t signals = termination_signals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before any thread starts
  std::signal(SIGPIPE, SIG_IGN);
  int lock_fd = -1;
  try {
    fs::create_directories(o.state_dir);
    fs::permissions(o.state_dir, fs::perms::owner_all, fs::perm_options::replace);
    lock_fd = lock_state_dir(o.state_dir);
    prepare_socket(o.socket);
  } catch (const std::exception& e) {
    fmt::print(stderr, "auvloopd: {}\n", e.what());
    return 4;
  }
  SchedulerConfig config;
  config.state_dir = o.state_dir;
  config.slots = o.slots > 0 ? o.slots : default_slots();
  config.default_timeout_s = o.timeout_s;
  config.worker_executable = o.worker_executable;
  config.plots = o.plots;
  config.socket = o.socket.string();
  std::string token;
  if (o.tcp_port >= 0) {
    token = new_token();
    write_file_atomically(o.state_dir / kTokenFile, token + "\n");
  }
  Scheduler scheduler(config, make_local_process_backend());
  std::mutex m;
  std::condition_variable cv;
  bool stop = false, drain = false;
  auto request_stop = [&](bool d) {
    std::lock_guard lock(m);
    stop = true;
    drain = d;
    cv.notify_all();
  };
  SchedulerService service(scheduler, token, request_stop);
  grpc::ServerBuilder builder;
  builder.AddListeningPort("unix:" + o.socket.string(), grpc::InsecureServerCredentials());
  int tcp_port = 0;
  if (o.tcp_port >= 0) {
    builder.AddListeningPort(fmt::format("127.0.0.1:{}", o.tcp_port),
                             grpc::InsecureServerCredentials(), &tcp_port);
  }
  builder.SetMaxReceiveMessageSize(static_cast<int>(kMaxSourceFiles + 2) *
                                   static_cast<int>(kMaxSourceBytes));
  builder.RegisterService(&service);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || (o.tcp_port >= 0 && tcp_port == 0)) {
    fmt::print(stderr, "auvloopd: cannot listen on {}{}\n", o.socket.string(),
               o.tcp_port >= 0 ? fmt::format(" and 127.0.0.1:{}", o.tcp_port) : "");
    return 4;
  }
  if (o.tcp_port >= 0)
    write_file_atomically(o.state_dir / kTcpPortFile, fmt::format("{}\n", tcp_port));
  scheduler.start();
  spdlog::info("auvloopd {} listening on {}{}; state in {}; {} slot(s)", getpid(),
               o.socket.string(), tcp_port ? fmt::format(" and 127.0.0.1:{}", tcp_port) : "",
               o.state_dir.string(), config.slots);
  std::thread signal_thread([&] {
    int sig = 0;
    sigwait(&signals, &sig);
    if (sig != 0) request_stop(false);
  });
  {
    std::unique_lock lock(m);
    cv.wait(lock, [&] { return stop; });
  }
  spdlog::info("shutting down{}", drain ? " after the running jobs" : "");
  // Let the reply to a Shutdown request leave before the server stops serving.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  scheduler.stop(drain);
  server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  fs::remove(o.socket);
  if (o.tcp_port >= 0) fs::remove(o.state_dir / kTcpPortFile);
  // Wake the signal thread if it still waits.
  pthread_kill(signal_thread.native_handle(), SIGTERM);
  signal_thread.join();
  close(lock_fd);
  spdlog::info("stopped");
  return 0;
}

}  // namespace auvloop::scheduler
