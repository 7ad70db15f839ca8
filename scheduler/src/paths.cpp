// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/scheduler/paths.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

#include <fmt/format.h>

namespace auvloop::scheduler {
namespace fs = std::filesystem;

namespace {
const char* env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? v : nullptr;
}
}  // namespace

fs::path default_state_dir() {
  if (const char* v = env("AUVLOOP_STATE_DIR")) return v;
  if (const char* v = env("XDG_STATE_HOME")) return fs::path(v) / "auvloop";
  if (const char* v = env("HOME")) return fs::path(v) / ".local" / "state" / "auvloop";
  return fs::path("/tmp") / ("auvloop-state-" + std::to_string(getuid()));
}

fs::path default_socket() {
  if (const char* v = env("AUVLOOP_SOCKET")) return v;
  if (const char* v = env("XDG_RUNTIME_DIR")) return fs::path(v) / "auvloop" / "auvloopd.sock";
  return fs::path("/tmp") / ("auvloop-" + std::to_string(getuid())) / "auvloopd.sock";
}

void check_socket_directory(const fs::path& socket) {
  const fs::path dir = socket.has_parent_path() ? socket.parent_path() : fs::path(".");
  struct stat st {};
  if (lstat(dir.c_str(), &st) != 0) return;  // not there yet: whoever creates it owns it
  const auto refuse = [&](const std::string& why) {
    throw std::runtime_error(fmt::format(
        "the socket directory {} {}: it is not safe to talk to a daemon through it (remove it, "
        "or choose another with --socket or AUVLOOP_SOCKET)",
        dir.string(), why));
  };
  if (S_ISLNK(st.st_mode)) refuse("is a symbolic link");
  if (!S_ISDIR(st.st_mode)) refuse("is not a directory");
  if (st.st_uid != geteuid() && st.st_uid != 0) refuse(fmt::format("belongs to uid {}", st.st_uid));
  if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0 && (st.st_mode & S_ISVTX) == 0) {
    refuse("is writable by other users");
  }
}

}  // namespace auvloop::scheduler
