// SPDX-License-Identifier: GPL-3.0-or-later
// Manufactured solution on stretched, skewed hexahedra: the observed order of accuracy of
// convection (van Leer, deferred correction) plus diffusion (non-orthogonal correction).
#include <cmath>

#include <gtest/gtest.h>

#include "auvloop/engine/validation.hpp"

using namespace auvloop::engine;

TEST(FvMms, SecondOrderOnSkewedStretchedHexahedra) {
  // The case's rows state their own tolerances (engine/src/validation/cases.cpp).
  const auto* mms = &validation::cases().front();
  ASSERT_EQ(mms->name, "mms");
  const auto result = mms->run(true);
  for (const auto& n : result.notes) std::printf("%s\n", n.c_str());
  for (const auto& r : result.rows) {
    std::printf("%s: %.3f (expected %.1f)\n", r.quantity.c_str(), r.value, r.reference);
    EXPECT_TRUE(r.pass) << r.quantity;
  }
}
