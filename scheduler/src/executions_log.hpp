// SPDX-License-Identifier: GPL-3.0-or-later
// STATE_DIR/executions.log: one line "KEY NAME WALL_S" per case actually computed (auvloopd
// --help). Internal to the scheduler module.
//
// Invariant: every computed case has exactly one line. A worker appends its line after its
// result is stored; a worker killed between the two (a daemon's SIGKILL takes its workers) leaves
// a stored result without a line, so the daemon, completing a job it queued again at its restart
// from that stored result, records the line on the dead worker's behalf when the key has none
// (only such jobs are checked: the log is read whole).
#pragma once

#include <filesystem>
#include <string>

namespace auvloop::scheduler {

// Appends one line with a single O_APPEND write (lines of concurrent workers never interleave);
// an empty path or a log that cannot be opened is ignored (the log is a record, not a result).
void append_execution(const std::filesystem::path& log, const std::string& key,
                      const std::string& name, double wall_s);

// Whether the log has a line for `key`.
bool execution_logged(const std::filesystem::path& log, const std::string& key);

}  // namespace auvloop::scheduler
