// SPDX-License-Identifier: GPL-3.0-or-later
// Profiling of the solver's phases: adds the wall-clock time of a scope to an accumulator.
#pragma once

#include <chrono>

namespace auvloop::engine::fv {

class ScopedSeconds {
 public:
  explicit ScopedSeconds(double& seconds)
      : seconds_(seconds), t0_(std::chrono::steady_clock::now()) {}
  ~ScopedSeconds() {
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }
  ScopedSeconds(const ScopedSeconds&) = delete;
  ScopedSeconds& operator=(const ScopedSeconds&) = delete;

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace auvloop::engine::fv
