// SPDX-License-Identifier: GPL-3.0-or-later
// A team of the engine's threads kept awake for a stretch of work (a time step, a linear solve),
// private to engine/src. A pressure solve on a small grid runs about 40 parallel loops per
// iteration of about a millisecond; a TBB fork-join costs 1-5 us each (34 us once the idle
// worker has gone to sleep: bench_kernels), which held the coarse hull grid's two-thread speed-up
// to 1.45. Within a team the loops cost a store and a spin on a counter instead.
//
// The protocol (one leader, the thread that opened the region, and size - 1 helpers, TBB tasks):
//   1. the leader publishes a phase: the work function, then one atomic word holding the phase's
//      sequence number s and its number of parts;
//   2. every thread claims parts by a compare-and-swap of the part's claim word from a value
//      below s to s, its own parts first (thread t owns parts t * P / size ..), then the others';
//      a thread that sees an older phase finds every part of it claimed, so it never runs a part
//      it did not see published;
//   3. a thread runs each part it claimed and counts it finished; the leader returns when all
//      parts are finished (and rethrows the first exception a part threw);
//   4. between phases helpers spin, then yield, then sleep on the phase word (atomic wait); the
//      leader wakes sleepers only when some sleep, and without a fence (a helper that falls
//      asleep as a phase starts may miss that phase; the others run its parts).
// Nothing waits for a thread to arrive: a helper that is late (or never scheduled) leaves its
// parts to the others, so a region can never deadlock, and the results do not depend on which
// thread ran a part (parallel.hpp's rules make every loop's result independent of its
// partition). Inside a part, parallel loops run on the calling thread.
#pragma once

#include <cstdint>
#include <memory>

namespace auvloop::engine::fv {

class Team {
 public:
  // The most parts a phase may have.
  static constexpr int kMaxParts = 64;

  // Opens a team of `size` threads on the calling thread, closed on destruction; does nothing
  // when size < 2 or when the calling thread is already in a team.
  class Region {
   public:
    explicit Region(int size);
    ~Region();
    Region(const Region&) = delete;
    Region& operator=(const Region&) = delete;

   private:
    std::unique_ptr<Team> team_;
  };

  // The team the calling thread leads, outside any part; nullptr otherwise.
  static Team* current();
  // The calling thread runs a part of some team's phase (parallel loops there run serially).
  static bool in_part();

  [[nodiscard]] int size() const { return size_; }

  // fn(part) for every part in [0, parts), parts in [1, kMaxParts], spread over the team; the
  // leader's call returns when all have run.
  template <class F>
  void run(int parts, F&& fn) {
    using Fn = std::remove_reference_t<F>;
    run_erased(
        parts, [](void* f, int part) { (*static_cast<Fn*>(f))(part); }, static_cast<void*>(&fn));
  }

  explicit Team(int size);
  ~Team();
  Team(const Team&) = delete;
  Team& operator=(const Team&) = delete;

 private:
  struct State;
  void run_erased(int parts, void (*call)(void*, int), void* fn);
  void start();
  void stop();
  int size_;
  std::unique_ptr<State> state_;
};

}  // namespace auvloop::engine::fv
