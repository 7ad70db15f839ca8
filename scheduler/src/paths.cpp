// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/scheduler/paths.hpp"

#include <unistd.h>

#include <cstdlib>

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

}  // namespace auvloop::scheduler
