// SPDX-License-Identifier: GPL-3.0-or-later
// How jobs, optimisations and their progress look on a terminal.
#pragma once

#include <string>

#include "daemon_connection.hpp"

namespace auvloop::cli {

std::string duration_text(double seconds);  // "42 s", "3 min 05 s", "2 h 10 min"
std::string state_text(v1::State s);        // "queued", "running", ...
bool finished(v1::State s);

void print_job_table_header();
void print_job_row(const v1::Job& j);
void print_job(const v1::Job& j);                    // `auvloop status jN`
void print_optimization(const v1::Optimization& o);  // `auvloop status oN`

// Follows a job or optimisation until it ends, drawing progress bars with an ETA (redrawn in
// place on a terminal, one line per change otherwise). Returns its final state.
v1::State watch(DaemonClient& client, const std::string& id, bool quiet = false);

}  // namespace auvloop::cli
