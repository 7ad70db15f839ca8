// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant's closed-loop trials (results/trials.hpp), as `auvloop validate` runs them: the
// CI-sized version (coarse, the first second, against the derivative plant: about a minute
// each), or the full one when built with AUVLOOP_FULL_VALIDATION (label slow: coarse and medium
// against the sea trials).
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "auvloop/results/trials.hpp"

namespace {
#ifdef AUVLOOP_FULL_VALIDATION
constexpr bool kQuick = false;
#define TRIAL_SUITE TrialsFull
#else
constexpr bool kQuick = true;
#define TRIAL_SUITE Trials
#endif

void run(const std::string& name) {
  for (const auto& c : auvloop::results::trial_cases()) {
    if (c.name != name) continue;
    const auto result = c.run(kQuick);
    for (const auto& n : result.notes) std::printf("  %s\n", n.c_str());
    ASSERT_FALSE(result.rows.empty());
    for (const auto& r : result.rows) {
      std::printf("  %-44s %10.5g  reference %8.4g  error %8.4g  tolerance %6.3g\n",
                  r.quantity.c_str(), r.value, r.reference, r.error, r.tolerance);
      EXPECT_TRUE(r.pass) << r.quantity;
    }
    return;
  }
  FAIL() << "no trial " << name;
}
}  // namespace

TEST(TRIAL_SUITE, YawTrial) {
  run("remus-yaw-trial");
}
TEST(TRIAL_SUITE, PitchTrial) {
  run("remus-pitch-trial");
}
TEST(TRIAL_SUITE, TurningCircle) {
  run("remus-turning-circle");
}
// The paper's heading step (quick: its first second against the derivative plant; full: the
// grid and time-step study, coarse and medium at 10 ms, coarse at 5 and 20 ms: about 4 h).
TEST(TRIAL_SUITE, HeadingStep) {
  run("remus-heading-step");
}
