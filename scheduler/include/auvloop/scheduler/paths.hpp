// SPDX-License-Identifier: GPL-3.0-or-later
// Where the daemon keeps its state and listens, shared by auvloopd and the client so that both
// agree without configuration. Flags override environment variables, which override defaults.
#pragma once

#include <filesystem>
#include <string>

namespace auvloop::scheduler {

// $AUVLOOP_STATE_DIR, else $XDG_STATE_HOME/auvloop, else ~/.local/state/auvloop.
std::filesystem::path default_state_dir();
// $AUVLOOP_SOCKET, else $XDG_RUNTIME_DIR/auvloop/auvloopd.sock, else /tmp/auvloop-UID/auvloopd.sock
// (a per-user directory with mode 0700).
std::filesystem::path default_socket();
// Throws std::runtime_error unless the socket's directory is safe to talk through: owned by this
// user (or root) and not writable by others (unless sticky, like /tmp). Someone else's
// /tmp/auvloop-UID could otherwise host a fake daemon that reads every submitted case.
void check_socket_directory(const std::filesystem::path& socket);

// Inside the state directory:
inline constexpr const char* kTokenFile = "token";         // TCP bearer token, mode 0600
inline constexpr const char* kTcpPortFile = "tcp-port";    // the port actually bound
inline constexpr const char* kLockFile = "auvloopd.lock";  // held while a daemon runs
inline constexpr const char* kDaemonLog = "daemon.log";    // when started by `auvloop daemon`

}  // namespace auvloop::scheduler
