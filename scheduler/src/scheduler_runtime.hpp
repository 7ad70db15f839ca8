// SPDX-License-Identifier: GPL-3.0-or-later
// A running optimisation held in memory by the scheduler (private to scheduler/src).
#pragma once

#include "auvloop/optimizer/optimizer.hpp"
#include "auvloop/scheduler/scheduler.hpp"
#include "auvloop/scheduler/study.hpp"

namespace auvloop::scheduler {

// Throws RequestError (invalid_argument) when a request's files exceed the limits.
void check_source_size(const SourceBundle& s);

struct Scheduler::Runtime {
  Study study;
  optimizer::SurrogateOptimizer optimizer;
  OptimizationRecord record;
};

template <class F>
void Scheduler::atomically(F&& f) {
  StateStore::Transaction t(*store_);
  try {
    f();
    t.commit();
  } catch (...) {
    runtimes_.clear();
    throw;
  }
}

}  // namespace auvloop::scheduler
