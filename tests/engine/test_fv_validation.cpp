// SPDX-License-Identifier: GPL-3.0-or-later
// Runs every validation case of the engine (the same definitions `auvloop validate` runs): the
// CI-sized version, or the full one when built with AUVLOOP_FULL_VALIDATION (label slow). Each
// row carries its own tolerance and where it comes from (engine/src/validation/cases.cpp).
#include <gtest/gtest.h>

#include "auvloop/engine/validation.hpp"

using namespace auvloop::engine;

namespace {
#ifdef AUVLOOP_FULL_VALIDATION
constexpr bool kQuick = false;
#else
constexpr bool kQuick = true;
#endif

void run(const std::string& name) {
  for (const auto& c : validation::cases()) {
    if (c.name != name) continue;
    const auto result = c.run(kQuick);
    for (const auto& n : result.notes) std::printf("  %s\n", n.c_str());
    ASSERT_FALSE(result.rows.empty());
    for (const auto& r : result.rows) {
      std::printf("  %-28s %10.5f  reference %8.4f  error %8.5f  tolerance %6.3f\n",
                  r.quantity.c_str(), r.value, r.reference, r.error, r.tolerance);
      EXPECT_TRUE(r.pass) << r.quantity;
    }
    return;
  }
  FAIL() << "no validation case " << name;
}
}  // namespace

TEST(FvValidation, ManufacturedSolutionSecondOrder) {
  run("mms");
}
TEST(FvValidation, TaylorGreenBdf2SecondOrder) {
  run("taylor-green");
}
TEST(FvValidation, CavityRe100Ghia) {
  run("cavity-re100");
}
TEST(FvValidation, CavityRe1000Ghia) {
  run("cavity-re1000");
}
