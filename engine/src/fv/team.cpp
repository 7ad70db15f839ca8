// SPDX-License-Identifier: GPL-3.0-or-later
// The team's protocol (steps 1-4 of team.hpp).
#include "team.hpp"

#include <tbb/task_group.h>

#include <array>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace auvloop::engine::fv {

namespace {
constexpr std::size_t kLine = 64;  // one claim word per cache line: no false sharing

// Waiting for a phase: spin (a new phase arrives within a microsecond), then yield the core
// (another thread may need it), then sleep. The spin is long enough to cover the serial work
// between the loops of a solve; the sleep, after the yielding stretch, ends the region's cost to
// a machine whose leader is busy elsewhere.
constexpr auto kSpin = std::chrono::microseconds(50);
constexpr auto kYield = std::chrono::microseconds(2000);

inline void pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

thread_local Team* led = nullptr;    // the team this thread leads
thread_local int parts_running = 0;  // > 0: this thread runs a part of a phase
}  // namespace

struct Team::State {
  // Step 1: the phase word, s << 8 | parts, and the work (written before the word).
  alignas(kLine) std::atomic<std::uint64_t> phase{0};
  void (*call)(void*, int) = nullptr;
  void* fn = nullptr;
  alignas(kLine) std::atomic<std::uint64_t> finished{0};  // parts finished, all phases
  alignas(kLine) std::atomic<int> sleepers{0};
  alignas(kLine) std::atomic<bool> stopping{false};
  struct alignas(kLine) Claim {
    std::atomic<std::uint64_t> phase{0};
  };
  std::array<Claim, kMaxParts> claims;
  std::mutex error_mutex;
  std::exception_ptr error;
  std::thread::id leader;
  tbb::task_group helpers;

  // Steps 2-3 for thread t of `size` in phase s of `parts` parts: its own parts forward, then
  // the others' from the end backward, up to the first claimed one (their owner claims forward,
  // so the parts before it are taken); the finished parts are counted once, at the end.
  bool claim(std::uint64_t s, int k) {
    auto& word = claims[static_cast<std::size_t>(k)].phase;
    std::uint64_t seen = word.load(std::memory_order_relaxed);
    return seen < s && word.compare_exchange_strong(seen, s, std::memory_order_acq_rel);
  }
  void run_part(int k) {
    ++parts_running;
    try {
      call(fn, k);
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
    }
    --parts_running;
  }
  void work(std::uint64_t s, int parts, int t, int size) {
    const auto first = [&](int owner) { return owner * parts / size; };
    int done = 0;
    for (int k = first(t); k < first(t + 1); ++k)
      if (claim(s, k)) {
        run_part(k);
        ++done;
      }
    for (int i = 1; i < size; ++i) {
      const int owner = (t + i) % size;
      for (int k = first(owner + 1); k-- > first(owner) && claim(s, k);) {
        run_part(k);
        ++done;
      }
    }
    if (done > 0) finished.fetch_add(static_cast<std::uint64_t>(done), std::memory_order_release);
  }

  // Step 4, a helper's loop.
  void help(int t, int size) {
    if (std::this_thread::get_id() == leader) return;  // TBB ran the task on the leader
    std::uint64_t seen = phase.load(std::memory_order_acquire);
    using clock = std::chrono::steady_clock;
    for (;;) {
      const auto since = clock::now();
      std::uint64_t now = phase.load(std::memory_order_acquire);
      for (int spins = 0; now == seen && !stopping.load(std::memory_order_acquire); ++spins) {
        const auto waited = (spins & 255) == 255 ? clock::now() - since : clock::duration{};
        if (waited > kYield) {
          sleepers.fetch_add(1, std::memory_order_seq_cst);
          if (phase.load(std::memory_order_seq_cst) == seen &&
              !stopping.load(std::memory_order_seq_cst))
            phase.wait(seen, std::memory_order_seq_cst);
          sleepers.fetch_sub(1, std::memory_order_seq_cst);
        } else if (waited > kSpin) {
          std::this_thread::yield();
        } else {
          pause();
        }
        now = phase.load(std::memory_order_acquire);
      }
      if (stopping.load(std::memory_order_acquire)) return;
      seen = now;
      work(now >> 8, static_cast<int>(now & 255), t, size);
    }
  }
};

Team::Team(int size) : size_(size), state_(std::make_unique<State>()) {}
Team::~Team() = default;

void Team::start() {
  State& st = *state_;
  st.leader = std::this_thread::get_id();
  for (int t = 1; t < size_; ++t) st.helpers.run([&st, t, n = size_] { st.help(t, n); });
}

void Team::stop() {
  State& st = *state_;
  st.stopping.store(true, std::memory_order_seq_cst);
  st.phase.fetch_add(std::uint64_t{1} << 8, std::memory_order_seq_cst);  // wakes every wait
  st.phase.notify_all();
  st.helpers.wait();
}

void Team::run_erased(int parts, void (*call)(void*, int), void* fn) {
  if (parts < 1 || parts > kMaxParts) throw std::logic_error("Team::run: parts out of range");
  State& st = *state_;
  st.call = call;
  st.fn = fn;
  const std::uint64_t target =
      st.finished.load(std::memory_order_relaxed) + static_cast<std::uint64_t>(parts);
  const std::uint64_t s = (st.phase.load(std::memory_order_relaxed) >> 8) + 1;
  // A release store, not a fence: the leader does not stall while the word travels. A helper
  // that goes to sleep just as the word changes may miss this wake-up; it then sleeps through
  // phases that the others run, until the next phase's (or stop's) notification.
  st.phase.store(s << 8 | static_cast<std::uint64_t>(parts), std::memory_order_release);
  if (st.sleepers.load(std::memory_order_relaxed) > 0) st.phase.notify_all();
  st.work(s, parts, 0, size_);
  for (int spins = 0; st.finished.load(std::memory_order_acquire) < target; ++spins) {
    if (spins < 4096) {
      pause();
    } else {
      std::this_thread::yield();  // a helper that claimed a part was descheduled
    }
  }
  if (st.error) {
    std::exception_ptr e;
    std::swap(e, st.error);
    std::rethrow_exception(e);
  }
}

Team* Team::current() {
  return parts_running > 0 ? nullptr : led;
}

bool Team::in_part() {
  return parts_running > 0;
}

Team::Region::Region(int size) {
  if (size < 2 || led != nullptr || parts_running > 0) return;
  team_ = std::make_unique<Team>(size);
  team_->start();
  led = team_.get();
}

Team::Region::~Region() {
  if (!team_) return;
  led = nullptr;
  team_->stop();
}

}  // namespace auvloop::engine::fv
