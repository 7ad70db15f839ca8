// SPDX-License-Identifier: GPL-3.0-or-later
// The engine's thread team (engine/src/fv/team.hpp, white box): every part of every phase runs
// exactly once whichever thread takes it, an exception in a part reaches the leader, loops
// inside a part run serially, and a region never waits for a helper that cannot run.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "fv/parallel.hpp"
#include "fv/team.hpp"

namespace fv = auvloop::engine::fv;

namespace {
// Runs `phases` phases of 1 to kMaxParts parts on a team of `size` and checks that each part of
// each ran once.
void every_part_once(int size, int phases) {
  const fv::Team::Region region(size);
  fv::Team* team = fv::Team::current();
  ASSERT_NE(team, nullptr);
  EXPECT_EQ(team->size(), size);
  std::vector<std::atomic<int>> runs(fv::Team::kMaxParts);
  for (int phase = 0; phase < phases; ++phase) {
    const int parts = 1 + phase % fv::Team::kMaxParts;
    for (auto& r : runs) r.store(0);
    team->run(parts, [&](int k) { runs[static_cast<std::size_t>(k)].fetch_add(1); });
    for (int k = 0; k < fv::Team::kMaxParts; ++k)
      ASSERT_EQ(runs[static_cast<std::size_t>(k)].load(), k < parts ? 1 : 0)
          << "phase " << phase << ", part " << k << " of " << parts;
  }
}
}  // namespace

TEST(Team, EveryPartOfEveryPhaseRunsOnce) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 3);
  every_part_once(2, 20000);
  every_part_once(3, 5000);
}

TEST(Team, ARegionNeverWaitsForAHelperThatCannotRun) {
  // One thread allowed: TBB has no worker for the helper, so the leader runs every part.
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  every_part_once(2, 1000);
}

TEST(Team, HelpersThatFellAsleepWakeForTheNextPhase) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const fv::Team::Region region(2);
  fv::Team* team = fv::Team::current();
  std::atomic<int> sum{0};
  for (int gap_ms : {0, 5, 20}) {
    std::this_thread::sleep_for(std::chrono::milliseconds(gap_ms));  // past the yield stretch
    team->run(8, [&](int k) { sum.fetch_add(k); });
  }
  EXPECT_EQ(sum.load(), 3 * 28);
}

TEST(Team, AnExceptionInAPartReachesTheLeaderAndTheTeamGoesOn) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const fv::Team::Region region(2);
  fv::Team* team = fv::Team::current();
  std::atomic<int> ran{0};
  EXPECT_THROW(team->run(8,
                         [&](int k) {
                           ran.fetch_add(1);
                           if (k == 5) throw std::runtime_error("part 5");
                         }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 8);  // the other parts still ran
  std::atomic<int> after{0};
  team->run(4, [&](int) { after.fetch_add(1); });
  EXPECT_EQ(after.load(), 4);
}

TEST(Team, LoopsInsideAPartRunSeriallyAndRegionsDoNotNest) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const fv::Team::Region region(2);
  fv::Team* team = fv::Team::current();
  EXPECT_FALSE(fv::Team::in_part());
  {
    const fv::Team::Region inner(2);  // already in a team: nothing opens
    EXPECT_EQ(fv::Team::current(), team);
  }
  EXPECT_EQ(fv::Team::current(), team);
  std::vector<int> out(4 * 100000, 0);
  team->run(4, [&](int k) {
    EXPECT_TRUE(fv::Team::in_part());
    EXPECT_EQ(fv::Team::current(), nullptr);
    const auto caller = std::this_thread::get_id();
    fv::parallel_ranges(100000, [&](int b, int e) {
      EXPECT_EQ(std::this_thread::get_id(), caller);  // on the part's thread
      for (int i = b; i < e; ++i) out[static_cast<std::size_t>(k * 100000 + i)] = 1;
    });
  });
  for (int v : out) ASSERT_EQ(v, 1);
}

TEST(Team, ParallelLoopsOnATeamGiveTheSerialSums) {
  // A reduction's result does not depend on which thread ran which block (parallel.hpp, rule 3).
  std::vector<double> x(100003);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 1.0 / static_cast<double>(i + 1);
  const auto sum = [&] {
    return fv::parallel_sum<1>(static_cast<int>(x.size()), [&](int b, int e, auto& s) {
      for (int i = b; i < e; ++i) s[0] += x[static_cast<std::size_t>(i)];
    })[0];
  };
  double serial = 0;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    serial = sum();
  }
  for (int threads : {2, 3}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
    const fv::Team::Region region(threads);
    for (int k = 0; k < 200; ++k) ASSERT_EQ(sum(), serial) << threads << " threads";
  }
}
