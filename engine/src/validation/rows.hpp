// SPDX-License-Identifier: GPL-3.0-or-later
// Rows of a validation result shared by the cases' files (cases.cpp, remus_cases.cpp), and the
// cases defined outside cases.cpp.
#pragma once

#include <cmath>
#include <string>
#include <utility>

#include "auvloop/engine/validation.hpp"

namespace auvloop::engine::validation {

// A measure that must stay at or below `limit` (a conservation error at the solver's tolerance).
inline Row bound_row(std::string quantity, double value, double limit) {
  Row r{std::move(quantity), value, 0.0, value, limit, false};
  r.pass = value <= limit;  // NaN fails
  return r;
}

// |value / reference - 1| within tolerance.
inline Row relative_to(std::string quantity, double value, double reference, double tolerance) {
  Row row{std::move(quantity), value, reference, std::abs(value / reference - 1), tolerance, false};
  row.pass = row.error <= tolerance;  // NaN fails
  return row;
}

Result run_remus_resistance(bool quick);       // remus_cases.cpp
Result run_remus_self_propulsion(bool quick);  // remus_cases.cpp

}  // namespace auvloop::engine::validation
