// SPDX-License-Identifier: GPL-3.0-or-later
// Shared pieces of the auvloop command-line program.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace auvloop::cli {

// Exit codes, documented in `auvloop --help` and docs/cli.md.
enum ExitCode : int {
  kOk = 0,
  kInternalError = 1,  // a bug: please report it
  kUsage = 2,          // bad command line
  kBadInput = 3,       // an input file is invalid (the message names file:line)
  kFailed = 4,         // the work could not be done (geometry, I/O)
  kUnavailable = 5,    // no daemon answers
};

void register_geometry_commands(CLI::App& app);
// Commands that set a non-zero exit code without throwing write it to exit_code.
void register_run_commands(CLI::App& app, int& exit_code);
void register_optimize_command(CLI::App& app, int& exit_code);
void register_daemon_commands(CLI::App& app, int& exit_code);
void register_job_commands(CLI::App& app, int& exit_code);
void register_results_commands(CLI::App& app, int& exit_code);

struct ConnectOptions;
// `auvloop optimize OPT.toml --daemon`: submits to the daemon (job_commands.cpp).
int optimize_on_daemon(const ConnectOptions& co, const std::string& file, bool wait, bool json);
void register_validate_command(CLI::App& app, int& exit_code);
void register_mesh_command(CLI::App& app, int& exit_code);

}  // namespace auvloop::cli
