// SPDX-License-Identifier: GPL-3.0-or-later
// The worker: the child process that runs one case for the daemon (`auvloopd worker ...`).
// It rebuilds the case from the job's source bundle (plus the gains of an optimisation's
// evaluation), checks that its content key is the one the daemon computed, runs it, reporting
// "progress T TOTAL" lines on its progress channel, and stores the run in the result cache.
// A diverged run is stored too (its manifest says why): divergence is a result, not a crash.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "auvloop/engine/case.hpp"

namespace auvloop::scheduler {

struct WorkerArgs {
  std::filesystem::path job_file;        // job.json: {"key", "payload"}
  std::filesystem::path cache_root;      // results::ResultCache root
  std::filesystem::path executions_log;  // one line appended per finished run (accounting)
  int progress_fd = -1;
  long parent_pid = 0;  // exit at once if the daemon that started us is gone
  bool plots = true;    // false: deferred (results::WriteOptions)
};

// The case a job payload describes: {"bundle": SourceBundle, "case": name in the bundle (an
// optimisation's evaluation), "gains": {"kp": .., ...}}.
engine::CaseSpec case_from_payload(const nlohmann::json& payload);

// Returns the process exit code: 0 stored, 3 bad job, 4 could not store.
int run_worker(const WorkerArgs& args);

}  // namespace auvloop::scheduler
