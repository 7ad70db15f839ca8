// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant's closed-loop validation cases (issue 18 item 8), shown by `auvloop validate`
// beside the engine's (engine/validation.hpp): a whole manoeuvre run by run_case and read by
// manoeuvre_metrics (they need the indices, so they live here, after the engine):
//   remus-yaw-trial       Prestero's trial, rudder to 4 deg at 10 deg/s from 1.54 m/s: the
//                         heading change 5 s after the ramp starts (sea trial 51.9 deg);
//   remus-pitch-trial     stern planes to 4 deg at 10 deg/s: the pitch change 2 s after the
//                         ramp starts (sea trial 17.2 deg);
//   remus-turning-circle  1.03 m/s, the rudder held at 13.6 deg: the steady radius (4 m).
// Full: on medium, within 10 % (the trials) and 15 % (the circle) of the sea, coarse beside it.
// Quick (CI, coarse, 0.2 s straight, the first second): a check of the response's sign and
// size, not a validation: the CFD plant's change after 1 s against the derivative plant's on
// the same case, their ratio within a factor of two either way (|log2| <= 1).
#pragma once

#include <vector>

#include "auvloop/engine/validation.hpp"

namespace auvloop::results {

std::vector<engine::validation::Case> trial_cases();

}  // namespace auvloop::results
