// SPDX-License-Identifier: GPL-3.0-or-later
// Shared pieces of the auvloop command-line program.
#pragma once

#include <CLI/CLI.hpp>

namespace auvloop::cli {

// Exit codes, documented in `auvloop --help` and docs/cli.md.
enum ExitCode : int {
  kOk = 0,
  kInternalError = 1,  // a bug: please report it
  kUsage = 2,          // bad command line
  kBadInput = 3,       // an input file is invalid (the message names file:line)
  kFailed = 4,         // the work could not be done (geometry, I/O)
};

void register_geometry_commands(CLI::App& app);
// Commands that set a non-zero exit code without throwing write it to exit_code.
void register_run_commands(CLI::App& app, int& exit_code);
void register_optimize_command(CLI::App& app, int& exit_code);
void register_mesh_command(CLI::App& app, int& exit_code);

}  // namespace auvloop::cli
